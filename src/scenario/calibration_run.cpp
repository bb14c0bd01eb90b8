#include "calibration_run.h"

// STL
#include <cmath>
#include <random>
#include <stdexcept>

// Package
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

namespace sphere_contact_estimator
{
std::vector<CalibrationMessage> calibrationRun(const Scenario& scenario, const EstimatorSettings& truth, double rate,
                                               const CalibrationNoise& noise)
{
  if (!(rate > 0.0))
    throw std::invalid_argument("calibration run: the rate must be > 0");
  EstimatorSettings exact = truth;
  exact.accuracy_target = std::min(truth.accuracy_target, 1e-4);
  exact.propagate_covariance = false;
  exact.auto_noise_fraction = 0.0;
  ContactEstimator estimator(exact);
  std::mt19937_64 rng(noise.seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  const double mass = truth.robot_mass, g = truth.gravity;
  std::vector<CalibrationMessage> out;
  for (const ScenarioSample& s : scenario.sample(1.0 / rate))
  {
    CalibrationMessage m;
    m.stamp = 1.0 + s.time;
    m.yaw = s.yaw;
    m.position = s.position;
    const double c = std::cos(s.yaw), sn = std::sin(s.yaw);
    const auto toGround = [&](const Eigen::Vector3d& b) {
      return Eigen::Vector3d(c * b.x() - sn * b.y(), sn * b.x() + c * b.y(), b.z());
    };
    // the force on the exact kinematics
    EstimatorInput exact_in;
    exact_in.stamp = m.stamp;
    exact_in.omega = toGround(s.omega_body);
    exact_in.v_contact = toGround(s.velocity_body);
    exact_in.body_heading = s.yaw;
    const ContactEstimateData* e = estimator.update(exact_in);
    const Eigen::Vector2d force = e ? robotForce(*e) : Eigen::Vector2d::Zero();
    m.force_true = Eigen::Vector3d(force.x(), force.y(), 0.0);
    // the IMU: acceleration F / m, less gravity (an accelerometer at rest reads +g up), in body axes, with noise
    const Eigen::Vector3d f_ground(force.x() / mass, force.y() / mass, g);
    const Eigen::Vector3d f_body(c * f_ground.x() + sn * f_ground.y(), -sn * f_ground.x() + c * f_ground.y(), g);
    m.specific_force_body = f_body + Eigen::Vector3d(noise.imu * unit(rng) + noise.imu_bias.x(),
                                                     noise.imu * unit(rng) + noise.imu_bias.y(), noise.imu * unit(rng));
    // the odometry as recorded, with its noise
    m.omega_body = s.omega_body + noise.omega * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    m.velocity_body = s.velocity_body + noise.velocity * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    // what the calibration reads: the odometry in the ground frame (as the node turns it with the odometry's
    // orientation), the IMU's force turned into the ground frame
    CalibrationSample& cs = m.sample;
    cs.input.stamp = m.stamp;
    cs.input.omega = toGround(m.omega_body);
    cs.input.v_contact = toGround(m.velocity_body);
    cs.input.body_heading = s.yaw;
    TwistCovariance cov = TwistCovariance::Zero();
    for (int i = 0; i < 3; ++i)
    {
      cov(i, i) = noise.velocity * noise.velocity;
      cov(3 + i, 3 + i) = noise.omega * noise.omega;
    }
    cs.input.twist_covariance = cov;
    const Eigen::Vector3d measured_ground = toGround(m.specific_force_body);
    cs.force = forceFromSpecificForce(measured_ground, mass);
    cs.force_sd = mass * std::max(noise.imu, 1e-6);
    cs.has_force = true;
    out.push_back(m);
  }
  return out;
}

EstimatorSettings calibrationTruth()
{
  EstimatorSettings s;
  s.robot_mass = 3.0;
  s.bristle_stiffness = 1.5e8;
  s.friction = 0.6;
  return s;
}

std::vector<ScenarioSegment> calibrationSegments()
{
  // name, duration, speed start/end, sliding start/end (V_s,x), lateral sliding, yaw rate, spin rate
  return {
    { "accelerate", 2.0, 0.0, 1.0, -0.01, -0.01, 0.0, 0.0, 0.0 },
    { "cruise, small slip", 3.0, 1.0, 1.0, -0.004, 0.004, 0.003, 0.0, 0.0 },
    { "turn with spin", 3.0, 1.0, 1.0, 0.0, 0.0, 0.01, 0.6, 0.6 },
    { "brake hard", 1.0, 1.0, 0.4, 0.25, 0.25, 0.0, 0.0, 0.0 },
    { "slow, small slip", 3.0, 0.4, 0.4, 0.002, -0.002, -0.002, 0.0, 0.0 },
    { "lateral skid", 1.0, 0.4, 0.4, 0.0, 0.0, 0.15, 0.0, 0.0 },
    { "speed up", 2.0, 0.4, 1.5, -0.02, -0.01, 0.0, 0.0, 0.0 },
    { "fast, small slip", 2.0, 1.5, 1.5, 0.006, -0.006, 0.004, 0.0, 0.0 },
    { "skid to a stop", 1.5, 1.5, 0.0, 0.3, 0.1, 0.0, 0.0, 0.0 },
    { "rest", 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 },
  };
}

}  // namespace sphere_contact_estimator
