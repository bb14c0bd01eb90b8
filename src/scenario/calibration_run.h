#pragma once

// STL
#include <cstdint>
#include <vector>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/calibration/calibration_sample.h"
#include "sphere_contact_estimator/core/estimator/estimator_settings.h"
#include "scenario.h"

namespace sphere_contact_estimator
{
/// The noise of a synthetic calibration run: on the odometry as the demo has it (and declared in its twist covariance),
/// and on the IMU's specific force.
struct CalibrationNoise
{
  double omega = 0.02;     ///< [rad/s], standard deviation on each axis
  double velocity = 0.005; ///< [m/s]
  double imu = 0.05;       ///< [m/s^2]
  /// A constant bias on the IMU's horizontal specific force (body axes) [m/s^2]: a run that is not the model's.
  Eigen::Vector2d imu_bias = Eigen::Vector2d::Zero();
  std::uint64_t seed = 1;
};

/// One message of a synthetic run: what a robot would record (odometry in its body axes, the IMU's specific force in
/// its body axes, the yaw) and the sample the calibration reads from it.
struct CalibrationMessage
{
  double stamp = 0.0;
  double yaw = 0.0;                                     ///< body heading in the odometry frame [rad]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< sphere centre [m]
  Eigen::Vector3d omega_body = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_body = Eigen::Vector3d::Zero();
  Eigen::Vector3d specific_force_body = Eigen::Vector3d::Zero();  ///< IMU at the centre, gravity included [m/s^2]
  Eigen::Vector3d force_true = Eigen::Vector3d::Zero();           ///< the models' horizontal force, ground frame [N]
  CalibrationSample sample;
};

/// A run of a robot with known parameters (`truth`): the scenario's kinematics (the drive's slip as chosen), the force
/// from the node's estimator at those parameters on the exact kinematics (its accuracy target raised to 1e-4), the IMU
/// reading that force over the robot's mass plus gravity, and noise on both as `noise` says.
std::vector<CalibrationMessage> calibrationRun(const Scenario& scenario, const EstimatorSettings& truth, double rate,
                                               const CalibrationNoise& noise);

/// The robot of the bundled calibration run (data/calibration.bag), its tests and its benchmark: the default robot at
/// 3 kg with k = 1.5e8 N/m^3 and mu = 0.6.
EstimatorSettings calibrationTruth();

/// The segments of the bundled calibration run: rolling at several speeds with small slips (the slip stiffness), hard
/// braking and a lateral skid (friction), turns with spin.
std::vector<ScenarioSegment> calibrationSegments();

}  // namespace sphere_contact_estimator
