#include "brush_coulomb_reference.h"

// STL
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

// Boost
#include <boost/math/constants/constants.hpp>

namespace sphere_contact_estimator::test
{
namespace
{
using boost::math::double_constants::pi;
using cd = std::complex<double>;  // plane vectors as x + i y; A_phi v = i phi v
constexpr cd kI{ 0.0, 1.0 };

constexpr double kEdgeClamp = 1e-13;      // q_z at r^2 <= a^2 (1 - kEdgeClamp): a rounded rim point keeps its bound
constexpr double kMaxSubstepAngle = 0.1;  // |phi_psi| H, |phi_gamma| H per Gauss substep: error ~1e-15

/// Travel over tau from s0 along a path: root z(s0 + tau) = R z(s0) + D; adhering bristle
/// u(s0 + tau) = P u(s0) + A + B z(s0).
struct Affine
{
  cd P{ 1.0 }, A{ 0.0 }, B{ 0.0 }, R{ 1.0 }, D{ 0.0 };
};

/// What one path contributes (per unit of the across-path measure).
struct PathSums
{
  cd int_u{ 0.0 };         // integral of u ds
  double int_m = 0.0;      // integral of (x u_y - y u_x) ds
  double slide_len = 0.0;  // travel on the bound (trapezoid in tau on the step ends)
  double max_util = 0.0;
};

class CoulombMarcher
{
public:
  CoulombMarcher(const BrushParameters& p, cd sigma, double phi, double phi_gamma, double phi_psi)
    : p_(p), sigma_(sigma), phi_(phi), phg_(phi_gamma), phs_(phi_psi), b_max_(p.mu * p.qz(0.0) / p.k)
  {
  }

  /// Root motion dx/ds = A_gamma (x - C), C = i/phi_gamma (eq. 39b); phi_gamma = 0: dx/ds = (-1, 0) (eq. 18a).
  /// z(s0 + t) = e^{-i phi_gamma t} z(s0) + D(t), D(t) = (i/phi_gamma)(1 - e^{-i phi_gamma t}) without cancellation.
  cd rot(double t) const { return std::polar(1.0, -phg_ * t); }
  cd shift(double t) const
  {
    if (phg_ == 0.0)
      return -t;
    const double th = phg_ * t, sh = std::sin(0.5 * th);
    return cd(-std::sin(th), 2.0 * sh * sh) / phg_;
  }

  /// Bound b = mu q_z / k on |u| [m] (eq. 4).
  double bound(cd z) const { return p_.mu / p_.k * p_.qz(std::min(std::norm(z), r2Max())); }

  /// Adhesion over h on a straight path without turn coupling (eq. 17c): u + h sigma + i phi (h z - h^2 / 2).
  Affine straight(double h) const
  {
    Affine T;
    T.A = h * sigma_ - 0.5 * kI * phi_ * h * h;
    T.B = kI * phi_ * h;
    T.D = -h;
    return T;
  }

  /// Exact-rotation propagator of adhesion, du/ds = sigma + A_phi x + A_phi_psi u (eqs. 11, 32, 39c):
  /// u(s0+H) = e^{i phi_psi H} u(s0) + integral_0^H e^{i phi_psi (H - t)} w(x(s0 + t)) dt, the integral by 3-point
  /// Gauss-Legendre on substeps short enough for 1e-14 (exact for straight paths without turn spin).
  Affine propagator(double tau) const
  {
    const int m =
        std::max(1, static_cast<int>(std::ceil(tau * std::max(std::abs(phs_), std::abs(phg_)) / kMaxSubstepAngle)));
    const double H = tau / m;
    static const double gx[3] = { 0.5 - std::sqrt(0.15), 0.5, 0.5 + std::sqrt(0.15) };
    static const double gw[3] = { 5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0 };
    const cd P1 = std::polar(1.0, phs_ * H), R1 = rot(H), D1 = shift(H);
    cd a1 = 0.0, b1 = 0.0;
    for (int j = 0; j < 3; ++j)
    {
      const cd e = std::polar(gw[j] * H, phs_ * H * (1.0 - gx[j]));
      a1 += e * (sigma_ + kI * phi_ * shift(H * gx[j]));
      b1 += e * kI * phi_ * rot(H * gx[j]);
    }
    Affine T;
    for (int i = 0; i < m; ++i)
    {
      T.A = P1 * T.A + a1 + b1 * T.D;
      T.B = P1 * T.B + b1 * T.R;
      T.P = P1 * T.P;
      T.D = R1 * T.D + D1;
      T.R = R1 * T.R;
    }
    T.R = rot(tau);
    T.D = shift(tau);
    return T;
  }

