#pragma once

// STL
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

// Package
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/core/estimator/run_summary.h"

namespace sphere_contact_estimator
{
struct BagAnalysisOptions
{
  std::string input;                ///< bag to read
  std::string output;               ///< bag to write (empty: none): the estimate topics and the copied input
  std::string csv;                  ///< CSV of every estimate (empty: none)
  std::string odom_topic;           ///< empty: the bag's only nav_msgs/Odometry topic
  std::vector<std::string> topics;  ///< input topics to copy into the output; empty: all
  bool copy_input = true;           ///< false: the output holds the estimate topics only
  double start = 0.0;               ///< from this many seconds after the bag's first message
  double end = std::numeric_limits<double>::infinity();  ///< up to this many seconds after it
  ContactEstimatorConfig config = ContactEstimatorConfig::__getDefault__();
  std::string config_source;        ///< where config came from (the parameter file, overrides), for the record
};

struct BagAnalysisResult
{
  std::string odom_topic;
  std::uint64_t odometry = 0;       ///< odometry messages read
  std::uint64_t estimates = 0;      ///< estimates written
  std::uint64_t no_orientation = 0, rejected = 0;  ///< skipped, by reason
  std::uint64_t dropped = 0;        ///< missing before the recording: gaps in the odometry's header.seq
  std::uint64_t out_of_order = 0;   ///< stamps within stamp_tolerance before the last: answered without a reset
  std::uint64_t tf_stale = 0;       ///< the bag's latest transform older than tf_max_age: odometry orientation used
  std::uint64_t copied = 0;         ///< input messages copied to the output
  std::vector<std::string> replaced_topics;  ///< input topics the estimates replace (a bag recorded live)
  double bag_seconds = 0.0;         ///< span of the bag time analysed [s]
  double compute_seconds = 0.0;     ///< wall time in the estimator's update() (the models, their uncertainty) [s]
  RunSummary summary;
  /// Where the bag's own record disagrees with config: estimates made live with another load or patch radius, or a
  /// recorded configuration with another rolling radius (these analyses would then be of another robot).
  std::vector<std::string> warnings;
};

/// Replays a bag through the node's OdometryEstimator as fast as the machine allows, with the transforms in
/// the bag's /tf and /tf_static. The output bag has the node's topic names (/contact_estimate, /brush_wrench,
/// /rolling_resistance_wrench, and the contact frame on /tf), each at its odometry message's bag time, beside
/// the input topics, and the configuration it ran with (dynamic_reconfigure/Config on
/// /contact_estimator/parameter_updates at the start, as the live node's server publishes it; in the CSV, as comment
/// lines before the header). progress(fraction) is called now and then. Throws std::runtime_error with a message for
/// people (a bag that cannot be read, no odometry topic, an invalid configuration).
BagAnalysisResult analyzeBag(const BagAnalysisOptions& options, const std::function<void(double)>& progress = {});

}  // namespace sphere_contact_estimator
