#pragma once

// STL
#include <algorithm>
#include <cmath>

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator::lattice
{
/// Along a straight path through the patch, t = 1 - r^2 / a^2 is a concave quadratic in the time s from a step's
/// start, t0 + t1 s + t2 s^2 = t2 (s - s_a) (s - s_b), with s_a < 0 < s_b the rim crossings behind and ahead: there the
/// bound's shape f = t^(m/2) vanishes and 1 / f has its pole (m = 2) or branch point (m = 1), which a quadrature rule
/// through a few points does not see. This integrates (alpha0 + alpha1 s + alpha2 s^2) / f(t(s)) over the step [0, d]
/// in closed form: for f = t by partial fractions over the two roots (logarithms of the distances to them), for
/// f = sqrt(t) by s = mid + h sin(phi), t = |t2| h^2 cos^2(phi), phi measured from the nearer root, where it is exact.
class RimIntegral
{
public:
  /// The crossings s_a < 0 < s_b of t0 + t1 s + t2 s^2, by the quadratic formula without cancellation; false where
  /// there are none around s = 0 (t2 >= 0: no rolling; t0 <= 0: on or beyond the rim).
  static bool crossings(double t0, double t1, double t2, double& s_a, double& s_b);

  /// m: f^2 = t^m (1 or 2); the step [0, d] with d < s_b
  RimIntegral(int m, double t0, double t1, double t2, double s_a, double s_b, double d);

  /// The integral over [0, d] of (alpha0 + alpha1 s + alpha2 s^2) / f(t(s)).
  double operator()(double alpha0, double alpha1, double alpha2) const;

  /// The stretched time u = the integral of ds / f(t(s)) from 0, in which the pole is gone (an affine function of s is
  /// smooth in u: s(u) is a logistic curve for f = t, a sine for f = sqrt(t)): its value U at d, and the s where
  /// u = c U for c = c_1, 1/2, 1 - c_1 (0 < c_1 < 1/2).
  double stretchedLength() const;
  void stretchedNodes(double c_1, double s[3]) const;

private:
  int m_;
  double t0_, t1_, t2_, s_a_, s_b_, d_;
  double h_, mid_;                                            // half the distance between the roots, their middle
  double log_a_ = 0.0, log_b_ = 0.0;                          // f = t
  double dphi_ = 0.0, sin0_ = 0.0, cos0_ = 0.0, sin1_ = 0.0, cos1_ = 0.0;  // f = sqrt(t)
};

/// A bound on |w|''' over a step [0, d] of a path where the drive w = w_start + s w' is affine (w_dot_norm = |w'|; w0 and
/// w1, |w| at the ends): with |w|^2 = |w_start + w' s|^2, |w|''' = -3 D (w . w') / |w|^5, D = (w_start x w')^2, so
/// ||w|'''| <= 3 D |w'| / |w|^4 at the least |w| over the step (at the vertex of |w|^2 where that lies within it). The
/// error of |w|'s quadratic through 0, d / 2, d, which nearRim and RimEntry integrate against 1 / f, is
/// |w|'''(xi) / 6 s (s - d / 2) (s - d), at most this bound / 12 d^2 min(s, d - s).
inline double driveNormThird(const Eigen::Vector2d& w_start, const Eigen::Vector2d& w_dot, double w_dot_norm, double d,
                             double w0, double w1)
{
  const double cross = w_start.x() * w_dot.y() - w_start.y() * w_dot.x();
  const double vertex = -w_start.dot(w_dot) / std::max(w_dot_norm * w_dot_norm, 1e-300);
  const double w_least = vertex > 0.0 && vertex < d ? std::abs(cross) / w_dot_norm : std::min(w0, w1);
  return 3.0 * (cross * cross) * w_dot_norm / (w_least * w_least * w_least * w_least);
}

}  // namespace sphere_contact_estimator::lattice
