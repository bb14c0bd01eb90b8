#include "rigid_sliding.h"

// STL
#include <algorithm>
#include <cmath>

// Package
#include "sphere_contact_estimator/core/numerics/quadrature_rules.h"

namespace sphere_contact_estimator::path
{
namespace
{
constexpr double kGaussRadius = 6.0;  // graded rules split where the pole's ellipse is closer than this
constexpr double kClosedFormRadius = 60.0;  // straight sliding pieces in closed form while the pole's is closer

// The parameter of the Bernstein ellipse of [lo, hi] through `star`: its semi-axis sum, from the semi-major axis
// A = (|t - 1| + |t + 1|) / 2 of the confocal ellipse through t (star mapped onto [-1, 1]).
double bernsteinRadius(double lo, double hi, cd star)
{
  const cd t = (2.0 * star - (lo + hi)) / (hi - lo);
  const double A = 0.5 * (std::sqrt(std::norm(t - 1.0)) + std::sqrt(std::norm(t + 1.0)));
  return A + std::sqrt(std::max(0.0, A * A - 1.0));
}

class RigidSlider
{
public:
  RigidSlider(PathContext& ctx, double tolerance)
    : ctx_(ctx), f_(ctx.field), p_(ctx.path), out_(ctx.out), tolerance_(tolerance)
  {
  }

  void slide(double a, double b)
  {
    ctx_.addPiece(a, b, false, cd(0.0));
    if (!(b > a))
      return;
    out_.sliding += b - a;
    out_.utilisation2 = 1.0;
    integrate(a, b);
  }

  void integrate(double a, double b)
  {
    if (!(b > a))
      return;
    // the integrand's nearest complex singularity: where w(z(tau)) = 0 (its modulus has a branch point)
    cd star(1e300, 1e300);
    if (f_.phi != 0.0)
    {
      const cd zp = f_.pole();
      if (f_.omega == 0.0)
        star = p_.entry - zp;  // z_e - tau = z_p
      else
      {
        const cd centre(0.0, f_.tiltingCentre());
        // centre + e^{i omega tau}(z_e - centre) = z_p: the complex log, without the hypot std::log takes
        const cd ratio = (zp - centre) / (p_.entry - centre);
        star = cd(std::atan2(ratio.imag(), ratio.real()), -0.5 * std::log(std::norm(ratio))) / f_.omega;
      }
    }
    const bool sqrt_edges = f_.pressure.infiniteSlopeAtRim();
    if (f_.omega == 0.0 && !sqrt_edges)
    {
      // straight, f a polynomial in x: the closed form while the pole is near enough that its differences keep
      // their digits (they lose about rho^4 eps), a short Gauss rule beyond (a degree-4 polynomial times a
      // function analytic out to rho: degree 4 exactly plus rho^-2 per further node)
      const double rho = f_.phi != 0.0 ? bernsteinRadius(a, b, star) : INFINITY;
      if (rho < kClosedFormRadius && slideStraight(a, b, rho))
        return;
      if (rho >= kClosedFormRadius)
      {
        const double half = 0.5 * (b - a), C = 64.0 / 15.0 * 8.0 * half;
        const int m = std::clamp(
            2 + static_cast<int>(std::ceil(std::log(std::max(C / tolerance_, 1.0)) / (2.0 * std::log(rho)))), 3,
            numerics::GaussLegendre::kMaxPoints);
        gauss(a, b, m, [&](double tau, cd& q, double& mm) { sliding(tau, q, mm); });
        out_.error += C * std::pow(rho, -2.0 * (m - 2));
        return;
      }
    }
    if (!sqrt_edges)
    {
      graded(a, b, star, [&](double tau, cd& q, double& m) { sliding(tau, q, m); });
      return;
    }
    // f = sqrt(1 - r^2) has square-root branch points at both edges, f ~ sqrt(tau (L - tau)) (times an
    // analytic factor on a circle): tau = L (1 - cos v) / 2 makes it analytic in v
    const double L = p_.length, h = 0.5 * L;
    const auto angle = [&](double tau) { return std::acos(std::clamp(1.0 - tau / h, -1.0, 1.0)); };
    const cd v_star = std::acos(cd(1.0, 0.0) - star / h);
    graded(
        angle(a), angle(b), v_star,
        [&](double v, cd& q, double& m) {
          sliding(h * (1.0 - std::cos(v)), q, m);
          const double jac = h * std::sin(v);
          q *= jac;
          m *= jac;
        },
        h);
  }

private:
  // The sliding stress f w / |w| and its moment at travel tau.
  void sliding(double tau, cd& q, double& m) const
  {
    const cd z = p_.position(tau);
    const cd w = f_.drive(z);
    const double n = std::sqrt(std::norm(w));
    // only the square-root bound needs 1 - r^2 without cancellation at the edges
    const double t = f_.pressure.infiniteSlopeAtRim() ? p_.edgeDistance(tau) : 1.0 - std::norm(z);
    q = n > 0.0 ? f_.pressure.shape(t) * w / n : cd(0.0);
    m = cross(z, q);
  }

