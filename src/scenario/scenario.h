#pragma once

// STL
#include <string>
#include <vector>

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// One phase of a manoeuvre: quantities ramp linearly from start to end over the duration.
struct ScenarioSegment
{
  std::string name;
  double duration = 1.0;             ///< [s]
  double speed_start = 0.0;          ///< rolling speed V_r along the heading [m/s]
  double speed_end = 0.0;
  double sliding_start = 0.0;        ///< longitudinal sliding velocity V_s,x (> 0: the centre outruns the
  double sliding_end = 0.0;          ///< rolling speed, as in braking) [m/s]
  double lateral_sliding = 0.0;      ///< V_s,y, to the left [m/s]
  double yaw_rate = 0.0;             ///< turning rate of the path [rad/s]
  double spin_rate = 0.0;            ///< omega_z of the sphere [rad/s]
};

/// The kinematic state of a spherical robot at one instant, ROS axes (REP 103), with the body frame
/// yawed along the path (its x is the heading) and its origin at the sphere centre.
struct ScenarioSample
{
  double time = 0.0;                                   ///< since the start [s]
  int segment = 0;                                     ///< index into the segments
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< sphere centre in the odometry frame [m]
  double yaw = 0.0;                                    ///< heading [rad]
  Eigen::Vector3d omega_body = Eigen::Vector3d::Zero();     ///< angular velocity, body axes [rad/s]
  Eigen::Vector3d velocity_body = Eigen::Vector3d::Zero();  ///< contact-patch centre velocity, body axes [m/s]
};

/// A manoeuvre of a spherical robot of rolling radius R, sampled at a fixed rate: pure rolling at V_r along
/// the heading (omega_y = V_r / R in body axes, docs/conventions.md) plus the sliding velocities of the segment.
class Scenario
{
public:
  /// Throws std::invalid_argument for no segments, non-positive durations, non-finite values or R <= 0.
  Scenario(std::vector<ScenarioSegment> segments, double rolling_radius);

  /// accelerate, cruise, turn, brake with slip, spin in place, rest.
  static std::vector<ScenarioSegment> defaultSegments();

  double duration() const { return duration_; }
  const std::vector<ScenarioSegment>& segments() const { return segments_; }

  /// The samples at t = 0, dt, 2 dt, ... up to the duration, integrating the pose.
  std::vector<ScenarioSample> sample(double dt) const;

private:
  std::vector<ScenarioSegment> segments_;
  double rolling_radius_;
  double duration_ = 0.0;
};

}  // namespace sphere_contact_estimator
