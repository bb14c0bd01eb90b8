#pragma once

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_parameters.h"

namespace sphere_contact_estimator
{
/// Force density on the plane in comoving coordinates, eq. 12 [N/m^2]:
/// f(xi) = k/(2R) xi^2 - gamma v/R xi + m v^2/R - h k, with h = xi_+^2 / (2R) (eq. 13).
double forceDensity(const CylinderParameters& p, double xi, double xi_plus, double v);

/// The contact patch [xi_-, xi_+] for a given front boundary xi_+ and speed v, and the two
/// integrals of eq. 12 over it in closed form.
struct ContactPatch
{
  double xi_minus = 0.0;      ///< rear boundary, eq. 15 [m]
  double width = 0.0;         ///< xi_+ - xi_-, computed without cancellation [m]
  double F_N = 0.0;           ///< -integral f dxi over the patch (eq. 7) [N/m]
  double first_moment = 0.0;  ///< -integral xi f dxi over the patch (eq. 17 times R) [N]
};

/// Evaluates the patch for xi_+ >= m v / gamma, where f(xi_+) <= 0 (the self-consistency
/// condition after eq. 15). Writing f = k/(2R) (xi - xi_-)(xi - xi_-'), with the second root
/// xi_-' = xi_- + D and D = 2 sqrt(xi_+^2 + lambda v^2), the integrals become polynomials in the
/// width w, so they stay accurate as the patch closes (w -> 0 near the critical speed):
///   -integral f       = k/(2R) w^2 (D/2 - w/3)
///   -integral xi f    = (gamma v/k) (-integral f) - v^2 (gamma xi_+ - m v)^2 / (2 R k)   if gamma v/k <= xi_+
///                     = k/(2R) w^2 [xi_- (D/2 - w/3) + D w/3 - w^2/4]                    otherwise
/// The first form is O(v) term by term (accurate at creep speeds), the second does not cancel when the
/// patch is narrow and viscous; both are the same polynomial.
ContactPatch contactPatch(const CylinderParameters& p, double xi_plus, double v);

}  // namespace sphere_contact_estimator
