#pragma once

// STL
#include <array>
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

/// Odometry in, estimate messages out: frames (tf at the stamp, else tf's latest if within tf_max_age of the stamp,
/// else the odometry's own orientation; never waits), gaps in each publisher's header.seq counted as dropped messages, the core ContactEstimator, and the conversions to messages. Transport-free: the
/// node and nodelet (ContactEstimatorRos, live tf) and bag_analyze (tf read from the bag) run this same class,
/// so live and offline give the same numbers. Not thread-safe: callers serialise.
class OdometryEstimator
{
public:
  explicit OdometryEstimator(const ContactEstimatorConfig& config);

  /// Applies a configuration. Throws std::invalid_argument and keeps the previous one when it is invalid.
  void configure(const ContactEstimatorConfig& config);

  /// Processes one message with the transforms in `tf`. Returns nullptr (and sets reason) when it is
  /// skipped; otherwise the outputs, valid until the next call. `publisher` names the message's source (the
  /// connection's callerid): header.seq counts per publisher, so a gap in it is a message lost on the way (a
  /// subscriber queue that overflowed, the source, the network); empty: one source.
  const EstimateOutputs* process(const nav_msgs::Odometry& msg, const tf2::BufferCore& tf, SkipReason& reason,
                                 const std::string& publisher = std::string());

  /// The core estimator's input for one message, its frames as process() finds them (counted the same way), and the
  /// sphere centre in the ground frame where known; false (counted) when it has no orientation. For tools that replay
  /// the inputs themselves (calibrate).
  bool toInput(const nav_msgs::Odometry& msg, const tf2::BufferCore& tf, EstimatorInput& in, Eigen::Vector3d& centre,
               bool& have_centre);
  /// Forgets the history (time, heading, transient state). The epoch stays.
  void reset();
  /// The core's time for a stamp: seconds since this estimator's epoch, the first stamp it was given, by ros::Time's
  /// integer nanoseconds. (A stamp's seconds since 1970, about 1.8e9, hold only to 2.4e-7 s as a double: each step
  /// of a 1 kHz source was off by up to 2.4e-4 of itself, differently in every recording of the same stream, and
  /// replays of two recordings parted.)
  double secondsSinceEpoch(const ros::Time& stamp);

  const ContactEstimator& estimator() const { return estimator_; }
  const std::string& groundFrame() const { return ground_frame_; }
  const std::string& contactFrame() const { return contact_frame_; }

  /// Where orientations came from, and what was skipped, since construction.
  struct Counters
  {
    std::uint64_t tf_at_stamp = 0, tf_latest = 0, from_odometry = 0, no_orientation = 0, rejected = 0,
                  time_jumps = 0;
    std::uint64_t bad_covariance = 0;  ///< twist covariances marked unknown or invalid (the estimate goes on without)
    std::uint64_t tf_stale = 0;        ///< messages whose only transform was older than tf_max_age (not used)
    std::uint64_t dropped = 0;         ///< messages missing in the publishers' header.seq
    std::uint64_t out_of_order = 0;    ///< stamps within stamp_tolerance before the last: answered without a reset
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

  // messages missing before this one from this publisher (0 for the first of a publisher, a restart or a loop)
  std::uint32_t sequenceGap(const std::string& publisher, std::uint32_t seq);

  ContactEstimator estimator_;
  std::string ground_frame_, contact_frame_;
  bool publish_tf_ = true;
  double tf_max_age_ = 0.5;
  bool tf_stale_ = false;  // this message found only a transform older than tf_max_age_
  struct Sequence
  {
    std::string publisher;
    std::uint32_t last = 0;
    std::uint64_t used = 0;  // when it was last seen (a message count): the oldest is replaced
  };
  std::array<Sequence, 8> sequences_;  // a few publishers on one topic; a ninth replaces the longest unseen
  int n_sequences_ = 0;
  std::uint64_t messages_ = 0;
  ros::Time last_transform_stamp_;  // one contact transform per stamp: no TF_REPEATED_DATA
  ros::Time epoch_;                 // the core's time 0 (secondsSinceEpoch)
  bool have_epoch_ = false;
  EstimateOutputs out_;
  Counters counters_;
  std::string last_tf_error_;
  const char* last_covariance_problem_ = nullptr;
};

}  // namespace sphere_contact_estimator
