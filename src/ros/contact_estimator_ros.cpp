#include "sphere_contact_estimator/ros/contact_estimator_ros.h"

// STL
#include <algorithm>
#include <cmath>
#include <cstdio>

// Package
#include "sphere_contact_estimator/ros/config_report.h"
#include "sphere_contact_estimator/ros/contact_markers.h"
#include "sphere_contact_estimator/ros/parameter_text.h"

namespace sphere_contact_estimator
{
ContactEstimatorRos::ContactEstimatorRos(ros::NodeHandle nh, ros::NodeHandle pnh)
  : nh_(nh)
  , pnh_(pnh)
  , tf_listener_(tf_buffer_)
  , diagnostics_nh_([&] {
    ros::NodeHandle h(nh);
    h.setCallbackQueue(&diagnostics_queue_);
    return h;
  }())
  , updater_(diagnostics_nh_, pnh, pnh.getNamespace())
  , estimator_(ContactEstimatorConfig::__getDefault__())
  , config_(ContactEstimatorConfig::__getDefault__())
{
  // Queues as deep as the input's, so that a burst in is a burst out, not a loss (bounded all the same).
  const int queue_size = std::max(1, pnh_.param("queue_size", 1000));
  estimate_pub_ = nh_.advertise<ContactEstimate>("contact_estimate", queue_size);
  brush_wrench_pub_ = nh_.advertise<geometry_msgs::WrenchStamped>("brush_wrench", queue_size);
  rr_wrench_pub_ = nh_.advertise<geometry_msgs::WrenchStamped>("rolling_resistance_wrench", queue_size);
  marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("contact_markers", 2);  // best effort

  updater_.setHardwareID("sphere_contact_estimator");
  updater_.add("odometry input", this, &ContactEstimatorRos::diagnoseInput);
  updater_.add("tf", this, &ContactEstimatorRos::diagnoseTf);
  updater_.add("contact models", this, &ContactEstimatorRos::diagnoseModels);
  updater_.add("uncertainty", this, &ContactEstimatorRos::diagnoseUncertainty);
  window_start_ = ros::WallTime::now();

  // Numbers that YAML 1.1 read as text, enum names, values out of range: the server would drop or clamp them in
  // silence.
  bool all_repaired = true;
  for (const std::string& line : repairTextParameters(pnh_, all_repaired))
  {
    if (line.find(kParameterIgnored) == std::string::npos)
      ROS_WARN_STREAM("contact estimator: parameter " << line);  // read as meant
    else
      ROS_ERROR_STREAM("contact estimator: parameter " << line);
  }
  // A parameter of no such name (a typo in a YAML, a parameter of another node) would be ignored without a word.
  {
    const std::vector<std::string> start_up{ "queue_size", "diagnostic_period" };
    std::vector<std::string> names;
    ros::param::getParamNames(names);
    const std::string prefix = pnh_.getNamespace() + "/";
    std::vector<std::string> unknown;
    for (const std::string& full : names)
    {
      if (full.compare(0, prefix.size(), prefix) != 0)
        continue;
      const std::string name = full.substr(prefix.size(), full.find('/', prefix.size()) - prefix.size());
      if (!isKnownParameter(name, start_up) && std::find(unknown.begin(), unknown.end(), name) == unknown.end())
        unknown.push_back(name);
    }
    for (const std::string& name : unknown)
    {
      const std::string nearest = nearestParameter(name, start_up);
      ROS_WARN_STREAM("contact estimator: unknown parameter " << prefix << name << " ignored"
                                                              << (nearest.empty() ? std::string(" (cfg/ContactEstimator.cfg lists them)")
                                                                                  : "; did you mean " + nearest + "?"));
    }
  }
  // The server reads the private parameters (config/contact_estimator.yaml) and calls back once now.
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<ContactEstimatorConfig>>(reconfigure_mutex_, pnh_);
  reconfigure_server_->setCallback(
      [this](ContactEstimatorConfig& config, uint32_t level) { reconfigureCallback(config, level); });

  // A bounded queue deep enough for bursts (a bag, a driver catching up): older messages are dropped beyond it.
  odom_sub_ = nh_.subscribe("odom", queue_size, &ContactEstimatorRos::odometryCallback, this,
                            ros::TransportHints().tcpNoDelay());
  // force_update: Updater::update() waits for ros::Time to pass its period, which a paused /clock never does. On the
  // diagnostics' own queue and thread: a long update (or a busy single-threaded node) never holds them up.
  diagnostics_timer_ =
      diagnostics_nh_.createWallTimer(ros::WallDuration(0.25), [this](const ros::WallTimerEvent&) { updater_.force_update(); });
  diagnostics_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &diagnostics_queue_);
  diagnostics_spinner_->start();
  ROS_INFO_STREAM("contact estimator: listening on " << odom_sub_.getTopic() << ", publishing "
                                                     << estimate_pub_.getTopic());
}

