#pragma once

// STL
#include <cmath>

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
// The turn of a vector in the patch plane by an angle, and its integral over time at a constant rate: the frames'
// rotations, and the coupling of a bristle's deflection to the frame's turn (eq. 1's A_omega_z chi_psi u, A_psi_dot u).
inline Eigen::Matrix2d rotation(double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

// Integral over [0, t] of the rotation R(rate tau): [[S, -C], [C, S]] with S = sin(rate t)/rate and
// C = (1 - cos(rate t))/rate, by series where rate t is small.
inline Eigen::Matrix2d rotationIntegral(double rate, double t)
{
  const double x = rate * t;
  double S, C;
  if (std::abs(x) < 1e-3)
  {
    S = t * (1.0 - x * x / 6.0);
    C = t * x * 0.5 * (1.0 - x * x / 12.0);
  }
  else
  {
    S = std::sin(x) / rate;
    C = (1.0 - std::cos(x)) / rate;
  }
  return (Eigen::Matrix2d() << S, -C, C, S).finished();
}
}  // namespace sphere_contact_estimator
