#pragma once

// STL
#include <cmath>
#include <random>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "sphere_contact_estimator/core/brush/contact_kinematics.h"

namespace sphere_contact_estimator::test
{
/// One message of a noisy history at a random point: rolling at the base slips and spin a_phi / a with noise on each
/// (phi held within |R_gamma| > a / 0.9 with tilt), or, parked, creeping at 0.01 m/s with noise for the slip velocity
/// and the spin; the draws in a fixed order.
struct NoisyHistory
{
  Eigen::Vector2d base;
  double a_phi, noise;
  double chi;         // rolling: chi_gamma
  double chi_parked;  // parked: psi_dot = (1 - chi_parked) omega_z

  /// With the caller's normal distribution (which keeps a spare draw between calls: its lifetime is part of the draw).
  ContactKinematics message(std::mt19937_64& rng, std::normal_distribution<double>& g, bool parked,
                            const BrushParameters& p) const
  {
    ContactKinematics k;
    if (parked)
    {
      const double vx = g(rng), vy = g(rng);
      k.V_r = 0.01 * Eigen::Vector2d(vx, vy);
      const double sx = g(rng), sy = g(rng);
      k.V_s = noise * Eigen::Vector2d(sx, sy);
      k.omega_z = (a_phi + noise * g(rng)) / p.a;
      k.psi_dot = (1.0 - chi_parked) * k.omega_z;
      return k;
    }
    double phi = (a_phi + noise * g(rng)) / p.a;
    if (p.tilt && std::abs(chi * phi) * p.a > 0.9)
      phi = std::copysign(0.9 / (std::abs(chi) * p.a), phi);
    const double sx = g(rng), sy = g(rng);
    return ContactKinematics::fromSlips(base + noise * Eigen::Vector2d(sx, 0.3 * sy), phi, chi, 1.0);
  }
  /// With a normal distribution of its own.
  ContactKinematics message(std::mt19937_64& rng, bool parked, const BrushParameters& p) const
  {
    std::normal_distribution<double> g(0.0, 1.0);
    return message(rng, g, parked, p);
  }
};

/// A seeded random noisy history for a patch of radius p.a: slips and spins from 1e-3 of the envelope to all of it,
/// noise 1e-3 to 1e-1, 0.03-2.5 patch radii a message at V_r = 1 m/s, three in ten ending parked.
struct NoisyHistoryDraw
{
  NoisyHistory history;
  double dt;    // a message's step [s]
  bool parked;  // from message 16 on
};

inline NoisyHistoryDraw drawNoisyHistory(std::mt19937_64& rng, const BrushParameters& p)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double scale = std::pow(10.0, -3.0 * u(rng));
  const Eigen::Vector2d base = scale * Eigen::Vector2d(0.3 * (2.0 * u(rng) - 1.0), 0.1 * (2.0 * u(rng) - 1.0));
  const double a_phi = scale * (2.0 * u(rng) - 1.0);
  const double noise = std::pow(10.0, -3.0 + 2.0 * u(rng));
  const double dt = std::pow(10.0, -1.5 + 1.9 * u(rng)) * p.a;  // at V_r = 1 m/s
  const double chi = -0.5 + 2.0 * u(rng);
  const bool parked = u(rng) < 0.3;
  return { NoisyHistory{ base, a_phi, noise, chi, chi }, dt, parked };
}
}  // namespace sphere_contact_estimator::test
