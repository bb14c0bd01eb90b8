#include "brush_brute_force.h"

// STL
#include <algorithm>
#include <cmath>
#include <complex>

// Boost
#include <boost/math/constants/constants.hpp>

namespace sphere_contact_estimator::test
{
namespace
{
using boost::math::double_constants::pi;
using cd = std::complex<double>;  // plane vectors as x + i y; A_phi v = i phi v
constexpr cd kI{ 0.0, 1.0 };

constexpr double kEdgeClamp = 1e-13;  // evaluate q_z at r^2 <= a^2 (1 - kEdgeClamp): no jump to 0 on the rim
constexpr int kBisections = 40;
constexpr int kMaxEventsPerStep = 8;
constexpr double kMaxSubstepAngle = 0.1;  // |phi_psi| H, |phi_gamma| H per Gauss substep: error ~1e-15

/// Travel over tau from s0 along a path: root z(s0 + tau) = R z(s0) + D; adhering bristle u(s0 + tau) = P u(s0) + A + B z(s0).
struct Affine
{
  cd P{ 1.0 }, A{ 0.0 }, B{ 0.0 }, R{ 1.0 }, D{ 0.0 };
};

/// What one path contributes (per unit of the across-path measure).
struct PathSums
{
  cd int_u{ 0.0 };        // integral of u ds
  double int_m = 0.0;     // integral of (x u_y - y u_x) ds
  double slide_len = 0.0; // travel spent sliding
  double max_util = 0.0;
};

class Marcher
{
public:
  Marcher(const BrushParameters& p, cd sigma, double phi, double phi_gamma, double phi_psi)
    : p_(p), sigma_(sigma), phi_(phi), phg_(phi_gamma), phs_(phi_psi), b_max_(p.mu * p.qz(0.0) / p.k)
  {
  }

  /// Root motion dx/ds = A_gamma (x - C), C = i/phi_gamma (eq. 39b); phi_gamma = 0: dx/ds = (-1, 0) (eq. 18a).
  /// z(s0 + t) = e^{-i phi_gamma t} z(s0) + D(t), D(t) = (i/phi_gamma)(1 - e^{-i phi_gamma t}), written without cancellation.
  cd rot(double t) const { return std::polar(1.0, -phg_ * t); }
  cd shift(double t) const
  {
    if (phg_ == 0.0)
      return -t;
    const double th = phg_ * t, sh = std::sin(0.5 * th);
    return cd(-std::sin(th), 2.0 * sh * sh) / phg_;
  }
  cd velocity(cd z) const { return -1.0 - kI * phg_ * z; }

  /// Rigid sliding field w = sigma + A_phi x, the drive of eqs. 11/32 and the sliding direction (Sect. 6).
  cd drive(cd z) const { return sigma_ + kI * phi_ * z; }

  /// Bound b = mu q_z / k on |u| (eq. 4) and its rate along the path.
  double bound(cd z) const { return p_.mu / p_.k * p_.qz(std::min(std::norm(z), r2Max())); }
  double boundRate(cd z) const
  {
    const double a2 = p_.a * p_.a, t = std::max(1.0 - std::norm(z) / a2, kEdgeClamp);
    double dq_dr2 = 0.0;
    switch (p_.pressure)
    {
      case PressureDistribution::Parabolic:
        dq_dr2 = -2.0 * p_.F_z / (pi * a2 * a2);
        break;
      case PressureDistribution::Hertzian:
        dq_dr2 = -0.75 * p_.F_z / (pi * a2 * a2 * std::sqrt(t));
        break;
      case PressureDistribution::Uniform:
        break;
    }
    return p_.mu / p_.k * dq_dr2 * 2.0 * std::real(std::conj(z) * velocity(z));
  }

  /// Capped (sliding) deflection b w/|w| (Sect. 6); w = 0 keeps the direction of u_prev.
  cd capped(cd z, cd u_prev) const
  {
    const cd w = drive(z);
    const double b = bound(z), nw = std::abs(w), nu = std::abs(u_prev);
    return nw > 0.0 ? b * w / nw : (nu > 0.0 ? b * u_prev / nu : cd(0.0));
  }

