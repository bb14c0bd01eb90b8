#pragma once

// STL
#include <cmath>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "pressure_law.h"

namespace sphere_contact_estimator
{
/// Limited friction for one bristle (Romano et al. eq. 4): |k u| <= mu q_z. A bristle whose adhesion
/// deflection exceeds the bound slides, with |q| = mu q_z along the rigid sliding field w (Sect. 6: the
/// sliding direction neglects u; w = sigma + A_phi x, or -V_s - A_omega_z x in the time domain, which
/// points the same way). Points on or outside the patch edge carry no deflection.
/// It runs once per bristle and step, so the constants are folded once and nothing divides.
class FrictionCap
{
public:
  explicit FrictionCap(const BrushParameters& p)
    : pressure_(p.pressure), inv_a2_(1.0 / (p.a * p.a)), edge_(1.0 - 1e-12), mu_over_k_(p.mu / p.k)
  {
    q0_ = pressure_.peakFactor() * p.F_z / (M_PI * p.a * p.a);  // q_z at the centre
  }

  struct Result
  {
    bool sliding = false;
    double utilisation2 = 0.0;  ///< (|q| / (mu q_z))^2 after capping, in [0, 1]
    double q_z = 0.0;           ///< pressure at the bristle [N/m^2]
  };

  /// Pressure q_z [N/m^2] at squared distance r2 from the patch centre (BrushParameters::qz, folded).
  double qz(double r2) const { return q0_ * pressure_.shape(1.0 - r2 * inv_a2_); }

  /// The growth of the bound mu q_z / k with r^2 [m/m^2]: d(mu q_z / k) / d(r^2) (0 off the patch, and for the
  /// uniform pressure; unbounded at the edge for the Hertzian one).
  double boundSlope(double r2) const { return -mu_over_k_ * q0_ * inv_a2_ * pressure_.shapeSlope(1.0 - r2 * inv_a2_); }

  /// Puts a sliding bristle at x [m] on the bound along w (u = mu q_z / k w / |w|), whatever its deflection was.
  Result slide(Eigen::Vector2d& u, const Eigen::Vector2d& x, const Eigen::Vector2d& w) const
  {
    const double r2 = x.squaredNorm();
    if (r2 * inv_a2_ >= edge_)
    {
      u.setZero();
      return {};
    }
    const double q_z = qz(r2), bound = mu_over_k_ * q_z, wn = w.norm();
    if (wn > 0.0)
      u = bound / wn * w;
    else if (u.squaredNorm() > 0.0)
      u *= bound / u.norm();
    return { true, 1.0, q_z };
  }

  /// Caps the deflection u [m] of the bristle at x [m] in place; w gives the sliding direction.
  Result apply(Eigen::Vector2d& u, const Eigen::Vector2d& x, const Eigen::Vector2d& w) const
  {
    return apply(u.x(), u.y(), x.x(), x.y(), w.x(), w.y());
  }

  /// The same on components, for the models' inner loops.
  Result apply(double& ux, double& uy, double x, double y, double wx, double wy) const
  {
    const double r2 = x * x + y * y;
    if (r2 * inv_a2_ >= edge_)
    {
      ux = uy = 0.0;
      return {};
    }
    const double q_z = qz(r2);
    const double bound = mu_over_k_ * q_z;  // mu q_z / k
    const double n2 = ux * ux + uy * uy, b2 = bound * bound;
    if (n2 <= b2)
      return { false, b2 > 0.0 ? n2 / b2 : 0.0, q_z };
    const double wn2 = wx * wx + wy * wy;
    if (wn2 > 0.0)
    {
      const double f = bound / std::sqrt(wn2);
      ux = f * wx;
      uy = f * wy;
    }
    else  // at the spin centre the sliding direction is undefined (Sect. 5): keep the bristle's own
    {
      const double f = bound / std::sqrt(n2);
      ux *= f;
      uy *= f;
    }
    return { true, 1.0, q_z };
  }

private:
  PressureLaw pressure_;
  double inv_a2_, edge_, mu_over_k_, q0_ = 0.0;
};

}  // namespace sphere_contact_estimator
