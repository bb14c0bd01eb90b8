#pragma once

// STL
#include <cmath>
#include <random>

// Eigen
#include <Eigen/Core>

// Package
#include "brush_closed_form.h"
#include "sphere_contact_estimator/core/brush/brush_forces.h"
#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "sphere_contact_estimator/core/brush/contact_kinematics.h"

namespace sphere_contact_estimator::test
{
/// The paper's Fig. 4 set: F_z = 3000 N, a = 0.05 m, k = 1.023e8 N/m^3, mu = 1, parabolic pressure; the law of the
/// sliding direction as given (the paper drew Fig. 4 with the rigid one).
inline BrushParameters figure4Parameters(bool tilt = false, int resolution = 32, SlidingLaw law = SlidingLaw::Coulomb)
{
  BrushParameters p;
  p.a = 0.05;
  p.k = 1.023e8;
  p.F_z = 3000.0;
  p.mu = 1.0;
  p.tilt = tilt;
  p.resolution = resolution;
  p.sliding_law = law;
  return p;
}

/// A robot whose rigid-law search for G's component around a front-half pole is at its dearest (found by
/// bench/work_units.cpp): tilted paths, the Hertzian pressure, the rigid law; its slips and spin in RigidSearchInputs.
inline BrushParameters rigidSearchRobot(int resolution = 32)
{
  BrushParameters p;
  p.a = 0.0148;
  p.k = 5.46e7;
  p.F_z = 63.5;
  p.mu = 1.04;
  p.pressure = PressureDistribution::Hertzian;
  p.tilt = true;
  p.sliding_law = SlidingLaw::Rigid;
  p.resolution = resolution;
  return p;
}
struct RigidSearchInputs
{
  Eigen::Vector2d sigma{ -0.0815, 0.0864 };
  double a_phi = -0.959;  ///< phi a; chi_gamma 0.9 (phi_gamma = 0.9 phi, phi_psi = 0.1 phi)
};

/// The robot and inputs of a held-input check where a bristle past the spin pole, more than a right angle off its drive,
/// re-adheres within an update and slides again (a = 16 mm, parabolic, eq. 4b; a phi = -0.813 at 1 m/s): the tests of
/// a long stiff step through a re-adhesion
inline BrushParameters spinPoleRobot()
{
  BrushParameters p;
  p.sliding_law = SlidingLaw::Coulomb;
  p.a = 0.01596;
  p.k = 5.18e7;
  p.F_z = 56.1;
  p.mu = 1.0;
  return p;
}
inline ContactKinematics spinPoleKinematics(const BrushParameters& p)
{
  return ContactKinematics::fromSlips({ -0.00973, -0.00487 }, -0.813 / p.a, 1.0, 1.0);
}

/// Both laws, for tests of what holds under either.
constexpr SlidingLaw kSlidingLaws[] = { SlidingLaw::Coulomb, SlidingLaw::Rigid };

/// The brush parameters of the envelope the random tests draw from (issue 11): a = 0.01-0.08 m, F_z = 20-5000 N
/// (log-uniform), mu = 0.2-1.2, k = 10^6.5-10^9 N/m^3 (log-uniform), drawn in that order from rng; the pressure
/// cycles with i, tilt alternates every three; the sliding law as given.
inline BrushParameters drawEnvelopeParameters(std::mt19937_64& rng, int i, SlidingLaw law = SlidingLaw::Coulomb)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  BrushParameters p;
  p.sliding_law = law;
  p.a = 0.01 + 0.07 * u(rng);
  p.F_z = std::exp(std::log(20.0) + std::log(250.0) * u(rng));
  p.mu = 0.2 + u(rng);
  p.k = std::pow(10.0, 6.5 + 2.5 * u(rng));
  p.pressure = static_cast<PressureDistribution>(i % 3);
  p.tilt = (i / 3) % 2;
  return p;
}

/// Forces of a deflection field u(x) by a fine midpoint rule in polar coordinates (an independent
/// quadrature for the closed-form fields).
template <class Field>
BrushForces integrateField(const Field& u, double a, double k, int n = 400)
{
  BrushForces f;
  const double dr = a / n, dt = 2.0 * M_PI / (4 * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 4 * n; ++j)
    {
      const double r = (i + 0.5) * dr, t = (j + 0.5) * dt;
      const Eigen::Vector2d x(r * std::cos(t), r * std::sin(t));
      const Eigen::Vector2d q = k * u(x);
      const double dA = r * dr * dt;
      f.F_x += q.x() * dA;
      f.F_y += q.y() * dA;
      f.M_z += (x.x() * q.y() - x.y() * q.x()) * dA;
    }
  return f;
}

/// Largest difference of forces and moment (moment over a) relative to mu F_z.
inline double forceDistance(const BrushForces& a, const BrushForces& b, const BrushParameters& p)
{
  const double scale = p.mu * p.F_z;
  return std::max({ std::abs(a.F_x - b.F_x), std::abs(a.F_y - b.F_y), std::abs(a.M_z - b.M_z) / p.a }) / scale;
}

}  // namespace sphere_contact_estimator::test
