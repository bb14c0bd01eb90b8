#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"

// STL
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

// Boost
#include <boost/math/tools/toms748_solve.hpp>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_contact.h"

namespace sphere_contact_estimator
{
namespace
{
// Point contact puts xi_+ = M g R / (m v^2). That only grows without bound in states already flagged
// (gamma -> 0 with m > 0, where v_c -> 0); the cap keeps h = xi_+^2 / 2R finite there.
constexpr double kMaxPointContactLever = 1.0e6;  // times R
}  // namespace

CylinderExact::CylinderExact(const CylinderParameters& parameters) : CylinderModel(parameters)
{
}

double CylinderExact::residual(double xi_plus, double v) const
{
  return contactPatch(p_, xi_plus, v).F_N + p_.m * v * v * xi_plus / p_.R - p_.weight();  // eq. 18
}

CylinderState CylinderExact::solve(double v) const
{
  return solve(v, nullptr);
}

CylinderState CylinderExact::solve(double v, Slopes* slopes) const
{
  checkSpeed(v);
  const double R = p_.R, k = p_.k, gamma = p_.gamma, m = p_.m;
  if (v == 0.0)
  {
    if (slopes)  // first-order terms of eqs. 23, 24, 27
      *slopes = Slopes{ 0.0, gamma / k, gamma / k };
    return staticState();
  }

  CylinderState st;
  st.v = v;
  // Front boundary where f(xi_+) = (m v^2 - gamma v xi_+)/R changes sign (self-consistency, after eq. 15).
  const double s_c = m == 0.0 ? 0.0 : (gamma > 0.0 ? m * v / gamma : std::numeric_limits<double>::infinity());
  const double G_c = std::isfinite(s_c) ? residual(s_c, v) : std::numeric_limits<double>::infinity();

  double s = 0.0;  // xi_+
  if (G_c >= 0.0 && (m * k <= gamma * gamma || v >= scales_.v_critical))
  {
    // Point contact (note 13): M g = F'_N = m v^2 xi_+ / R (eqs. 8, 9); F_R = F'_N xi_+ / R (eq. 17).
    s = std::min(p_.weight() * R / (m * v * v), kMaxPointContactLever * R);
    st.regime = CylinderRegime::PointContact;
    st.xi_plus = st.xi_minus = s;
    st.h = s * s / (2.0 * R);
    st.F_N = 0.0;
    st.F_R = m * v * v * s * s / (R * R);
    finish(st);
    if (slopes)
    {
      const double ds = s < kMaxPointContactLever * R ? -2.0 * s / v : 0.0;
      *slopes = Slopes{ s * ds / R, ds, ds };
    }
    return st;
  }

  if (G_c >= 0.0)
  {
    s = s_c;  // m k > gamma^2 and v < v_c: no consistent root; see the class comment
    st.regime = CylinderRegime::NoSteadyState;
  }
  else
  {
    // G is increasing in xi_+ on [s_c, inf): bracket the root within a factor of 2 around an estimate,
    // then TOMS 748. The estimate is the static xi0, or, when the rear boundary has moved far (gamma v/k
    // >> xi_+), the viscous limit of eq. 18, M g = gamma v xi_+^2 / (2R).
    const auto G = [this, v](double x) { return residual(x, v); };
    double guess = scales_.xi0;
    if (gamma > 0.0)
      guess = std::min(guess, std::sqrt(2.0 * R * p_.weight() / (gamma * v)));
    if (!(guess > s_c))
      guess = s_c > 0.0 ? 2.0 * s_c : scales_.xi0;
    double lo = s_c, G_lo = G_c, hi = guess, G_hi = G(hi);
    if (G_hi < 0.0)
    {
      do
      {
        lo = hi;
        G_lo = G_hi;
        hi *= 2.0;
        G_hi = G(hi);
      } while (G_hi < 0.0);
    }
    else
    {
      for (;;)
      {
        const double x = 0.5 * hi;
        if (x <= s_c)
          break;  // [s_c, hi] brackets it: G(s_c) < 0
        const double G_x = G(x);
        if (G_x < 0.0)
        {
          lo = x;
          G_lo = G_x;
          break;
        }
        hi = x;
        G_hi = G_x;
      }
    }
    std::uintmax_t iterations = max_iterations_;
    boost::math::tools::eps_tolerance<double> tolerance(kToleranceBits);
    const auto bracket = boost::math::tools::toms748_solve(G, lo, hi, G_lo, G_hi, tolerance, iterations);
    s = 0.5 * (bracket.first + bracket.second);
    if (!tolerance(bracket.first, bracket.second))  // the limit stopped it, not the tolerance
      st.flags |= cylinder_flags::kRootNotConverged;
    st.regime = CylinderRegime::ContactPatch;
  }

  const ContactPatch patch = contactPatch(p_, s, v);
  st.xi_plus = s;
  st.h = s * s / (2.0 * R);  // eq. 13
  st.xi_minus = patch.xi_minus;
  st.F_N = patch.F_N;
  st.F_R = patch.first_moment / R + m * v * v * s * s / (R * R);  // eq. 17, impact term m v^2 2h/R
  finish(st);

  if (slopes)
  {
    // Implicit differentiation of G(xi_+, v) = 0 (eq. 18), with f(xi_+) = (m v^2 - gamma v xi_+)/R,
    // f(xi_-) = 0, df/dxi_+ = -k xi_+/R and df/dv = (2 m v - gamma xi)/R.
    const double r = st.xi_minus, w = patch.width;
    const double f_s = (m * v * v - gamma * v * s) / R;
    const double s2r2 = w * (s + r);                  // xi_+^2 - xi_-^2
    const double s3r3 = w * (s * s + s * r + r * r);  // xi_+^3 - xi_-^3
    double ds = m / gamma;                            // NoSteadyState: xi_+ = m v / gamma
    if (st.regime == CylinderRegime::ContactPatch)
    {
      const double G_s = -f_s + k * s / R * w + m * v * v / R;
      const double G_v = gamma / (2.0 * R) * s2r2 - 2.0 * m * v / R * w + 2.0 * m * v * s / R;
      ds = -G_v / G_s;
    }
    const double root = p_.gamma * v / k - r;  // sqrt(xi_+^2 + lambda v^2)
    const double lambda = scales_.lambda;
    const double dr = root > 0.0 ? gamma / k - (s * ds + lambda * v) / root : ds;
    // first moment M1 = -integral xi f: dM1/dxi_+ and dM1/dv
    const double M1_s = -s * f_s + k * s / (2.0 * R) * s2r2;
    const double M1_v = gamma / (3.0 * R) * s3r3 - m * v / R * s2r2;
    const double dF_R = (M1_s * ds + M1_v) / R + 2.0 * m * v * s * (s + v * ds) / (R * R);
    *slopes = Slopes{ s * ds / R, dr, R * dF_R / p_.weight() };
  }
  return st;
}

}  // namespace sphere_contact_estimator
