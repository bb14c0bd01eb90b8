#pragma once

// STL
#include <cstdint>
#include <string>

// ROS
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <tf2/buffer_core.h>

// Eigen
#include <Eigen/Geometry>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

namespace sphere_contact_estimator
{
/// What one odometry message becomes: the node publishes it, bag_analyze writes it to a bag. Reused from
/// message to message, so the hot path does not allocate.
struct EstimateOutputs
{
  ContactEstimate estimate;
  geometry_msgs::WrenchStamped brush_wrench, rolling_resistance_wrench;
  geometry_msgs::TransformStamped contact_transform;  ///< ground -> contact frame
  bool has_transform = false;                         ///< false: nothing to broadcast for this message
  const ContactEstimateData* data = nullptr;          ///< the core's estimate behind the messages
};

/// Why a message gave no estimate.
enum class SkipReason
{
  None,
  NoOrientation,  ///< no tf to the ground frame and no valid odometry orientation
  RejectedInput,  ///< non-finite or impossible twist or stamp
};

/// Odometry in, estimate messages out: frames (tf at the stamp, else tf's latest, else the odometry's own
/// orientation; never waits), the core ContactEstimator, and the conversions to messages. Transport-free: the
/// node and nodelet (ContactEstimatorRos, live tf) and bag_analyze (tf read from the bag) run this same class,
/// so live and offline give the same numbers. Not thread-safe: callers serialise.
class OdometryEstimator
{
public:
  explicit OdometryEstimator(const ContactEstimatorConfig& config);

  /// Applies a configuration. Throws std::invalid_argument and keeps the previous one when it is invalid.
  void configure(const ContactEstimatorConfig& config);

  /// Processes one message with the transforms in `tf`. Returns nullptr (and sets reason) when it is
  /// skipped; otherwise the outputs, valid until the next call.
  const EstimateOutputs* process(const nav_msgs::Odometry& msg, const tf2::BufferCore& tf, SkipReason& reason);

  /// Forgets the history (time, heading, transient state).
  void reset();

  const ContactEstimator& estimator() const { return estimator_; }
  const std::string& groundFrame() const { return ground_frame_; }
  const std::string& contactFrame() const { return contact_frame_; }

  /// Where orientations came from, and what was skipped, since construction.
  struct Counters
  {
    std::uint64_t tf_at_stamp = 0, tf_latest = 0, from_odometry = 0, no_orientation = 0, rejected = 0,
                  time_jumps = 0;
    std::uint64_t bad_covariance = 0;  ///< twist covariances marked unknown or invalid (the estimate goes on without)
  };
  const Counters& counters() const { return counters_; }
  const std::string& lastTfError() const { return last_tf_error_; }
  /// Why the last unusable twist covariance was refused (nullptr before any).
  const char* lastCovarianceProblem() const { return last_covariance_problem_; }

private:
  void configureFrames(const ContactEstimatorConfig& config);
  /// Rotation from the odometry's child frame into the ground frame, and the sphere centre there.
  bool groundPose(const nav_msgs::Odometry& msg, const std::string& ground, const tf2::BufferCore& tf,
                  Eigen::Quaterniond& rotation, Eigen::Vector3d& centre, bool& have_centre);
  bool lookup(const tf2::BufferCore& tf, const std::string& target, const std::string& source, const ros::Time& stamp,
              geometry_msgs::TransformStamped& out);

  ContactEstimator estimator_;
  std::string ground_frame_, contact_frame_;
  bool publish_tf_ = true;
  ros::Time last_transform_stamp_;  // one contact transform per stamp: no TF_REPEATED_DATA
  EstimateOutputs out_;
  Counters counters_;
  std::string last_tf_error_;
  const char* last_covariance_problem_ = nullptr;
};

}  // namespace sphere_contact_estimator
