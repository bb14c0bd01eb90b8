#pragma once

// STL
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

namespace sphere_contact_estimator::test
{
/// A random robot of stream_sweep.py's envelope (patch radius 4-50 mm, k 3e7-1e9 N/m^3, mass 1-40 kg, mu 0.3-1.2, any
/// pressure; the rest the defaults, auto) at 30, 100 or 1000 Hz with 0.5-2 times the demo's noise (`scale`).
inline void randomParkedRobot(std::mt19937_64& r, EstimatorSettings& s, double& rate, double& scale)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto logUniform = [&](double lo, double hi) { return std::exp(std::log(lo) + u(r) * std::log(hi / lo)); };
  s.patch_radius = logUniform(0.004, 0.05);
  s.bristle_stiffness = logUniform(3e7, 1e9);
  s.robot_mass = logUniform(1.0, 40.0);
  s.friction = 0.3 + 0.9 * u(r);
  const PressureDistribution pressures[3] = { PressureDistribution::Parabolic, PressureDistribution::Hertzian,
                                              PressureDistribution::Uniform };
  s.pressure = pressures[std::min(2, static_cast<int>(3.0 * u(r)))];
  const double rates[3] = { 30.0, 100.0, 1000.0 };
  rate = rates[std::min(2, static_cast<int>(3.0 * u(r)))];
  scale = 0.5 + 1.5 * u(r);
}

/// A random robot (randomParkedRobot) that moves without noise - parked from the start, after a skid (0.1-0.3 s at
/// 0.2-1 m/s with a lateral slip of 2-8 % either way) or after spinning in place (2-10 rad/s for 0.3-1 s) - then parks
/// for a second with its noise on every twist component (`noisy`), the covariance declared the noise's throughout;
/// `clean` is the same stream with the parked part noise-free: the truth of a robot at rest.
struct ParkedStreams
{
  EstimatorSettings settings;
  double rate = 0.0, noise_scale = 0.0;
  int kind = 0;    // 0 parked from the start, 1 after a skid, 2 after spinning in place
  int moving = 0;  // messages before the park
  std::vector<EstimatorInput> noisy, clean;

  /// An estimate against the truth in the band it publishes: each of F_x, F_y and M_z's error and standard deviation
  /// over its scale (mu F_z; M_z: mu F_z a). Any covariance method counts (held: the walk; moved by the noise: the
  /// linearised or unscented spread); none published, a band of zero width.
  struct Band
  {
    Eigen::Vector3d error, sd;
    bool published = false;
    /// the largest miss beyond 2 sd, over its scale (and its component): outside the band where above 1e-12
    double largestMiss(Eigen::Index* component = nullptr) const
    {
      Eigen::Index j = 0;
      const double miss = (error.cwiseAbs() - 2.0 * sd).maxCoeff(&j);
      if (component)
        *component = j;
      return miss;
    }
  };

  Band band(const ContactEstimateData& estimate, const ContactEstimateData& truth) const
  {
    const double muFz = settings.friction * settings.verticalLoad();
    const Eigen::Vector3d scale(muFz, muFz, muFz * settings.patch_radius);
    Band b;
    b.published = estimate.covariance.brush_method != CovarianceMethod::None;
    b.error = Eigen::Vector3d(estimate.brush.F_x - truth.brush.F_x, estimate.brush.F_y - truth.brush.F_y,
                              estimate.brush.M_z - truth.brush.M_z)
                  .cwiseQuotient(scale);
    b.sd.setZero();
    for (int j = 0; b.published && j < 3; ++j)
      b.sd(j) = std::sqrt(std::max(0.0, estimate.covariance.brush(j, j))) / scale(j);
    return b;
  }

  static const char* kindName(int kind)
  {
    static const char* const names[3] = { "parked", "after_skid", "after_spin" };
    return names[kind];
  }

  ParkedStreams(std::mt19937_64& r, unsigned noise_seed)
  {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    randomParkedRobot(r, settings, rate, noise_scale);
    kind = std::min(2, static_cast<int>(3.0 * u(r)));
    const double duration = kind == 1 ? 0.1 + 0.2 * u(r) : 0.3 + 0.7 * u(r);
    const double speed = 0.2 + 0.8 * u(r), skid = (u(r) < 0.5 ? -1.0 : 1.0) * (0.02 + 0.06 * u(r));
    const double spin = (u(r) < 0.5 ? -1.0 : 1.0) * (2.0 + 8.0 * u(r));
    moving = kind == 0 ? 0 : static_cast<int>(duration * rate);
    const int parked = static_cast<int>(rate);
    Eigen::Matrix<double, 6, 1> sd;
    sd << 0.005, 0.005, 0.005, 0.02, 0.02, 0.02;  // the demo's [m/s, rad/s], scaled
    sd *= noise_scale;
    const TwistCovariance twist = sd.cwiseAbs2().asDiagonal();
    std::mt19937_64 noise(noise_seed);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int k = 0; k < moving + parked; ++k)
    {
      EstimatorInput in;
      in.stamp = k / rate;
      in.twist_covariance = twist;
      in.v_contact.setZero();
      in.omega.setZero();
      if (k < moving && kind == 1)
      {
        // rolling along x (ROS) and sliding sideways by skid times that: V_r = R (omega_y, -omega_x)
        in.omega = Eigen::Vector3d(0.0, speed / settings.rolling_radius, 0.0);
        in.v_contact = Eigen::Vector3d(speed, -speed * skid, 0.0);
      }
      else if (k < moving)
        in.omega = Eigen::Vector3d(0.0, 0.0, spin);
      clean.push_back(in);
      if (k >= moving)
        for (int i = 0; i < 3; ++i)
        {
          in.v_contact(i) += sd(i) * g(noise);
          in.omega(i) += sd(3 + i) * g(noise);
        }
      noisy.push_back(in);
    }
  }
};

}  // namespace sphere_contact_estimator::test