ContactEstimatorRos::~ContactEstimatorRos()
{
  // Members go in reverse order of declaration: the state would go before the subscriber, timer and server
  // whose callbacks use it, while a worker thread may be inside one (ThreadSanitizer found it). roscpp's
  // shutdown and stop wait for a running callback to return.
  odom_sub_.shutdown();
  diagnostics_timer_.stop();
  diagnostics_spinner_->stop();  // joins its thread
  reconfigure_server_.reset();
}

void ContactEstimatorRos::reconfigureCallback(ContactEstimatorConfig& config, uint32_t /*level*/)
{
  std::lock_guard<std::mutex> lock(mutex_);
  const std::vector<ParameterChange> changes = configurationChanges(config_, config);
  try
  {
    estimator_.configure(config);
  }
  catch (const std::exception& e)
  {
    // At start-up "the previous one" is the .cfg's defaults: none of the user's parameters is in force, which the
    // diagnostics then say as an ERROR until a configuration is accepted (a line scrolled past in roslaunch's output
    // was all a user had)
    const bool at_start = !configured_;
    ROS_ERROR_STREAM("contact estimator: configuration rejected ("
                     << describeChanges(changes) << "): " << e.what()
                     << (at_start ? "; at start-up: none of the parameters is in force, the defaults of "
                                    "cfg/ContactEstimator.cfg are, until a configuration is accepted"
                                  : "; the previous one stays in force"));
    if (at_start)
    {
      std::lock_guard<std::mutex> stats(stats_mutex_);
      rejected_at_start_ = e.what();
    }
    config = config_;  // the server publishes what is in force
    return;
  }
  const bool first = !configured_;
  configured_ = true;
  config_ = config;
  {
    std::lock_guard<std::mutex> stats(stats_mutex_);
    rejected_at_start_.clear();
    stale_timeout_ = config.stale_timeout;
    uncertainty_warning_ = config.uncertainty_warning;
    ground_frame_ = estimator_.groundFrame();
  }
  // what is in force, by name: whole at start-up, then what changed
  const EstimatorSettings& s = estimator_.estimator().settings();
  char derived[160];
  std::snprintf(derived, sizeof derived, "R_r = %.4g m, F_z = %.4g N, a = %.4g m, mu F_z = %.4g N", s.rolling_radius,
                s.verticalLoad(), s.brushParameters().a, s.brushParameters().mu * s.verticalLoad());
  if (first)
    ROS_INFO_STREAM("contact estimator: configuration (" << derived << "): " << configurationText(config));
  else if (!changes.empty())
    ROS_INFO_STREAM("contact estimator: reconfigured: " << describeChanges(changes) << " (" << derived << ")");
  // the server clamps a value outside the .cfg's range to its end before the node sees it
  for (const ParameterChange& c : changes)
    if (c.at_bound)
      ROS_WARN_STREAM("contact estimator: " << c.name << " is now " << c.after
                                            << ", an end of its range in cfg/ContactEstimator.cfg: dynamic_reconfigure sets "
                                               "a value outside the range to the range's end, so a value beyond it "
                                               "was set to this one");
}

