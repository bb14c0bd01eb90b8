#pragma once

// STL
#include <cmath>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

namespace sphere_contact_estimator
{
/// One odometry message of a recorded run, as the estimator reads it, and the horizontal force on the robot that an IMU
/// at the sphere's centre measured at its stamp: with the robot's mass m and the IMU's specific force f (what an
/// accelerometer reports: the acceleration less gravity, here turned into the ground frame), m (f + g) with g = (0, 0,
/// -gravity). The ground's contact is the only horizontal force on a spherical robot (its drive acts inside the shell),
/// so this is what the node publishes as brush_wrench plus rolling_resistance_wrench, in the ground frame.
struct CalibrationSample
{
  EstimatorInput input;
  Eigen::Vector2d force = Eigen::Vector2d::Zero();  ///< measured horizontal force on the robot, ground frame [N]
  double force_sd = 0.0;                            ///< its standard deviation on each axis [N]
  bool has_force = false;                           ///< an IMU sample was paired with this message
};

/// A horizontal vector from the contact frame (ROS axes, x along the rolling direction) into the ground frame.
inline Eigen::Vector2d contactToGround(double heading, const Eigen::Vector2d& v)
{
  const double c = std::cos(heading), s = std::sin(heading);
  return { c * v.x() - s * v.y(), s * v.x() + c * v.y() };
}

/// The horizontal force on the robot in the ground frame that an estimate gives: the brush force and the rolling
/// resistance against the rolling direction (what the node publishes as brush_wrench and rolling_resistance_wrench).
inline Eigen::Vector2d robotForce(const ContactEstimateData& e)
{
  return contactToGround(e.heading, Eigen::Vector2d(e.brush.F_x - e.rolling_resistance_force, e.brush.F_y));
}

/// The IMU's specific force f (ground frame, m/s^2) to the horizontal force on a robot of mass m: m (f + g)_xy.
inline Eigen::Vector2d forceFromSpecificForce(const Eigen::Vector3d& f_ground, double mass)
{
  return mass * f_ground.head<2>();  // g has no horizontal part
}

}  // namespace sphere_contact_estimator
