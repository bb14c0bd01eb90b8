#pragma once

// STL
#include <cmath>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush_parameters.h"

namespace sphere_contact_estimator
{
/// Limited friction for one bristle (Romano et al. eq. 4): |k u| <= mu q_z. A bristle whose adhesion
/// deflection exceeds the bound slides, with |q| = mu q_z along the rigid sliding field w (Sect. 6: the
/// sliding direction neglects u; w = sigma + A_phi x, or -V_s - A_omega_z x in the time domain, which
/// points the same way). Points on or outside the patch edge carry no deflection.
class FrictionCap
{
public:
  explicit FrictionCap(const BrushParameters& p) : p_(p), edge2_(p.a * p.a * (1.0 - 1e-12)) {}

  struct Result
  {
    bool sliding = false;
    double utilisation = 0.0;  ///< |q| / (mu q_z) after capping, in [0, 1]
    double q_z = 0.0;          ///< pressure at the bristle [N/m^2]
  };

  /// Caps the deflection u [m] of the bristle at x [m] in place; w gives the sliding direction.
  Result apply(Eigen::Vector2d& u, const Eigen::Vector2d& x, const Eigen::Vector2d& w) const
  {
    const double r2 = x.squaredNorm();
    if (r2 >= edge2_)
    {
      u.setZero();
      return {};
    }
    const double q_z = p_.qz(r2);
    const double bound = p_.mu * q_z / p_.k;  // mu q_z / k
    const double n2 = u.squaredNorm();
    if (n2 <= bound * bound)
      return { false, bound > 0.0 ? std::sqrt(n2) / bound : 0.0, q_z };
    const double wn = w.norm();
    if (wn > 0.0)
      u = w * (bound / wn);
    else  // at the spin centre the sliding direction is undefined (Sect. 5): keep the bristle's own
      u *= bound / std::sqrt(n2);
    return { true, 1.0, q_z };
  }

private:
  const BrushParameters& p_;
  double edge2_;
};

}  // namespace sphere_contact_estimator