  // Sliding on a straight path, parabolic or uniform pressure, in closed form: with t = w_y = sigma_y + phi x
  // along the path, f is a polynomial in t and the stress f (A, t) / sqrt(A^2 + t^2), A = w_x, integrates by
  // J_n = int t^n / sqrt(A^2 + t^2) dt = (t^(n-1) R - (n-1) A^2 J_(n-2)) / n. Used where the pole is near the
  // piece (its Gauss rule would be long); there the differences J_n(t_b) - J_n(t_a) lose little.
  bool slideStraight(double a, double b, double rho)
  {
    const double eta = p_.entry.imag(), phi = f_.phi;
    const double A = f_.sigma.real() - phi * eta;
    if (std::abs(A) < 1e-300)
      return false;
    const double t_a = f_.sigma.imag() + phi * (p_.entry.real() - a), t_b = f_.sigma.imag() + phi * (p_.entry.real() - b);
    const double alpha = 1.0 / phi, gamma = -f_.sigma.imag() / phi;  // x = alpha t + gamma
    double c0 = 1.0, c1 = 0.0, c2 = 0.0;                             // f = c0 + c1 t + c2 t^2
    if (f_.pressure.squaredExponent() == 2)
    {
      c0 = 1.0 - eta * eta - gamma * gamma;
      c1 = -2.0 * alpha * gamma;
      c2 = -alpha * alpha;
    }
    double D[5];
    {
      const double A2 = A * A, absA = std::abs(A);
      double Ja[5], Jb[5];
      for (int side = 0; side < 2; ++side)
      {
        const double t = side == 0 ? t_a : t_b;
        double* J = side == 0 ? Ja : Jb;
        const double R = std::sqrt(A2 + t * t);
        J[0] = std::asinh(t / absA);
        J[1] = R;
        J[2] = (t * R - A2 * J[0]) / 2.0;
        J[3] = (t * t * R - 2.0 * A2 * J[1]) / 3.0;
        J[4] = (t * t * t * R - 3.0 * A2 * J[2]) / 4.0;
      }
      for (int n = 0; n < 5; ++n)
        D[n] = Jb[n] - Ja[n];
    }
    const double k = -alpha;  // d tau = -dx = -dt / phi
    const double fx = k * A * (c0 * D[0] + c1 * D[1] + c2 * D[2]);
    const double fy = k * (c0 * D[1] + c1 * D[2] + c2 * D[3]);
    // x q_y - y q_x = f (x t - eta A) / R with x t - eta A = -eta A + gamma t + alpha t^2
    const double e0 = -eta * A * c0, e1 = c0 * gamma - eta * A * c1, e2 = c0 * alpha + c1 * gamma - eta * A * c2,
                 e3 = c1 * alpha + c2 * gamma, e4 = c2 * alpha;
    const double m = k * (e0 * D[0] + e1 * D[1] + e2 * D[2] + e3 * D[3] + e4 * D[4]);
    if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(m)))
      return false;
    out_.force += cd(fx, fy);
    out_.moment += m;
    out_.error += 1e-15 * (1.0 + std::pow(rho, 4)) * (b - a);  // rounding: the differences lose about rho^4 eps
    return true;
  }