void ContactEstimatorRos::odometryCallback(const ros::MessageEvent<nav_msgs::Odometry const>& event)
{
  const nav_msgs::Odometry& msg = *event.getConstMessage();
  {
    std::lock_guard<std::mutex> stats(stats_mutex_);
    ++received_;
    ++window_received_;
    last_received_ = ros::WallTime::now();  // wall time: a paused /clock must not freeze the age
  }
  std::lock_guard<std::mutex> lock(mutex_);
  // An exception here is a defect (the models' own are caught by the estimator, which flags the estimate): logged and
  // counted, the message unanswered, instead of ending the node (or, in a nodelet manager, every nodelet in it).
  try
  {
    process(msg, event.getPublisherName());
  }
  catch (const std::exception& error)
  {
    ROS_ERROR_THROTTLE(5.0, "contact estimator: processing an odometry message failed: %s (a defect: please report it "
                            "with the bag); message unanswered",
                       error.what());
    std::lock_guard<std::mutex> stats(stats_mutex_);
    ++faults_;
    last_fault_ = std::string("processing a message threw: ") + error.what();
  }
}

void ContactEstimatorRos::process(const nav_msgs::Odometry& msg, const std::string& publisher)
{
  SkipReason reason;
  // the publisher's name: header.seq counts per publisher (a gap is a lost message)
  const EstimateOutputs* out = estimator_.process(msg, tf_buffer_, reason, publisher);
  if (!out)
  {
    if (reason == SkipReason::NoOrientation)
      ROS_WARN_THROTTLE(5.0, "contact estimator: no rotation from '%s' to the ground frame '%s' (tf: %s) and no "
                             "valid odometry orientation; message skipped",
                        msg.child_frame_id.c_str(),
                        (estimator_.groundFrame().empty() ? msg.header.frame_id : estimator_.groundFrame()).c_str(),
                        estimator_.lastTfError().c_str());
    else
      ROS_WARN_THROTTLE(5.0, "contact estimator: odometry with a non-finite or impossible twist or stamp skipped");
    snapshot();
    return;
  }
  const ContactEstimateData& e = *out->data;
  if (e.flags & estimate_flags::kTimeJumpReset)
    ROS_WARN("contact estimator: time went backwards (a looping bag?): state reset");
  if (out->estimate.flags & ContactEstimate::FLAG_TF_STALE)
    ROS_WARN_THROTTLE(5.0, "contact estimator: %s: using the odometry's own orientation", estimator_.lastTfError().c_str());
  if (e.flags & estimate_flags::kNotRolling)
    ROS_WARN_THROTTLE(10.0, "contact estimator: the centre has moved at %.2f m/s for over %.0f s while the shell does not "
                            "roll (V_r %.2f m/s): is twist.angular the body's yaw rate? It must be the angular velocity "
                            "of the sphere's shell (README: Your robot)",
                      std::hypot(msg.twist.twist.linear.x, msg.twist.twist.linear.y), kNotRollingTime, e.rolling_speed);
  const ContactEstimator& core = estimator_.estimator();
  const bool faulted = e.modelFault();
  if (faulted)
    ROS_ERROR_THROTTLE(5.0, "contact estimator: %s, the message stamped %u.%09u (a defect: please report it with the "
                            "bag); the estimate is published invalid with BRUSH_FLAG_MODEL_FAULT / FLAG_MODEL_FAULT, the "
                            "model's state reset",
                       core.lastFault().c_str(), msg.header.stamp.sec, msg.header.stamp.nsec);
  if (out->estimate.messages_dropped > 0)
    ROS_WARN_THROTTLE(5.0, "contact estimator: %u odometry messages missing before this one (a gap in header.seq: the "
                           "queue overflowed, or the source lost them)",
                      out->estimate.messages_dropped);

  // by shared pointer: a subscriber in the same nodelet manager gets the message without a copy
  publish(estimate_pub_, estimate_pool_, out->estimate);
  publish(brush_wrench_pub_, brush_wrench_pool_, out->brush_wrench);
  publish(rr_wrench_pub_, rr_wrench_pool_, out->rolling_resistance_wrench);
  if (out->has_transform)
    tf_broadcaster_.sendTransform(out->contact_transform);
  if (marker_pub_.getNumSubscribers() > 0)
    publishMarkers(e, out->estimate.header);

  std::lock_guard<std::mutex> stats(stats_mutex_);
  ++published_;
  compute_sum_ += e.compute_time;
  compute_max_ = std::max(compute_max_, e.compute_time);
  ++compute_count_;
  last_brush_flags_ = e.brush.flags;
  last_rr_flags_ = e.rolling_resistance.flags;
  last_regime_ = static_cast<std::uint8_t>(e.rolling_resistance.regime);
  last_flags_ = out->estimate.flags;
  last_motion_to_noise_ = e.motion_to_noise;
  within_noise_ += (e.flags & estimate_flags::kMotionWithinNoise) != 0;
  not_rolling_ += (e.flags & estimate_flags::kNotRolling) != 0;
  accuracy_missed_.add(e);
  ++since_report_;
  have_estimate_ = true;
  last_covariance_status_ = e.covariance.status;
  last_spread_ = e.covariance.brush_method == CovarianceMethod::None ? 0.0 : e.covariance.brush_spread;
  spread_max_ = std::max(spread_max_, last_spread_);
  if (uncertainty_warning_ > 0.0 && last_spread_ > uncertainty_warning_)
    ++over_spread_;
  counters_ = estimator_.counters();
  if (last_tf_error_ != estimator_.lastTfError())
    last_tf_error_.assign(estimator_.lastTfError());  // into its capacity: no allocation once sized
  last_covariance_problem_ = estimator_.lastCovarianceProblem();
  if (faulted)
  {
    ++faults_;
    last_fault_ = core.lastFault();
  }
}

