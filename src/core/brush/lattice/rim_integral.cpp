#include "rim_integral.h"

// STL
#include <algorithm>
#include <cmath>

namespace sphere_contact_estimator::lattice
{
bool RimIntegral::crossings(double t0, double t1, double t2, double& s_a, double& s_b)
{
  if (!(t2 < 0.0) || !(t0 > 0.0))
    return false;
  const double q = -0.5 * (t1 + std::copysign(std::sqrt(t1 * t1 - 4.0 * t2 * t0), t1));
  s_a = std::min(q / t2, t0 / q);
  s_b = std::max(q / t2, t0 / q);
  return true;
}

RimIntegral::RimIntegral(int m, double t0, double t1, double t2, double s_a, double s_b, double d)
  : m_(m), t0_(t0), t1_(t1), t2_(t2), s_a_(s_a), s_b_(s_b), d_(d), h_(0.5 * (s_b - s_a)), mid_(0.5 * (s_a + s_b))
{
  if (m_ == 2)
  {
    log_a_ = std::log1p(d / -s_a);
    log_b_ = std::log1p(-d / s_b);
    return;
  }
  // phi from the nearer root (asin of the square root of the distance to it over 2 h: no cancellation there)
  dphi_ = -s_a < s_b ? 2.0 * (std::asin(std::sqrt((d - s_a) / (2.0 * h_))) - std::asin(std::sqrt(-s_a / (2.0 * h_))))
                     : 2.0 * (std::asin(std::sqrt(s_b / (2.0 * h_))) - std::asin(std::sqrt((s_b - d) / (2.0 * h_))));
  sin0_ = -mid_ / h_;
  cos0_ = std::sqrt(-s_a * s_b) / h_;
  sin1_ = (d - mid_) / h_;
  cos1_ = std::sqrt((d - s_a) * (s_b - d)) / h_;
}

double RimIntegral::operator()(double alpha0, double alpha1, double alpha2) const
{
  if (m_ == 2)
  {
    // alpha2 s^2 = alpha2 / t2 (t - t0 - t1 s): the remainder's partial fractions over the roots
    const double beta0 = alpha0 - alpha2 * t0_ / t2_, beta1 = alpha1 - alpha2 * t1_ / t2_;
    const double A = (beta0 + beta1 * s_a_) / (t2_ * (s_a_ - s_b_)), B = (beta0 + beta1 * s_b_) / (t2_ * (s_b_ - s_a_));
    return alpha2 * d_ / t2_ + A * log_a_ + B * log_b_;
  }
  // the numerator about the roots' middle, in powers of h sin(phi)
  const double g0 = alpha0 + mid_ * (alpha1 + alpha2 * mid_), g1 = h_ * (alpha1 + 2.0 * alpha2 * mid_),
               g2 = alpha2 * h_ * h_;
  return (g0 * dphi_ + g1 * (cos0_ - cos1_) + g2 * 0.5 * (dphi_ - (sin1_ * cos1_ - sin0_ * cos0_))) / std::sqrt(-t2_);
}

double RimIntegral::stretchedLength() const
{
  if (m_ == 2)
    return (log_a_ - log_b_) / (-t2_ * (s_b_ - s_a_));  // ln((1 + s / -s_a) / (1 - s / s_b)) / beta
  return dphi_ / std::sqrt(-t2_);  // phi / sqrt|t2|
}

void RimIntegral::stretchedNodes(double c_1, double s[3]) const
{
  if (m_ == 2)
  {
    // g = e^{beta u} = (1 + s / A) / (1 - s / B), A = -s_a, B = s_b: s = (g - 1) A B / (B + g A); g at U is the ratio
    // of the logarithms' arguments, at U / 2 its square root, at (1 - c_1) U it over g at c_1 U
    const double A = -s_a_, B = s_b_, g_end = (1.0 + d_ / A) / (1.0 - d_ / B), g_1 = std::exp(c_1 * (log_a_ - log_b_));
    const double g[3] = { g_1, std::sqrt(g_end), g_end / g_1 };
    for (int i = 0; i < 3; ++i)
      s[i] = (g[i] - 1.0) * A * B / (B + g[i] * A);
    return;
  }
  // s = h (sin(phi0 + theta) - sin(phi0)) = h (cos0 sin(theta) - sin0 (1 - cos(theta))), theta = c dphi
  const double c[3] = { c_1, 0.5, 1.0 - c_1 };
  for (int i = 0; i < 3; ++i)
  {
    const double theta = c[i] * dphi_, sn = std::sin(theta), cs = std::cos(theta);
    s[i] = h_ * (cos0_ * sn - sin0_ * sn * sn / (1.0 + cs));
  }
}

}  // namespace sphere_contact_estimator::lattice