  // An m-point Gauss-Legendre rule on [a, b].
  template <class F>
  void gauss(double a, double b, int m, const F& g)
  {
    const numerics::GaussLegendre& rule = numerics::gaussLegendre(m);
    out_.work += 16 * m;  // a node: a sincos or a square root, a handful of products
    const double half = 0.5 * (b - a), mid = 0.5 * (b + a);
    cd sum = 0.0;
    double M_sum = 0.0;
    for (int i = 0; i < m; ++i)
    {
      cd q;
      double mm;
      g(mid + half * rule.x[i], q, mm);
      sum += rule.w[i] * q;
      M_sum += rule.w[i] * mm;
    }
    out_.force += half * sum;
    out_.moment += half * M_sum;
  }

  // Gauss-Legendre on [a, b] for an integrand analytic except near `star` (variable: travel, or the angle v
  // of the Hertzian map, whose Jacobian is at most `jacobian`): the rule on an interval is sized by the
  // classical bound for an integrand analytic in the Bernstein ellipse E_r, (64/15) M r^(-2m) / (r^2 - 1) times
  // the half-width, with r the geometric mean of 1 and the ellipse through the singularity, capped at 3 so
  // that the integrand's polynomial factors stay bounded on it (M from |z| <= 1 + r half-width). Intervals the
  // singularity is close to are split at its projection and graded geometrically.
  template <class F>
  void graded(double a, double b, cd star, const F& g, double jacobian = 1.0)
  {
    const double eps = tolerance_;
    const auto rho = [&](double lo, double hi) { return bernsteinRadius(lo, hi, star); };
    const auto apply = [&](double lo, double hi, double radius) {
      const double half = 0.5 * (hi - lo);
      const double r = std::clamp(std::sqrt(radius), 1.5, 3.0);
      const double R = 1.0 + r * half * jacobian, M = 2.0 * R * (1.0 + R * R) * jacobian;
      const double C = 64.0 / 15.0 * M * half / (r * r - 1.0);
      const double log_r = std::log(r);
      int m = static_cast<int>(std::ceil(std::log(std::max(C / eps, 1.0)) / (2.0 * log_r)));
      m = std::clamp(m, 2, numerics::GaussLegendre::kMaxPoints);
      gauss(lo, hi, m, g);
      out_.error += C * std::exp(-2.0 * m * log_r);
    };
    const double whole = rho(a, b);
    if (whole >= kGaussRadius)
    {
      apply(a, b, whole);
      return;
    }
    // split at the singularity's projection and grade outwards: widths delta, 2 delta, 4 delta, ...
    const double c = std::clamp(star.real(), a, b);
    const double delta = std::max(std::abs(star.imag()), 1e-12 * (b - a));
    for (int side = -1; side <= 1; side += 2)
    {
      const double end = side < 0 ? a : b;
      double from = c, width = delta;
      for (int k = 0; k < 60 && (end - from) * side > 0.0; ++k, width *= 2.0)
      {
        double to = from + side * width;
        if ((end - to) * side < 2.0 * width)  // the rest is short: take it in one
          to = end;
        const double lo = std::min(from, to), hi = std::max(from, to);
        apply(lo, hi, rho(lo, hi));
        from = to;
      }
    }
  }

  PathContext& ctx_;
  const BristleField& f_;
  const BristlePath& p_;
  PathIntegrals& out_;
  double tolerance_;
};
}  // namespace

void slideRigid(PathContext& ctx, double a, double b)
{
  RigidSlider(ctx, ctx.tolerance).slide(a, b);
}

void integrateRigid(PathContext& ctx, double a, double b, double tolerance)
{
  RigidSlider(ctx, tolerance).integrate(a, b);
}

cd rigidSlidingDeflection(const BristleField& field, const BristlePath& path, double tau)
{
  const cd w = field.drive(path.position(tau));
  const double n = std::sqrt(std::norm(w));
  return n > 0.0 ? field.bound(1.0 - path.edgeDistance(tau)) * w / n : cd(0.0);
}

}  // namespace sphere_contact_estimator::path