void ContactEstimatorRos::snapshot()
{
  std::lock_guard<std::mutex> stats(stats_mutex_);
  counters_ = estimator_.counters();
  if (last_tf_error_ != estimator_.lastTfError())
    last_tf_error_.assign(estimator_.lastTfError());
  last_covariance_problem_ = estimator_.lastCovarianceProblem();
}

void ContactEstimatorRos::publishMarkers(const ContactEstimateData& e, const std_msgs::Header& header)
{
  fillContactMarkers(e, estimator_.estimator(), header, 0.5, markers_);
  marker_pub_.publish(markers_);
}

void ContactEstimatorRos::diagnoseInput(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(stats_mutex_);
  const ros::WallTime now = ros::WallTime::now();
  const double window = (now - window_start_).toSec();
  const double rate = window > 0.0 ? window_received_ / window : 0.0;
  window_start_ = now;
  window_received_ = 0;
  status.add("rate [Hz]", rate);
  status.add("received", received_);
  status.add("published", published_);
  const OdometryEstimator::Counters& c = counters_;
  status.add("dropped (gaps in header.seq)", c.dropped);
  status.add("rejected (non-finite or impossible)", c.rejected);
  status.add("time jumps backwards", c.time_jumps);
  status.add("stamps out of order within stamp_tolerance", c.out_of_order);
  const double age = received_ ? (now - last_received_).toSec() : -1.0;
  status.add("age of last message [s]", age);
  if (compute_count_)
  {
    status.add("compute time mean [s]", compute_sum_ / compute_count_);
    status.add("compute time max [s]", compute_max_);
  }
  // what went wrong since the last report, all of it
  std::string problems;
  const auto note = [&problems](const std::string& text) { problems += (problems.empty() ? "" : "; ") + text; };
  if (!received_)
    note("no odometry received yet");
  else if (stale_timeout_ > 0.0 && age > stale_timeout_)
    note("stale input: no odometry for " + std::to_string(age) + " s");
  if (c.rejected > reported_rejected_)
    note(std::to_string(c.rejected - reported_rejected_) + " odometry messages rejected (non-finite twist)");
  if (c.time_jumps > reported_time_jumps_)
    note("time went backwards: state reset");
  if (c.dropped > reported_dropped_)
    note(std::to_string(c.dropped - reported_dropped_) +
         " odometry messages dropped (gaps in header.seq: the queue overflowed, or the source lost them)");
  if (not_rolling_ > 0)
    note(std::to_string(not_rolling_) + " estimates with the centre moving while the shell does not roll (for over " +
         std::to_string(static_cast<int>(kNotRollingTime)) + " s): twist.angular must be the shell's angular velocity, " +
         "not the body's yaw rate");
  status.add("centre moving, shell not rolling (since the last report)", not_rolling_);
  not_rolling_ = 0;
  reported_rejected_ = c.rejected;
  reported_time_jumps_ = c.time_jumps;
  reported_dropped_ = c.dropped;
  reported_out_of_order_ = c.out_of_order;
  if (problems.empty())
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "receiving odometry");
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, problems);
}