  /// March one path from the leading-edge point z_in over travel s_total: n steps of return mapping, equal in
  /// tau = arccos(1 - 2 s / s_total) (steps shrink like tau near both rims, so a bound with a square root there,
  /// the Hertzian one, and thin sliding bands along the trailing rim are resolved: the along-path error stays first
  /// order with a smooth coefficient). Forces by the trapezoid rule in tau, whose integrand stays smooth there.
  PathSums march(cd z_in, double s_total, int n)
  {
    PathSums out;
    const double dtau = pi / n;
    const bool simple = phg_ == 0.0 && phs_ == 0.0;  // straight, no turn coupling: propagator in closed form
    auto travel = [&](int k) {                          // s_k = s_total sin^2(tau_k / 2)
      if (k >= n)
        return s_total;
      const double sh = std::sin(0.5 * k * dtau);
      return s_total * sh * sh;
    };
    // Steps are symmetric about the middle: propagators for the first half serve the second.
    std::vector<Affine>& T = cache_;
    T.resize(n / 2 + 1);
    for (int k = 1; k <= n / 2 + n % 2; ++k)
    {
      const double h = s_total * std::sin((k - 0.5) * dtau) * std::sin(0.5 * dtau);  // s_k - s_{k-1}
      T[k - 1] = simple ? straight(h) : propagator(h);
    }
    auto cross = [](cd z, cd v) { return std::imag(std::conj(z) * v); };
    cd u = 0.0, z = z_in;  // eq. 8: undeformed on the leading edge
    cd sum_u = 0.0;
    double sum_m = 0.0, slide = 0.0;
    for (int k = 1; k <= n; ++k)
    {
      const Affine& Tk = T[k <= n / 2 + n % 2 ? k - 1 : n - k];
      const double s = travel(k);
      const cd z_next = phg_ == 0.0 ? z_in - s : rot(s) * z_in + shift(s);  // exact root: the last lands on the rim
      const cd trial = Tk.P * u + Tk.A + Tk.B * z;
      const double b = bound(z_next), nt = std::abs(trial);
      const double weight = std::sin(k * dtau);  // ds/dtau / (s_total / 2); 0 on the rims
      if (nt > b)  // backward Euler of eq. 4b: back onto the bound along the trial
      {
        u = b / nt * trial;
        slide += weight;
        out.max_util = 1.0;
      }
      else
      {
        u = trial;
        if (b > 1e-9 * b_max_)
          out.max_util = std::max(out.max_util, nt / b);
      }
      z = z_next;
      sum_u += weight * u;
      sum_m += weight * cross(z, u);
    }
    const double scale = 0.5 * s_total * dtau;
    out.int_u = scale * sum_u;
    out.int_m = scale * sum_m;
    out.slide_len = scale * slide;
    return out;
  }

private:
  double r2Max() const { return p_.a * p_.a * (1.0 - kEdgeClamp); }

