#pragma once

// STL
#include <cmath>

// Package
#include "sphere_contact_estimator/core/brush/brush_parameters.h"

namespace sphere_contact_estimator
{
/// The vertical pressure q_z over the circular patch as the solvers see it (Romano et al. Sect. 6: "an expression for
/// the steady-state vertical pressure distribution q_z(x) needs to be specified"). Everything is written in
/// t = 1 - r^2 / a^2, the distance from the rim that every path carries without cancellation: the bound's shape
/// f(t) = q_z / q_z(0), with f^2 = t^m for an integer m, so that the solvers' event polynomials stay polynomials.
/// The one place that knows the three laws: adding one is this file.
class PressureLaw
{
public:
  explicit PressureLaw(PressureDistribution kind) : kind_(kind) {}

  PressureDistribution kind() const { return kind_; }

  /// m with f^2 = t^m: 2 (parabolic, f = t), 1 (Hertzian, f = sqrt t), 0 (uniform, f = 1).
  int squaredExponent() const
  {
    switch (kind_)
    {
      case PressureDistribution::Parabolic:
        return 2;
      case PressureDistribution::Hertzian:
        return 1;
      case PressureDistribution::Uniform:
        return 0;
    }
    return 0;
  }

  /// q_z(0) over the mean pressure F_z / (pi a^2): 2, 1.5, 1 (each law integrates to F_z).
  double peakFactor() const
  {
    switch (kind_)
    {
      case PressureDistribution::Parabolic:
        return 2.0;
      case PressureDistribution::Hertzian:
        return 1.5;
      case PressureDistribution::Uniform:
        return 1.0;
    }
    return 1.0;
  }

  /// f(t) = q_z / q_z(0) at t = 1 - r^2 / a^2; 0 on and beyond the rim (t <= 0).
  double shape(double t) const
  {
    if (t <= 0.0)
      return 0.0;
    switch (kind_)
    {
      case PressureDistribution::Parabolic:
        return t;
      case PressureDistribution::Hertzian:
        return std::sqrt(t);
      case PressureDistribution::Uniform:
        return 1.0;
    }
    return 0.0;
  }

  /// df/dt (0 beyond the rim; unbounded at the rim for the Hertzian law).
  double shapeSlope(double t) const
  {
    if (t <= 0.0)
      return 0.0;
    switch (kind_)
    {
      case PressureDistribution::Parabolic:
        return 1.0;
      case PressureDistribution::Hertzian:
        return 0.5 / std::sqrt(t);
      case PressureDistribution::Uniform:
        return 0.0;
    }
    return 0.0;
  }

  /// d^2f/dt^2 (0 beyond the rim; -1 / (4 t^{3/2}) for the Hertzian law, 0 for the others).
  double shapeCurvature(double t) const
  {
    if (t <= 0.0 || kind_ != PressureDistribution::Hertzian)
      return 0.0;
    return -0.25 / (t * std::sqrt(t));
  }

  /// The bound vanishes at the rim (m > 0): a bristle entering there can start sliding at once.
  bool vanishesAtRim() const { return squaredExponent() > 0; }
  /// The bound grows without limit at the rim (m = 1): a bristle always adheres as it enters.
  bool infiniteSlopeAtRim() const { return squaredExponent() == 1; }

  /// The integral of f along a chord of half-length c across the unit patch (t = c^2 - x^2 on it):
  /// 4 c^3 / 3, pi c^2 / 2, 2 c.
  double chordIntegral(double c) const
  {
    switch (kind_)
    {
      case PressureDistribution::Parabolic:
        return 4.0 / 3.0 * c * c * c;
      case PressureDistribution::Hertzian:
        return 0.5 * M_PI * c * c;
      case PressureDistribution::Uniform:
        return 2.0 * c;
    }
    return 0.0;
  }

  /// The part of chordIntegral(c) from x = d - c to c: the load on a straight path's bristles that entered more than
  /// a travel d ago (0 from d = 2c on).
  double chordIntegralAfter(double c, double d) const
  {
    if (!(d < 2.0 * c))
      return 0.0;
    if (d <= 0.0)
      return chordIntegral(c);
    const double x0 = d - c;
    switch (kind_)
    {
      case PressureDistribution::Parabolic:  // of c^2 - x^2
        return c * c * (c - x0) - (c * c * c - x0 * x0 * x0) / 3.0;
      case PressureDistribution::Hertzian:  // of sqrt(c^2 - x^2), x = c sin(theta)
      {
        const double s = x0 / c;
        return 0.5 * c * c * (0.5 * M_PI - std::asin(s) - s * std::sqrt(1.0 - s * s));
      }
      case PressureDistribution::Uniform:
        return c - x0;
    }
    return 0.0;
  }

private:
  PressureDistribution kind_;
};

}  // namespace sphere_contact_estimator