void ContactEstimatorRos::diagnoseTf(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(stats_mutex_);
  const OdometryEstimator::Counters& c = counters_;
  status.add("ground frame", ground_frame_.empty() ? std::string("(the odometry's frame)") : ground_frame_);
  status.add("tf at the stamp", c.tf_at_stamp);
  status.add("tf latest", c.tf_latest);
  status.add("tf older than tf_max_age (not used)", c.tf_stale);
  status.add("odometry orientation", c.from_odometry);
  status.add("skipped: no orientation", c.no_orientation);
  status.add("last tf error", last_tf_error_);
  // since the last report, not over all time: a transform that stopped shows at once
  const std::uint64_t tf = c.tf_at_stamp + c.tf_latest - reported_tf_, odometry = c.from_odometry - reported_from_odometry_,
                      stale = c.tf_stale - reported_tf_stale_, skipped = c.no_orientation - reported_no_orientation_;
  if (skipped > 0)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "%lu messages skipped: no tf to the ground frame and no valid odometry orientation",
                    static_cast<unsigned long>(skipped));
  else if (stale > 0)
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "tf stale in %lu messages (%s): the odometry's orientation was used", static_cast<unsigned long>(stale),
                    last_tf_error_.c_str());
  else if (odometry > 0 && tf == 0 && !ground_frame_.empty())
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "no tf to the ground frame '%s' (%s): using the odometry's orientation", ground_frame_.c_str(),
                    last_tf_error_.c_str());
  else if (odometry > 0 && tf == 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "no tf: using the odometry's orientation");
  else if (tf > 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "tf available");
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "no odometry since the last report");
  reported_no_orientation_ = c.no_orientation;
  reported_tf_ = c.tf_at_stamp + c.tf_latest;
  reported_from_odometry_ = c.from_odometry;
  reported_tf_stale_ = c.tf_stale;
}

