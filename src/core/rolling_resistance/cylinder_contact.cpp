#include "sphere_contact_estimator/core/rolling_resistance/cylinder_contact.h"

// STL
#include <algorithm>
#include <cmath>

namespace sphere_contact_estimator
{
double forceDensity(const CylinderParameters& p, double xi, double xi_plus, double v)
{
  const double h = xi_plus * xi_plus / (2.0 * p.R);  // eq. 13
  return p.k / (2.0 * p.R) * xi * xi - p.gamma * v / p.R * xi + p.m * v * v / p.R - h * p.k;  // eq. 12
}

ContactPatch contactPatch(const CylinderParameters& p, double xi_plus, double v)
{
  const double s = xi_plus;
  const double lambda = (p.gamma / p.k) * (p.gamma / p.k) - 2.0 * p.m / p.k;
  // sqrt(2 h R + lambda v^2) of eq. 15; the argument equals (xi_+ - gamma v/k)^2 + 2 v (gamma xi_+ - m v)/k,
  // non-negative where f(xi_+) <= 0, so only round-off can make it negative.
  const double root = std::sqrt(std::max(0.0, s * s + lambda * v * v));
  ContactPatch c;
  // eq. 15, xi_- = gamma v/k - root, rationalised: the difference cancels where xi_- ~ 0, the sum does not.
  const double sum = p.gamma * v / p.k + root;
  c.xi_minus = sum > 0.0 ? (2.0 * p.m * v * v / p.k - s * s) / sum : 0.0;
  // w = xi_+ - xi_- = (xi_+ - gamma v/k) + root. When the bracket is negative the sum cancels; then use
  // root^2 - (xi_+ - gamma v/k)^2 = 2 v (gamma xi_+ - m v) / k, which stays accurate as w -> 0.
  const double a = s - p.gamma * v / p.k;
  if (a >= 0.0)
    c.width = a + root;
  else
    c.width = std::max(0.0, 2.0 * v * (p.gamma * s - p.m * v) / p.k / (root - a));
  const double w = c.width;
  const double D = 2.0 * root;  // distance between the two roots of eq. 12
  const double c0 = p.k / (2.0 * p.R);
  c.F_N = c0 * w * w * (0.5 * D - w / 3.0);
  // First moment. About the vertex xi = gamma v/k of the parabola, the odd part integrates to
  // (u_+^2 - D^2/4)^2 / 4 with u_+ = xi_+ - gamma v/k, and u_+^2 - D^2/4 = -2 v (gamma xi_+ - m v)/k exactly:
  //   -integral xi f = (gamma v/k) F_N - v^2 (gamma xi_+ - m v)^2 / (2 R k),            (a)
  // O(v) term by term, so accurate at creep speeds where the form in w, with the vertex xi_- + D/2,
  //   -integral xi f = k/(2R) w^2 [xi_- (D/2 - w/3) + D w/3 - w^2/4],                   (b)
  // cancels. When gamma v/k exceeds xi_+ (a viscous, narrow patch), (a) cancels instead and (b) does not.
  const double vertex = p.gamma * v / p.k;
  if (vertex <= s)
  {
    const double q = p.gamma * s - p.m * v;
    c.first_moment = vertex * c.F_N - v * v * q * q / (2.0 * p.R * p.k);
  }
  else
  {
    c.first_moment = c0 * w * w * (c.xi_minus * (0.5 * D - w / 3.0) + D * w / 3.0 - 0.25 * w * w);
  }
  return c;
}

}  // namespace sphere_contact_estimator
