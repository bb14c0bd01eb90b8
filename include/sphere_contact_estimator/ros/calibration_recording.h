#pragma once

// STL
#include <cstdint>
#include <string>
#include <vector>

// Package
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/core/calibration/calibration_sample.h"

namespace sphere_contact_estimator
{
struct CalibrationReadOptions
{
  ContactEstimatorConfig config;  ///< the robot's parameters (mass, frames, tf_max_age)
  std::string odom_topic;         ///< nav_msgs/Odometry; empty: the bag's only one
  std::string imu_topic;          ///< sensor_msgs/Imu at the sphere's centre; empty: the bag's only one
  /// The IMU's noise, standard deviation of its specific force on each axis [m/s^2]; 0: from the messages'
  /// linear_acceleration_covariance where they give one, else estimated from the run (successive differences).
  double imu_noise = 0.0;
  double max_imu_gap = 0.05;  ///< an odometry message further than this from the IMU samples around it has none [s]
};

/// The odometry messages of one or more runs with the IMU's horizontal force paired to each, as the calibration
/// reads them.
struct CalibrationRecording
{
  std::vector<CalibrationSample> samples;
  std::vector<double> time;  ///< since the first message of its bag [s]
  std::vector<int> bag;      ///< which bag (index into bags)
  std::vector<std::string> bags;
  std::string odom_topic, imu_topic;  ///< of the first bag
  std::uint64_t imu_messages = 0;
  std::uint64_t imu_without_orientation = 0;  ///< no orientation in the message and no tf for its frame: unused
  std::uint64_t odometry_without_orientation = 0;
  double imu_noise = 0.0;         ///< used [m/s^2]
  std::string imu_noise_source;   ///< "option", "messages' covariance", "estimated from the run"
  double imu_rate = 0.0;          ///< median [Hz]
};

/// Reads bags in order. The odometry turns into the estimator's input as the node has it (OdometryEstimator::toInput:
/// tf in the bag, else the odometry's orientation); the IMU's linear acceleration (specific force, gravity included,
/// in its frame) turns into the ground frame with the message's orientation (REP 145: none where
/// orientation_covariance[0] is -1), else tf from the IMU's frame; the horizontal force is robot mass x that, linearly
/// interpolated to each odometry stamp. Each bag after the first starts after a gap beyond max_step, so the estimator
/// starts afresh. Throws std::runtime_error naming the bag and topic: no odometry, no IMU topic, no IMU sample with an
/// orientation.
CalibrationRecording readCalibrationBags(const std::vector<std::string>& bags, const CalibrationReadOptions& options);

}  // namespace sphere_contact_estimator