  /// Exact-rotation propagator of du/ds = sigma + A_phi x + A_phi_psi u (eqs. 11, 32, 39c):
  /// u(s0+H) = e^{i phi_psi H} u(s0) + integral_0^H e^{i phi_psi (H - t)} w(x(s0 + t)) dt, the integral by 3-point
  /// Gauss-Legendre on substeps short enough for 1e-14 (exact for straight paths without turn spin).
  Affine propagator(double tau) const
  {
    const int m = std::max(1, static_cast<int>(std::ceil(tau * std::max(std::abs(phs_), std::abs(phg_)) / kMaxSubstepAngle)));
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

  /// March one path from the leading-edge point z_in over travel s_total in n equal steps.
  PathSums march(cd z_in, double s_total, int n) const
  {
    PathSums out;
    const double h = s_total / n;
    const Affine Th = propagator(h), Tm = propagator(0.5 * h);

    // Eq. 8: u = 0 on the leading edge. Where the bound starts at 0 (parabolic rim) and grows slower than |w|,
    // the bristle slides from the start.
    cd u = 0.0;
    bool slide = bound(z_in) <= 1e-9 * b_max_ && boundRate(z_in) - std::abs(drive(z_in)) <= 0.0;

    // State value at z reached over T from (uc, zc); event function (> 0: the mode must change).
    auto value = [&](bool sl, const Affine& T, cd uc, cd zc, cd z) { return sl ? capped(z, uc) : T.P * uc + T.A + T.B * zc; };
    auto event = [&](bool sl, cd uu, cd z) {
      return sl ? boundRate(z) - std::abs(drive(z))  // re-adhesion: |u| - b decreases under adhesion
                : std::abs(uu) - bound(z);           // adhesion reaches the bound
    };
    auto utilisation = [&](bool sl, cd uu, cd z) {
      if (sl)
        return;
      const double b = bound(z);
      if (b > 1e-9 * b_max_)
        out.max_util = std::max(out.max_util, std::min(1.0, std::abs(uu) / b));
    };
    // Simpson on one smooth piece of length L.
    auto piece = [&](bool sl, double L, cd ua, cd um, cd ub, cd za, cd zm, cd zb) {
      auto cross = [](cd z, cd v) { return std::imag(std::conj(z) * v); };
      out.int_u += L / 6.0 * (ua + 4.0 * um + ub);
      out.int_m += L / 6.0 * (cross(za, ua) + 4.0 * cross(zm, um) + cross(zb, ub));
      if (sl && L > 0.0)
      {
        out.slide_len += L;
        out.max_util = 1.0;
      }
      utilisation(sl, um, zm);
      utilisation(sl, ub, zb);
    };

    for (int k = 0; k < n; ++k)
    {
      const double s0 = k * h, s1 = (k + 1) * h;
      double cur = s0;
      cd zc = rot(s0) * z_in + shift(s0);
      bool fast = true;
      int events = 0;
      while (s1 - cur > 0.0)
      {
        const double L = s1 - cur;
        const Affine Tm2 = fast ? Tm : propagator(0.5 * L), Te = fast ? Th : propagator(L);
        const cd zm = Tm2.R * zc + Tm2.D, ze = Te.R * zc + Te.D;
        const cd um = value(slide, Tm2, u, zc, zm), ue = value(slide, Te, u, zc, ze);
        double lo = -1.0, hi = 0.0;
        if (events < kMaxEventsPerStep)
        {
          if (event(slide, um, zm) > 0.0)
            lo = 0.0, hi = 0.5 * L;
          else if (event(slide, ue, ze) > 0.0)
            lo = 0.5 * L, hi = L;
        }
        if (lo < 0.0)  // no event: the whole rest of the step in the current mode
        {
          piece(slide, L, u, um, ue, zc, zm, ze);
          u = ue;
          break;
        }
        for (int it = 0; it < kBisections; ++it)  // first point where the event function turns positive
        {
          const double mid = 0.5 * (lo + hi);
          const Affine T = propagator(mid);
          const cd z = T.R * zc + T.D;
          (event(slide, value(slide, T, u, zc, z), z) > 0.0 ? hi : lo) = mid;
        }
        const Affine T1 = propagator(0.5 * hi), T2 = propagator(hi);
        const cd z1 = T1.R * zc + T1.D, z2 = T2.R * zc + T2.D;
        const cd u2 = value(slide, T2, u, zc, z2);
        piece(slide, hi, u, value(slide, T1, u, zc, z1), u2, zc, z1, z2);
        // Switch: slide with b w/|w|, or re-adhere from the capped deflection: the same value either way.
        u = capped(z2, u2);
        zc = z2;
        slide = !slide;
        cur += hi;
        fast = false;
        ++events;
      }
    }
    return out;
  }

private:
  double r2Max() const { return p_.a * p_.a * (1.0 - kEdgeClamp); }

  const BrushParameters& p_;
  cd sigma_;
  double phi_, phg_, phs_, b_max_;
};

}  // namespace

BrushForces bruteForceSteady(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi, double phi_gamma,
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
  const Marcher marcher(p, cd(sigma.x(), sigma.y()), phi, phg, phs);
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

}  // namespace sphere_contact_estimator::test
