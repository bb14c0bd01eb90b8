#include "sphere_contact_estimator/core/rolling_resistance/cylinder_scales.h"

// STL
#include <cmath>
#include <limits>

namespace sphere_contact_estimator
{
CylinderScales CylinderScales::of(const CylinderParameters& p)
{
  CylinderScales s;
  s.xi0 = std::cbrt(1.5 * p.R * p.weight() / p.k);             // eq. 22
  s.h0 = s.xi0 * s.xi0 / (2.0 * p.R);                          // eq. 25
  s.lambda = (p.gamma / p.k) * (p.gamma / p.k) - 2.0 * p.m / p.k;  // after eq. 20
  s.v_critical = p.m > 0.0 ? std::cbrt(p.weight() * p.gamma * p.R / (p.m * p.m))
                           : std::numeric_limits<double>::infinity();
  s.overdamped = 4.0 * p.m * p.k < p.gamma * p.gamma;          // eq. 2 times k^2
  if (s.lambda > 0.0)
  {
    s.mu_star = (p.gamma / p.k) * (p.gamma / p.k) * s.xi0 / (3.0 * s.lambda);  // eq. 28
    s.v_star = 2.0 * (p.gamma / p.k) * s.xi0 / (3.0 * s.lambda);                // eq. 29
  }
  return s;
}

}  // namespace sphere_contact_estimator
