#pragma once

// STL
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

// Boost
#include <boost/thread/recursive_mutex.hpp>

// ROS
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

// Eigen
#include <Eigen/Geometry>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"
#include "sphere_contact_estimator/core/estimator/run_summary.h"
#include "sphere_contact_estimator/ros/message_pool.h"
#include "sphere_contact_estimator/ros/odometry_estimator.h"

namespace sphere_contact_estimator
{
/// The ROS side of the contact estimator, shared by the node and the nodelet: subscriptions, tf,
/// dynamic_reconfigure, diagnostics and publishers around a core ContactEstimator.
///
/// Topics (relative to the node handle, remappable): subscribes `odom` (nav_msgs/Odometry); publishes
/// `contact_estimate`, `brush_wrench`, `rolling_resistance_wrench`, `contact_markers` (only while
/// subscribed) and /diagnostics; broadcasts the contact frame on tf.
///
/// The diagnostics run on their own callback queue and thread, and read only a snapshot of the counters that each
/// update leaves under a lock of its own: they never wait for an update, however long it takes.
class ContactEstimatorRos
{
public:
  /// @param nh topics; @param pnh private parameters and the reconfigure server
  ContactEstimatorRos(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Stops the callbacks first, waiting for any that runs (a nodelet unloaded from a multi-threaded manager).
  ~ContactEstimatorRos();
  ContactEstimatorRos(const ContactEstimatorRos&) = delete;
  ContactEstimatorRos& operator=(const ContactEstimatorRos&) = delete;

private:
  void odometryCallback(const ros::MessageEvent<nav_msgs::Odometry const>& event);
  void process(const nav_msgs::Odometry& msg, const std::string& publisher);  // the callback's work, under mutex_
  // what the diagnostics read, copied after each update and configuration (under stats_mutex_)
  void snapshot();
  void reconfigureCallback(ContactEstimatorConfig& config, uint32_t level);
  void publishMarkers(const ContactEstimateData& estimate, const std_msgs::Header& header);
  /// Copies the message into one from the pool (no allocation once its strings have their capacity) and
  /// publishes that by pointer; skipped without subscribers.
  template <class M>
  static void publish(ros::Publisher& publisher, MessagePool<M>& pool, const M& message)
  {
    if (publisher.getNumSubscribers() == 0)
      return;
    const boost::shared_ptr<M> m = pool.acquire();
    *m = message;
    publisher.publish(boost::shared_ptr<const M>(m));
  }
  void diagnoseInput(diagnostic_updater::DiagnosticStatusWrapper& status);
  void diagnoseTf(diagnostic_updater::DiagnosticStatusWrapper& status);
  void diagnoseModels(diagnostic_updater::DiagnosticStatusWrapper& status);
  void diagnoseUncertainty(diagnostic_updater::DiagnosticStatusWrapper& status);

  // **** ROS-related
  ros::NodeHandle nh_, pnh_;
  ros::Subscriber odom_sub_;
  ros::Publisher estimate_pub_, brush_wrench_pub_, rr_wrench_pub_, marker_pub_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ContactEstimatorConfig>> reconfigure_server_;
  // the diagnostics' own queue and thread (a long update never delays them)
  ros::CallbackQueue diagnostics_queue_;
  ros::NodeHandle diagnostics_nh_;
  diagnostic_updater::Updater updater_;
  ros::WallTimer diagnostics_timer_;  // wall time: diagnostics (stale input) go on when sim time stops
  std::unique_ptr<ros::AsyncSpinner> diagnostics_spinner_;

  // **** parameters and state, shared by the odometry and reconfigure callbacks (which run concurrently in a
  // multi-threaded nodelet manager): guarded by mutex_
  std::mutex mutex_;
  OdometryEstimator estimator_;    // the same class bag_analyze runs
  ContactEstimatorConfig config_;  // the accepted configuration
  bool configured_ = false;        // whether config_ is one the server gave (the first is logged whole)
  double stale_timeout_ = 1.0;
  visualization_msgs::MarkerArray markers_;  // reused so the hot path does not allocate it
  MessagePool<ContactEstimate> estimate_pool_;
  MessagePool<geometry_msgs::WrenchStamped> brush_wrench_pool_, rr_wrench_pool_;

  // **** what the diagnostics read: guarded by stats_mutex_, never held during an update
  std::mutex stats_mutex_;
  OdometryEstimator::Counters counters_;  // the estimator's, copied after each message
  std::string ground_frame_, last_tf_error_;
  std::string rejected_at_start_;  // why the start-up configuration was rejected (empty once one is accepted)
  const char* last_covariance_problem_ = nullptr;
  double uncertainty_warning_ = 0.0;
  std::uint64_t reported_dropped_ = 0, reported_out_of_order_ = 0, reported_tf_stale_ = 0;
  std::uint64_t reported_tf_ = 0, reported_from_odometry_ = 0;  // tf (at the stamp or latest) and odometry, at the last report
  std::uint64_t received_ = 0, published_ = 0;
  std::uint64_t window_received_ = 0;
  std::uint64_t reported_rejected_ = 0, reported_time_jumps_ = 0, reported_no_orientation_ = 0;  // at the last report
  ros::WallTime window_start_;
  ros::WallTime last_received_;  // staleness is measured on the wall clock
  double compute_sum_ = 0.0, compute_max_ = 0.0;
  std::uint64_t compute_count_ = 0;
  std::uint32_t last_brush_flags_ = 0, last_rr_flags_ = 0, last_flags_ = 0;
  std::uint8_t last_regime_ = 0;
  bool have_estimate_ = false;
  // the forces' propagated spread since the last report (a fraction of mu F_z), and the statuses seen
  double spread_max_ = 0.0, last_spread_ = 0.0;
  std::uint64_t over_spread_ = 0, reported_bad_covariance_ = 0;
  std::uint64_t within_noise_ = 0, since_report_ = 0;  // estimates flagged kMotionWithinNoise, and all, since the last report
  std::uint64_t not_rolling_ = 0;  // estimates flagged kNotRolling since the last report
  AccuracyMisses accuracy_missed_;  // since the last report
  // models that threw (ContactEstimator::faults) and messages whose processing threw elsewhere, in all and at the last
  // report, and what the last one said
  std::uint64_t faults_ = 0, reported_faults_ = 0;
  std::string last_fault_;
  double last_motion_to_noise_ = -1.0;
  CovarianceStatus last_covariance_status_ = CovarianceStatus::Disabled;
};

}  // namespace sphere_contact_estimator