  const BrushParameters& p_;
  cd sigma_;
  double phi_, phg_, phs_, b_max_;
  std::vector<Affine> cache_;  // per-step propagators of the current path
};

double distance(const BrushForces& f, const BrushForces& g, const BrushParameters& p)
{
  const double scale = p.mu * p.F_z;
  if (!(scale > 0.0))
    return 0.0;
  return std::max({ std::abs(f.F_x - g.F_x), std::abs(f.F_y - g.F_y), std::abs(f.M_z - g.M_z) / p.a }) / scale;
}

/// 2 fine - coarse in the forces and the sliding share; utilisation from fine.
BrushForces richardson(const BrushForces& coarse, const BrushForces& fine)
{
  BrushForces r = fine;
  r.F_x = 2.0 * fine.F_x - coarse.F_x;
  r.F_y = 2.0 * fine.F_y - coarse.F_y;
  r.M_z = 2.0 * fine.M_z - coarse.M_z;
  r.sliding_fraction = std::clamp(2.0 * fine.sliding_fraction - coarse.sliding_fraction, 0.0, 1.0);
  return r;
}

}  // namespace

BrushForces marchCoulomb(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi, double phi_gamma,
                         double phi_psi, int n_paths, int n_steps)
{
  BrushForces out;
  const double phg = p.tilt ? phi_gamma : 0.0, phs = p.tilt ? phi_psi : 0.0;  // eq. 32 terms with tilt only
  const double a = p.a;
  if (phg != 0.0 && 1.0 / std::abs(phg) < a)  // Assumption 4.1 violated: no steady state (Fig. 2)
  {
    out.flags = brush_flags::kNoSteadyStateTilt;
    return out;
  }
  CoulombMarcher marcher(p, cd(sigma.x(), sigma.y()), phi, phg, phs);
  const double dth = pi / n_paths;
  cd F = 0.0;
  double Mz = 0.0, slide_area = 0.0, max_util = 0.0;
  for (int i = 0; i < n_paths; ++i)
  {
    const double th = -0.5 * pi + (i + 0.5) * dth, st = std::sin(th), ct = std::cos(th);
    cd z_in;
    double s_total, weight;  // weight: area per unit travel and unit theta-interval
    if (phg == 0.0)          // eq. 18a: line y = a sin(theta) from x_L = a cos(theta)
    {
      z_in = cd(a * ct, a * st);
      s_total = 2.0 * a * ct;
      weight = a * ct * dth;
    }
    else  // eq. 44a: circle |x - C| = rho about C = (0, c); it meets |x| = a at (+-x*, y*)
    {
      const double c = 1.0 / phg, ac = std::abs(c), rho = ac + a * st;
      const double ys = (a * a * ct * ct - 2.0 * ac * a * st) / (2.0 * c);  // (c^2 + a^2 - rho^2) / (2c)
      const double xs = std::sqrt(std::max(0.0, a * a - ys * ys));
      z_in = cd(xs, ys);
      s_total = 2.0 * std::atan2(xs, ac - (c > 0.0 ? ys : -ys)) / std::abs(phg);  // half-angle seen from C
      weight = a * ct * dth * std::abs(phg) * rho;
    }
    const PathSums r = marcher.march(z_in, s_total, n_steps);
    F += p.k * weight * r.int_u;
    Mz += p.k * weight * r.int_m;
    slide_area += weight * r.slide_len;
    max_util = std::max(max_util, r.max_util);
  }
  out.F_x = F.real();
  out.F_y = F.imag();
  out.M_z = Mz;
  out.sliding_fraction = slide_area / (pi * a * a);
  out.max_utilisation = max_util;
  return out;
}

CoulombReference coulombReference(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi,
                                  double phi_gamma, double phi_psi, int n_paths, int n_steps)
{
  CoulombReference out;
  const BrushForces f1 = marchCoulomb(p, sigma, phi, phi_gamma, phi_psi, n_paths, n_steps);
  if (f1.flags & brush_flags::kNoSteadyStateTilt)
  {
    out.forces = f1;
    return out;
  }
  const BrushForces f2 = marchCoulomb(p, sigma, phi, phi_gamma, phi_psi, n_paths, 2 * n_steps);
  const BrushForces f4 = marchCoulomb(p, sigma, phi, phi_gamma, phi_psi, n_paths, 4 * n_steps);
  const BrushForces half = marchCoulomb(p, sigma, phi, phi_gamma, phi_psi, std::max(1, n_paths / 2), n_steps);
  const BrushForces r1 = richardson(f1, f2), r2 = richardson(f2, f4);
  out.forces = r2;
  out.error = distance(r2, r1, p) + distance(f1, half, p);
  out.forces.error_estimate = out.error;
  return out;
}

}  // namespace sphere_contact_estimator::test