void ContactEstimatorRos::diagnoseModels(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(stats_mutex_);
  if (!rejected_at_start_.empty())
  {
    // the models run on the defaults, not on the robot's parameters: that first, whatever else holds
    status.add("parameters rejected at start-up", rejected_at_start_);
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR,
                   "the parameters were rejected at start-up, the defaults are in force: " + rejected_at_start_);
    accuracy_missed_ = {};
    within_noise_ = 0;
    since_report_ = 0;
    return;
  }
  if (!have_estimate_ && faults_ == reported_faults_)
  {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "no estimate yet");
    return;
  }
  std::string problems;
  const auto note = [&problems](bool condition, const char* text) {
    if (condition)
      problems += problems.empty() ? text : std::string("; ") + text;
  };
  note(last_rr_flags_ & cylinder_flags::kUnderdamped, "underdamped surface (eq. 2)");
  note(last_regime_ == static_cast<std::uint8_t>(CylinderRegime::PointContact), "point-contact regime (past v_c)");
  note(last_rr_flags_ & cylinder_flags::kNoSteadyState, "no steady rolling state");
  note(last_brush_flags_ & brush_flags::kNoSteadyStateTilt, "|R_gamma| < a: no steady state");
  note(last_brush_flags_ & brush_flags::kStandstill, "standstill: steady brush model undefined");
  note(last_brush_flags_ & brush_flags::kLinearSaturated, "linear brush model saturated");
  status.add("model faults (in all)", faults_);
  status.add("brush flags", last_brush_flags_);
  status.add("rolling-resistance flags", last_rr_flags_);
  status.add("estimate flags", last_flags_);
  status.add("standstill", static_cast<bool>(last_flags_ & estimate_flags::kStandstill));
  status.add("motion within noise (parked)", static_cast<bool>(last_flags_ & estimate_flags::kMotionWithinNoise));
  status.add("motion / noise, last [-]", last_motion_to_noise_);
  status.add("estimates within noise since the last report", std::to_string(within_noise_) + " of " + std::to_string(since_report_));
  // a parked robot is no problem, but its forces are the bristles' answer to the odometry's noise, not measured sliding
  std::string notes;  // said at any level
  if (within_noise_ > 0)
    notes = "parked: the motion is within the odometry's declared noise in " + std::to_string(within_noise_) + " of " +
            std::to_string(since_report_) + " estimates (their brush forces are the response to that noise)";
  // the budget's best answer, flagged, with its estimate: not a fault, but the operator asked for more (work_budget,
  // accuracy_target); said beside "models valid" so that a spin in place, whose estimate stays well above its error,
  // does not hold a WARN for as long as it lasts
  status.add("accuracy target missed since the last report", std::to_string(accuracy_missed_.count) + " of " +
                                                                 std::to_string(since_report_));
  status.add("largest error estimate / target since the last report", accuracy_missed_.worst);
  if (accuracy_missed_.count > 0)
  {
    char worst[32];
    std::snprintf(worst, sizeof worst, "%.3g", accuracy_missed_.worst);
    std::string text = "accuracy target missed in " + std::to_string(accuracy_missed_.count) + " of " +
                       std::to_string(since_report_) + " estimates (error estimate up to " + worst +
                       " times the target: BRUSH_FLAG_ACCURACY_NOT_MET)";
    const auto reasons = accuracy_missed_.reasons();  // (worded as bag_analyze's summary words them)
    for (std::size_t i = 0; i < reasons.size(); ++i)
      if (reasons[i].count > 0)
        text += std::string(i == 0 ? ", of them " : ", ") + reasons[i].what + " in " +
                std::to_string(reasons[i].count) + reasons[i].hint;
    notes = notes.empty() ? text : notes + "; " + text;
  }
  accuracy_missed_ = {};
  within_noise_ = 0;
  since_report_ = 0;
  if (faults_ > reported_faults_)
  {
    // a defect: ERROR whatever else holds, until a report without a new one
    const std::string text = std::to_string(faults_ - reported_faults_) + " estimates without forces since the last " +
                             "report: a model failed (" + last_fault_ + "; please report it with the bag)";
    reported_faults_ = faults_;
    status.add("last fault", last_fault_);
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, problems.empty() ? text : text + "; " + problems);
    return;
  }
  if (problems.empty())
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, notes.empty() ? "models valid" : "models valid; " + notes);
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, notes.empty() ? problems : problems + "; " + notes);
}

void ContactEstimatorRos::diagnoseUncertainty(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  // how far the odometry's own uncertainty moves the forces: past uncertainty_warning of mu F_z an estimate is of
  // little use to a controller
  std::lock_guard<std::mutex> lock(stats_mutex_);
  const OdometryEstimator::Counters& c = counters_;
  status.add("covariance status", toString(last_covariance_status_));
  status.add("force spread, last [fraction of mu F_z]", last_spread_);
  status.add("force spread, largest since the last report", spread_max_);
  status.add("warning above", uncertainty_warning_);
  status.add("unusable twist covariances", c.bad_covariance);
  const char* problem = last_covariance_problem_;
  status.add("last covariance problem", problem ? problem : "");
  std::string problems;
  const auto note = [&problems](const std::string& text) { problems += (problems.empty() ? "" : "; ") + text; };
  if (over_spread_ > 0)
    note(std::to_string(over_spread_) + " estimates with a force spread above " +
         std::to_string(uncertainty_warning_) + " of mu F_z (largest " + std::to_string(spread_max_) + ")");
  if (c.bad_covariance > reported_bad_covariance_)
    note(std::to_string(c.bad_covariance - reported_bad_covariance_) + " twist covariances unusable (" +
         (problem ? problem : "?") + "): estimates without uncertainty");
  reported_bad_covariance_ = c.bad_covariance;
  over_spread_ = 0;
  spread_max_ = 0.0;
  if (!problems.empty())
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, problems);
  else if (!have_estimate_)
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "no estimate yet");
  else if (last_covariance_status_ == CovarianceStatus::Disabled)
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "propagation off");
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "forces' spread within the warning level");
}

}  // namespace sphere_contact_estimator
