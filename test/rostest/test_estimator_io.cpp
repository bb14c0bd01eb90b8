// Integration tests of contact_estimator_node over roscpp: one output per input with its stamp, values
// equal to the core library's, dynamic_reconfigure, bad input and missing tf.

// STL
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <vector>

// Eigen
#include <Eigen/Geometry>

// GTest
#include <gtest/gtest.h>

// ROS
#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/client.h>
#include <nav_msgs/Odometry.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>
#include <ros/ros.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"
#include "sphere_contact_estimator/ros/config_settings.h"
#include "sphere_contact_estimator/ros/contact_markers.h"
#include "sphere_contact_estimator/ros/parameter_text.h"
#include "wait_for.h"

namespace sce = sphere_contact_estimator;

namespace
{
const std::string kNode = "/contact_estimator";
double g_clock = 1000.0;  // stamps increase across tests; each test starts after a gap (> max_step)
// The node's clock counts from the first stamp it is given (OdometryEstimator::secondsSinceEpoch): main() sends it one
// message at this stamp before the tests, so that the core below can be given the same times.
const ros::Time kEpoch(500.0);

class EstimatorIo : public ::testing::Test
{
protected:
  void SetUp() override
  {
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("odom", 1000);
    estimate_sub_ = nh_.subscribe<sce::ContactEstimate>("contact_estimate", 1000, [this](const sce::ContactEstimate::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      estimates_.push_back(*m);
    });
    diag_sub_ = nh_.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 100, [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& s : m->status)
        diagnostics_[s.name] = s;
      ++diagnostics_count_;
    });
    ASSERT_TRUE(waitFor([this] { return odom_pub_.getNumSubscribers() > 0 && estimate_sub_.getNumPublishers() > 0; }, 20.0));
    client_ = std::make_unique<dynamic_reconfigure::Client<sce::ContactEstimatorConfig>>(kNode);
    ASSERT_TRUE(client_->getCurrentConfiguration(config_, ros::Duration(10.0)));
    g_clock += 10.0;
  }

  // Callbacks run on the AsyncSpinner of main(); the predicate is checked under the same lock.
  bool waitFor(const std::function<bool()>& done, double seconds) { return sce::test::waitFor(mutex_, done, seconds); }

  // Rolling at v along yaw with the body frame yawed along the path; the centre slides by (along, left).
  static nav_msgs::Odometry odometry(double stamp, double v, double yaw, double along, double left, double omega_z)
  {
    nav_msgs::Odometry o;
    o.header.stamp = ros::Time(stamp);
    o.header.frame_id = "odom";
    o.child_frame_id = "base_link";
    o.pose.pose.orientation.z = std::sin(0.5 * yaw);
    o.pose.pose.orientation.w = std::cos(0.5 * yaw);
    o.twist.twist.angular.y = v / 0.1;  // rolling radius of config/contact_estimator.yaml
    o.twist.twist.angular.z = omega_z;
    o.twist.twist.linear.x = v + along;
    o.twist.twist.linear.y = left;
    return o;
  }

  // What the node computes from it, by the core (ground frame = the odometry's, orientation from the pose).
  static sce::EstimatorInput input(const nav_msgs::Odometry& o)
  {
    const auto& q = o.pose.pose.orientation;
    const Eigen::Quaterniond r = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized();
    sce::EstimatorInput in;
    in.stamp = (o.header.stamp - kEpoch).toSec();
    in.omega = r * Eigen::Vector3d(o.twist.twist.angular.x, o.twist.twist.angular.y, o.twist.twist.angular.z);
    in.v_contact = r * Eigen::Vector3d(o.twist.twist.linear.x, o.twist.twist.linear.y, o.twist.twist.linear.z);
    return in;
  }

  bool reconfigure(const std::function<void(sce::ContactEstimatorConfig&)>& change)
  {
    sce::ContactEstimatorConfig c = config_;
    change(c);
    if (!client_->setConfiguration(c))
      return false;
    return client_->getCurrentConfiguration(config_, ros::Duration(5.0));
  }

  const sce::ContactEstimate* estimateAt(const ros::Time& stamp)
  {
    for (const auto& e : estimates_)
      if (e.header.stamp == stamp)
        return &e;
    return nullptr;
  }

  std::mutex mutex_;  // guards what the callbacks fill
  ros::NodeHandle nh_;
  ros::Publisher odom_pub_;
  std::vector<sce::ContactEstimate> estimates_;
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> diagnostics_;
  int diagnostics_count_ = 0;  // reports received
  // After what their callbacks fill, so that they are shut down first (members go in reverse order; a subscriber's
  // shutdown waits for its callback in progress). Declared before, a diagnostics report or a late estimate that
  // arrived while a test's fixture was torn down wrote into the destroyed map or vector on the spinner's thread:
  // "free(): corrupted unsorted chunks", and the binary died without results (once in CI, after
  // HostileInputHasADefinedOutcome)
  ros::Subscriber estimate_sub_, diag_sub_;
  std::unique_ptr<dynamic_reconfigure::Client<sce::ContactEstimatorConfig>> client_;
  sce::ContactEstimatorConfig config_;
};

TEST(ParameterText, NumbersReadAsTextAreRepaired)
{
  // what rosparam makes of "bristle_stiffness: 2.0e8" (YAML 1.1: no sign in the exponent, so text)
  ros::NodeHandle pnh("/parameter_text_check");
  pnh.setParam("bristle_stiffness", std::string("2.0e8"));
  pnh.setParam("resolution", std::string("24"));
  pnh.setParam("tilt", std::string("true"));
  pnh.setParam("friction", std::string("slippery"));
  pnh.setParam("contact_frame", std::string("1e3"));  // a string parameter stays text
  pnh.setParam("surface_damping", 1e5);               // a number stays as it is
  bool all_repaired = true;
  const std::vector<std::string> lines = sce::repairTextParameters(pnh, all_repaired);
  EXPECT_EQ(lines.size(), 4u);
  EXPECT_FALSE(all_repaired);  // "slippery" is no number
  double k = 0.0, damping = 0.0;
  int resolution = 0;
  bool tilt = false;
  std::string frame;
  EXPECT_TRUE(pnh.getParam("bristle_stiffness", k));
  EXPECT_EQ(k, 2e8);
  EXPECT_TRUE(pnh.getParam("resolution", resolution));
  EXPECT_EQ(resolution, 24);
  EXPECT_TRUE(pnh.getParam("tilt", tilt));
  EXPECT_TRUE(tilt);
  EXPECT_FALSE(pnh.hasParam("friction"));  // deleted: the default applies
  EXPECT_TRUE(pnh.getParam("contact_frame", frame));
  EXPECT_EQ(frame, "1e3");
  EXPECT_TRUE(pnh.getParam("surface_damping", damping));
  EXPECT_EQ(damping, 1e5);
  // whole numbers beyond int's range, and fractions, are no int: deleted
  for (const char* text : { "1e300", "3e9", "-3e9", "24.5", "nan", "inf" })
  {
    pnh.setParam("resolution", std::string(text));
    EXPECT_EQ(sce::repairTextParameters(pnh, all_repaired).size(), 1u) << text;
    EXPECT_FALSE(all_repaired) << text;
    EXPECT_FALSE(pnh.hasParam("resolution")) << text;
  }
  pnh.setParam("resolution", std::string("1024"));  // the .cfg's largest
  sce::repairTextParameters(pnh, all_repaired);
  EXPECT_TRUE(all_repaired);
  EXPECT_TRUE(pnh.getParam("resolution", resolution));
  EXPECT_EQ(resolution, 1024);
  // enum names; numbers the server would clamp or take for an enum without a word are refused, naming the valid ones
  pnh.setParam("brush_model", std::string("steady"));
  pnh.setParam("rolling_resistance_model", std::string("off"));
  sce::repairTextParameters(pnh, all_repaired);
  EXPECT_TRUE(all_repaired);
  int model = -1;
  EXPECT_TRUE(pnh.getParam("brush_model", model));
  EXPECT_EQ(model, 2);
  EXPECT_TRUE(pnh.getParam("rolling_resistance_model", model));
  EXPECT_EQ(model, 0);
  pnh.setParam("brush_model", 7);
  pnh.setParam("resolution", 100000);
  pnh.setParam("friction", -1.0);
  const std::vector<std::string> refused = sce::repairTextParameters(pnh, all_repaired);
  EXPECT_FALSE(all_repaired);
  ASSERT_EQ(refused.size(), 3u);
  std::string all;
  for (const std::string& line : refused)
    all += line + "\n";
  EXPECT_NE(all.find("off (0), linear (1), steady (2), transient (3), auto (4)"), std::string::npos) << all;
  EXPECT_NE(all.find("outside [2, 1024]"), std::string::npos) << all;
  EXPECT_FALSE(pnh.hasParam("brush_model"));
  EXPECT_FALSE(pnh.hasParam("resolution"));
  EXPECT_FALSE(pnh.hasParam("friction"));
  pnh.deleteParam("");
}

TEST_F(EstimatorIo, TheParameterFileIsInForce)
{
  // every value of config/contact_estimator.yaml reached the estimator (none dropped as mistyped)
  EXPECT_EQ(config_.bristle_stiffness, 2e8);
  EXPECT_EQ(config_.surface_stiffness, 1e8);
  EXPECT_EQ(config_.surface_damping, 1e5);
  EXPECT_EQ(config_.surface_density, 10.0);
  EXPECT_EQ(config_.standstill_speed, 0.05);
}

TEST_F(EstimatorIo, OneOutputPerInputWithItsStamp)
{
  const int n = 200;
  for (int i = 0; i < n; ++i)
  {
    odom_pub_.publish(odometry(g_clock + 0.01 * i, 1.0, 0.3, 0.01, 0.0, 0.2));
  }
  ASSERT_TRUE(waitFor([&] { return estimates_.size() >= static_cast<std::size_t>(n); }, 10.0)) << estimates_.size();
  ros::WallDuration(0.3).sleep();  // no extras arrive
  std::lock_guard<std::mutex> lock(mutex_);
  ASSERT_EQ(estimates_.size(), static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    EXPECT_EQ(estimates_[i].header.stamp, ros::Time(g_clock + 0.01 * i)) << i;
    EXPECT_EQ(estimates_[i].header.frame_id, config_.contact_frame);
  }
  g_clock += 0.01 * n;
}

TEST_F(EstimatorIo, ValuesEqualTheCoreLibrary)
{
  // Stamps before every other test's: the node sees time jump back and resets all its state, so it starts
  // from where a new core estimator starts (the transient bristle lattice included).
  sce::ContactEstimator core(sce::settingsFromConfig(config_));
  std::vector<nav_msgs::Odometry> sent;
  for (int i = 0; i < 60; ++i)  // accelerate while turning and sliding, then brake
  {
    const double t = 0.01 * i, v = i < 40 ? 0.05 + 0.04 * i : 1.65 - 0.05 * (i - 40);
    sent.push_back(odometry(100.0 + t, v, 0.5 * t, i < 40 ? -0.02 : 0.1, 0.02, 0.5));
    odom_pub_.publish(sent.back());
  }
  ASSERT_TRUE(waitFor([&] { return estimates_.size() >= sent.size(); }, 10.0));
  std::lock_guard<std::mutex> lock(mutex_);
  for (std::size_t i = 0; i < sent.size(); ++i)
  {
    const sce::ContactEstimateData* d = core.update(input(sent[i]));
    ASSERT_TRUE(d);
    const sce::ContactEstimate* m = estimateAt(sent[i].header.stamp);
    ASSERT_TRUE(m) << i;
    const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); };
    EXPECT_TRUE(near(m->rolling_speed, d->rolling_speed)) << i;
    EXPECT_TRUE(near(m->heading, d->heading)) << i;
    EXPECT_TRUE(near(m->turn_rate, d->turn_rate)) << i;
    EXPECT_TRUE(near(m->slip.x, d->slip.x()) && near(m->slip.y, d->slip.y())) << i;
    EXPECT_TRUE(near(m->spin, d->spin) && near(m->spin_turn, d->spin_turn)) << i;
    EXPECT_TRUE(near(m->brush_force.x, d->brush.F_x) && near(m->brush_force.y, d->brush.F_y)) << i;
    EXPECT_TRUE(near(m->brush_moment, d->brush.M_z)) << i;
    EXPECT_TRUE(near(m->sliding_fraction, d->brush.sliding_fraction)) << i;
    EXPECT_TRUE(near(m->rolling_resistance.force, d->rolling_resistance_force)) << i;
    EXPECT_TRUE(near(m->rolling_resistance.mu_roll, d->rolling_resistance.mu_roll)) << i;
    EXPECT_EQ(m->valid, d->valid()) << i;
    EXPECT_TRUE(m->flags & sce::ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY);  // no tf in this test
  }
  // physical signs in the ROS contact frame: sliding to the left, the ground pushes right
  const sce::ContactEstimate* last = estimateAt(sent.back().header.stamp);
  EXPECT_LT(last->brush_force.y, 0.0);
  EXPECT_LT(last->brush_force.x, 0.0);  // braking
}

TEST_F(EstimatorIo, ReconfigureTakesEffectOnTheNextMessage)
{
  const double friction = config_.friction;
  odom_pub_.publish(odometry(g_clock, 1.0, 0.0, 0.2, 0.0, 0.0));
  odom_pub_.publish(odometry(g_clock + 0.01, 1.0, 0.0, 0.2, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return estimates_.size() >= 2; }, 5.0));
  double before;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    before = estimates_.back().brush_force.x;
  }
  ASSERT_TRUE(reconfigure([&](sce::ContactEstimatorConfig& c) { c.friction = 0.5 * friction; }));
  EXPECT_DOUBLE_EQ(config_.friction, 0.5 * friction);
  odom_pub_.publish(odometry(g_clock + 0.02, 1.0, 0.0, 0.2, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return estimates_.size() >= 3; }, 5.0));
  {
    // full sliding (sigma_x = -0.2): |F_x| = mu F_z, now halved
    std::lock_guard<std::mutex> lock(mutex_);
    EXPECT_NEAR(estimates_.back().brush_force.x, 0.5 * before, 0.02 * std::abs(before));
  }
  // a configuration the core rejects (no load at all) keeps the previous one
  ASSERT_TRUE(reconfigure([&](sce::ContactEstimatorConfig& c) {
    c.robot_mass = 0.0;
    c.load = 0.0;
  }));
  EXPECT_GT(config_.robot_mass, 0.0);
  EXPECT_DOUBLE_EQ(config_.friction, 0.5 * friction);
  // auto: the message says which model ran
  ASSERT_TRUE(reconfigure([&](sce::ContactEstimatorConfig& c) {
    c.friction = friction;
    c.brush_model = sce::ContactEstimate::BRUSH_AUTO;
  }));
  odom_pub_.publish(odometry(g_clock + 0.03, 1.0, 0.0, 0.0005, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return estimates_.size() >= 4; }, 5.0));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    EXPECT_EQ(estimates_.back().brush_model, sce::ContactEstimate::BRUSH_AUTO);
    EXPECT_EQ(estimates_.back().brush_model_used, sce::ContactEstimate::BRUSH_LINEAR);  // a tiny slip
  }
  ASSERT_TRUE(reconfigure([&](sce::ContactEstimatorConfig& c) { c.brush_model = sce::ContactEstimate::BRUSH_TRANSIENT; }));
  g_clock += 1.0;
}

TEST_F(EstimatorIo, NonFiniteTwistIsSkippedDiagnosedAndSurvived)
{
  nav_msgs::Odometry bad = odometry(g_clock, 1.0, 0.0, 0.0, 0.0, 0.0);
  bad.twist.twist.angular.y = std::numeric_limits<double>::quiet_NaN();
  odom_pub_.publish(bad);
  bad.header.stamp = ros::Time(g_clock + 0.01);
  bad.twist.twist.angular.y = 10.0;
  bad.twist.twist.linear.x = std::numeric_limits<double>::infinity();
  odom_pub_.publish(bad);
  ASSERT_TRUE(waitFor([&] {
    const auto it = diagnostics_.find(kNode.substr(1) + ": odometry input");
    return it != diagnostics_.end() && it->second.level == diagnostic_msgs::DiagnosticStatus::WARN &&
           it->second.message.find("rejected") != std::string::npos;
  }, 10.0));
  // still running, and nothing non-finite reached the topic
  odom_pub_.publish(odometry(g_clock + 0.02, 1.0, 0.0, 0.0, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return estimateAt(ros::Time(g_clock + 0.02)) != nullptr; }, 5.0));
  std::lock_guard<std::mutex> lock(mutex_);
  EXPECT_EQ(estimateAt(ros::Time(g_clock)), nullptr);
  EXPECT_EQ(estimateAt(ros::Time(g_clock + 0.01)), nullptr);
  for (const auto& e : estimates_)
    EXPECT_TRUE(std::isfinite(e.brush_force.x) && std::isfinite(e.slip.x) && std::isfinite(e.rolling_resistance.force));
  g_clock += 1.0;
}

TEST_F(EstimatorIo, TwistCovarianceReachesTheEstimateAndBadOnesAreDiagnosed)
{
  // a sound covariance: the forces' covariance in the estimate, symmetric, with positive variances
  nav_msgs::Odometry o = odometry(g_clock, 1.0, 0.3, 0.01, 0.005, 0.2);
  for (int i : { 0, 7 })
    o.twist.covariance[i] = 1e-5;  // linear x, y [m^2/s^2]
  for (int i : { 21, 28, 35 })
    o.twist.covariance[i] = 1e-3;  // angular x, y, z [rad^2/s^2]
  odom_pub_.publish(o);
  // NaN, then the ROS "unknown" convention on a component the estimate uses: the estimate goes on, the covariance is
  // unknown (element 0 = -1) and says why
  nav_msgs::Odometry nan = o, unknown = o;
  nan.header.stamp = ros::Time(g_clock + 0.01);
  nan.twist.covariance[1] = nan.twist.covariance[6] = std::numeric_limits<double>::quiet_NaN();
  odom_pub_.publish(nan);
  unknown.header.stamp = ros::Time(g_clock + 0.02);
  unknown.twist.covariance[35] = -1.0;
  odom_pub_.publish(unknown);
  ASSERT_TRUE(waitFor([&] { return estimateAt(ros::Time(g_clock + 0.02)) != nullptr; }, 5.0));
  ASSERT_TRUE(waitFor([&] {
    const auto it = diagnostics_.find(kNode.substr(1) + ": uncertainty");
    return it != diagnostics_.end() && it->second.level == diagnostic_msgs::DiagnosticStatus::WARN &&
           it->second.message.find("unusable") != std::string::npos;
  }, 10.0));
  std::lock_guard<std::mutex> lock(mutex_);
  const sce::ContactEstimate* good = estimateAt(ros::Time(g_clock));
  ASSERT_NE(good, nullptr);
  // (approximate where the work budget took the linear model's Jacobian instead of the sigma points)
  EXPECT_TRUE(good->covariance_status == sce::ContactEstimate::COVARIANCE_OK ||
              good->covariance_status == sce::ContactEstimate::COVARIANCE_APPROXIMATE);
  EXPECT_NE(good->brush_covariance_method, sce::ContactEstimate::COVARIANCE_METHOD_NONE);
  for (int i : { 0, 4, 8 })
    EXPECT_GT(good->brush_covariance[i], 0.0) << i;
  EXPECT_DOUBLE_EQ(good->brush_covariance[1], good->brush_covariance[3]);
  EXPECT_GT(good->rolling_resistance_force_variance, 0.0);
  const sce::ContactEstimate* refused = estimateAt(ros::Time(g_clock + 0.01));
  ASSERT_NE(refused, nullptr);
  EXPECT_EQ(refused->covariance_status, sce::ContactEstimate::COVARIANCE_INVALID);
  EXPECT_EQ(refused->brush_covariance[0], -1.0);
  EXPECT_EQ(refused->rolling_resistance_force_variance, -1.0);
  EXPECT_TRUE(std::isfinite(refused->brush_force.x));
  const sce::ContactEstimate* marked = estimateAt(ros::Time(g_clock + 0.02));
  ASSERT_NE(marked, nullptr);
  EXPECT_EQ(marked->covariance_status, sce::ContactEstimate::COVARIANCE_UNKNOWN);
  EXPECT_EQ(marked->brush_covariance[0], -1.0);
  for (const auto& e : estimates_)
    for (double c : e.brush_covariance)
      EXPECT_TRUE(std::isfinite(c));
  g_clock += 1.0;
}

TEST_F(EstimatorIo, MissingTfNeverBlocks)
{
  // a ground frame nobody publishes: no tf, and the odometry's orientation is in another frame
  ASSERT_TRUE(reconfigure([](sce::ContactEstimatorConfig& c) { c.ground_frame = "map"; }));
  const ros::WallTime start = ros::WallTime::now();
  for (int i = 0; i < 100; ++i)
    odom_pub_.publish(odometry(g_clock + 0.01 * i, 1.0, 0.0, 0.0, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] {
    const auto it = diagnostics_.find(kNode.substr(1) + ": tf");
    return it != diagnostics_.end() && it->second.level == diagnostic_msgs::DiagnosticStatus::WARN;
  }, 10.0));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    EXPECT_TRUE(estimates_.empty());  // skipped, not guessed
  }
  ASSERT_TRUE(reconfigure([](sce::ContactEstimatorConfig& c) { c.ground_frame = ""; }));
  odom_pub_.publish(odometry(g_clock + 1.0, 1.0, 0.0, 0.0, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return !estimates_.empty(); }, 5.0));
  // 100 skipped messages, two reconfigurations and an estimate within a few seconds: nothing waited on tf
  EXPECT_LT((ros::WallTime::now() - start).toSec(), 5.0);
  g_clock += 2.0;
}

TEST_F(EstimatorIo, HostileInputHasADefinedOutcome)
{
  // The outcomes of docs/node.md's hostile-input table, in one sequence; the node answers each as documented and goes on.
  const double t = g_clock;
  odom_pub_.publish(odometry(t, 1.0, 0.0, 0.01, 0.0, 0.0));
  odom_pub_.publish(odometry(t, 1.0, 0.0, 0.01, 0.0, 0.0));        // duplicate stamp: answered, not advanced
  odom_pub_.publish(odometry(t - 0.5, 1.0, 0.0, 0.01, 0.0, 0.0));  // back in time: answered, state reset
  nav_msgs::Odometry no_frames = odometry(t + 0.01, 1.0, 0.0, 0.01, 0.0, 0.0);
  no_frames.header.frame_id.clear();
  no_frames.child_frame_id.clear();                                   // empty frame ids: the odometry's orientation
  odom_pub_.publish(no_frames);
  nav_msgs::Odometry nothing = odometry(t + 0.02, 1.0, 0.0, 0.01, 0.0, 0.0);
  nothing.header.frame_id.clear();
  nothing.child_frame_id.clear();
  nothing.pose.pose.orientation = geometry_msgs::Quaternion();        // and no orientation: skipped
  odom_pub_.publish(nothing);
  nav_msgs::Odometry huge = odometry(t + 0.03, 1.0, 0.0, 0.01, 0.0, 0.0);
  huge.twist.twist.angular.y = 1e300;                                 // faster than light: skipped
  odom_pub_.publish(huge);
  for (int i = 0; i < 500; ++i)                                       // a burst: all answered
    odom_pub_.publish(odometry(t + 0.04 + 1e-4 * i, 1.0, 0.0, 0.01, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return estimates_.size() >= 504; }, 20.0)) << estimates_.size();
  ros::WallDuration(0.3).sleep();
  std::lock_guard<std::mutex> lock(mutex_);
  ASSERT_EQ(estimates_.size(), 504u);  // 506 sent, the two without a usable input skipped
  EXPECT_TRUE(estimates_[1].flags & sce::ContactEstimate::FLAG_DUPLICATE_STAMP);
  EXPECT_TRUE(estimates_[2].flags & sce::ContactEstimate::FLAG_TIME_JUMP_RESET);
  EXPECT_TRUE(estimates_[3].flags & sce::ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY);
  EXPECT_EQ(estimateAt(ros::Time(t + 0.02)), nullptr);
  EXPECT_EQ(estimateAt(ros::Time(t + 0.03)), nullptr);
  for (const auto& e : estimates_)
    EXPECT_TRUE(std::isfinite(e.brush_force.x) && std::isfinite(e.brush_moment) && std::isfinite(e.slip.y));
  g_clock += 2.0;
}

TEST_F(EstimatorIo, MarkersWhileSubscribed)
{
  std::vector<visualization_msgs::MarkerArray> markers;
  ros::Subscriber sub = nh_.subscribe<visualization_msgs::MarkerArray>("contact_markers", 10, [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    markers.push_back(*m);
  });
  ASSERT_TRUE(waitFor([&] { return sub.getNumPublishers() > 0; }, 10.0));
  ros::WallDuration(0.5).sleep();  // the node sees the subscriber
  for (int i = 0; i < 20; ++i)
    odom_pub_.publish(odometry(g_clock + 0.01 * i, 1.0, 0.0, 0.05, 0.02, 0.0));
  // markers are best effort (a short queue); the last message's are kept, and its bristles have built up
  const ros::Time last(g_clock + 0.19);
  ASSERT_TRUE(waitFor([&] { return !markers.empty() && markers.back().markers.at(0).header.stamp == last; }, 10.0));
  std::lock_guard<std::mutex> lock(mutex_);
  const visualization_msgs::MarkerArray& m = markers.back();
  namespace cm = sphere_contact_estimator::contact_markers;
  ASSERT_EQ(m.markers.size(), static_cast<std::size_t>(cm::kCount));
  EXPECT_EQ(m.markers[0].header.frame_id, "contact_patch");
  const visualization_msgs::Marker& zones = m.markers[cm::kBristles];
  EXPECT_EQ(zones.type, visualization_msgs::Marker::POINTS);
  EXPECT_GT(zones.points.size(), 100u);
  EXPECT_EQ(zones.points.size(), zones.colors.size());
  EXPECT_EQ(m.markers[cm::kDeflections].points.size(), 2 * zones.points.size());
  EXPECT_EQ(m.markers[cm::kFrictionCircle].type, visualization_msgs::Marker::LINE_STRIP);
  EXPECT_EQ(m.markers[cm::kBrushForce].type, visualization_msgs::Marker::ARROW);
  EXPECT_LT(m.markers[cm::kBrushForce].points[1].x, 0.0);  // the brush force opposes the sliding
  g_clock += 1.0;
}

// Stamps that jitter (a USB source at 2 kHz): those a little earlier than the last are answered without a reset.
TEST_F(EstimatorIo, JitteredStampsAreAnsweredWithoutAReset)
{
  for (int i = 0; i < 60; ++i)  // every third stamp 0.7 ms late: the next one is 0.2 ms before it
    odom_pub_.publish(odometry(g_clock + 0.5e-3 * i + (i % 3 == 1 ? 0.7e-3 : 0.0), 1.0, 0.0, 0.05, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return estimates_.size() >= 60; }, 10.0)) << estimates_.size();
  std::lock_guard<std::mutex> lock(mutex_);
  int out_of_order = 0;
  for (std::size_t i = 1; i < estimates_.size(); ++i)  // (the first comes after the gap between tests)
  {
    EXPECT_FALSE(estimates_[i].flags & (sce::ContactEstimate::FLAG_TIME_JUMP_RESET | sce::ContactEstimate::FLAG_GAP_RESET)) << i;
    out_of_order += (estimates_[i].flags & sce::ContactEstimate::FLAG_STAMP_OUT_OF_ORDER) != 0;
  }
  EXPECT_EQ(out_of_order, 20);
  g_clock += 1.0;
}

// A burst beyond the node's queue (queue_size 1000) while each message takes long: the oldest are dropped, and every
// one of them is counted, in the estimate after the gap and in the diagnostics.
TEST_F(EstimatorIo, ABurstBeyondTheQueueIsCountedAsDropped)
{
  const sce::ContactEstimatorConfig original = config_;
  ASSERT_TRUE(reconfigure([](sce::ContactEstimatorConfig& c) {
    c.brush_model = 3;  // transient on a fine lattice: about a millisecond a message
    c.resolution = 128;
    c.work_budget = 1000000000;  // (the default cannot pay for this lattice: EstimatorSettings::leastWorkBudget)
  }));
  // one message first: the node knows this publisher's sequence from here on
  odom_pub_.publish(odometry(g_clock, 1.0, 0.0, 0.05, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return estimates_.size() == 1; }, 10.0));
  constexpr int kBurst = 3000;
  for (int i = 1; i <= kBurst; ++i)
    odom_pub_.publish(odometry(g_clock + 1e-4 * i, 1.0, 0.0, 0.05, 0.0, 0.0));
  const ros::Time last(g_clock + 1e-4 * kBurst);
  ASSERT_TRUE(waitFor([&] { return !estimates_.empty() && estimates_.back().header.stamp == last; }, 60.0))
      << "the burst's last message was not answered";
  ros::WallDuration(1.0).sleep();  // a diagnostics report after it
  {
  std::lock_guard<std::mutex> lock(mutex_);
  std::uint64_t dropped = 0;
  for (std::size_t i = 1; i < estimates_.size(); ++i)
  {
    dropped += estimates_[i].messages_dropped;
    EXPECT_EQ(estimates_[i].messages_dropped > 0, (estimates_[i].flags & sce::ContactEstimate::FLAG_MESSAGES_DROPPED) != 0);
  }
  EXPECT_GT(dropped, 0u) << "the burst did not overflow the queue: " << estimates_.size() << " answered";
  EXPECT_EQ(estimates_.size() - 1 + dropped, static_cast<std::size_t>(kBurst));  // each message answered or counted
  const auto it = diagnostics_.find(kNode.substr(1) + ": odometry input");
  ASSERT_NE(it, diagnostics_.end());
  std::uint64_t reported = 0;
  for (const auto& kv : it->second.values)
    if (kv.key == "dropped (gaps in header.seq)")
      reported = std::stoull(kv.value);
  EXPECT_GE(reported, dropped);
  }
  EXPECT_TRUE(reconfigure([&](sce::ContactEstimatorConfig& c) { c = original; }));
  g_clock += 2.0;
}

// A target the work budget cannot reach: the answers are flagged, and the contact models' diagnostic says how many and
// by how much (not a fault: the level stays below ERROR).
TEST_F(EstimatorIo, AnAccuracyTargetMissedIsSaidInTheDiagnostics)
{
  const sce::ContactEstimatorConfig original = config_;
  ASSERT_TRUE(reconfigure([](sce::ContactEstimatorConfig& c) {
    c.brush_model = sce::ContactEstimate::BRUSH_AUTO;
    c.accuracy_target = 1e-6;
    c.work_budget = 10000;  // the least it takes
  }));
  constexpr int kMessages = 20;
  for (int i = 0; i < kMessages; ++i)
    odom_pub_.publish(odometry(g_clock + 0.01 * i, 1.0, 0.0, 0.05, 0.02, 8.0));
  const ros::Time last(g_clock + 0.01 * (kMessages - 1));
  ASSERT_TRUE(waitFor([&] { return estimateAt(last) != nullptr; }, 20.0));
  int flagged = 0, held = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& e : estimates_)
    {
      flagged += (e.brush_flags & sce::ContactEstimate::BRUSH_FLAG_ACCURACY_NOT_MET) != 0;
      held += (e.brush_flags & sce::ContactEstimate::BRUSH_FLAG_BUDGET_LIMITED) != 0;
    }
  }
  EXPECT_GT(flagged, 0) << "a target of 1e-6 within 10^4 units was met: the test does not test the diagnostic";
  // auto at the lattice and tolerance the budget allows: what holds the target back is said, with what a larger budget
  // does
  EXPECT_GT(held, 0);
  std::string said;
  double worst = 0.0;
  EXPECT_TRUE(waitFor([&] {
    const auto it = diagnostics_.find(kNode.substr(1) + ": contact models");
    if (it == diagnostics_.end() || it->second.message.find("accuracy target missed") == std::string::npos ||
        it->second.message.find("held back by the work budget in ") == std::string::npos ||
        it->second.message.find("(BRUSH_FLAG_BUDGET_LIMITED: a larger work_budget lets auto refine)") ==
            std::string::npos)
      return false;
    said = it->second.message;
    EXPECT_LT(it->second.level, diagnostic_msgs::DiagnosticStatus::ERROR) << said;
    for (const auto& kv : it->second.values)
      if (kv.key == "largest error estimate / target since the last report")
        worst = std::stod(kv.value);
    return true;
  }, 5.0)) << "the contact models' diagnostic never said the target was missed";
  EXPECT_GT(worst, 1.0) << said;
  // parked with the default budget: the answers that miss the target are said to be at standstill, where auto's lattice
  // cannot refine (not the budget)
  ASSERT_TRUE(reconfigure([](sce::ContactEstimatorConfig& c) { c.work_budget = 100000; }));
  const double parked = g_clock + 0.01 * kMessages + 0.5;
  for (int i = 0; i < kMessages; ++i)
    odom_pub_.publish(odometry(parked + 0.01 * i, 0.0, 0.0, 0.003, 0.002, 0.5));
  ASSERT_TRUE(waitFor([&] { return estimateAt(ros::Time(parked + 0.01 * (kMessages - 1))) != nullptr; }, 20.0));
  EXPECT_TRUE(waitFor([&] {
    const auto it = diagnostics_.find(kNode.substr(1) + ": contact models");
    if (it == diagnostics_.end() || it->second.message.find("at standstill in ") == std::string::npos)
      return false;
    said = it->second.message;
    return true;
  }, 5.0)) << "the contact models' diagnostic never said the missed targets were at standstill: " << said;
  EXPECT_NE(said.find("(auto refines its lattice only while the patch rolls)"), std::string::npos) << said;
  EXPECT_TRUE(reconfigure([&](sce::ContactEstimatorConfig& c) { c = original; }));
  g_clock += 3.0;
}

// One update that takes seconds (the transient model on a fine lattice rolling 5 cm): the diagnostics go on at their
// rate meanwhile (their own queue and thread, and a lock the update does not hold).
TEST_F(EstimatorIo, DiagnosticsDoNotWaitForALongUpdate)
{
  const sce::ContactEstimatorConfig original = config_;
  ASSERT_TRUE(reconfigure([](sce::ContactEstimatorConfig& c) {
    c.brush_model = 3;
    c.resolution = 256;
    c.tilt = true;  // the lattice's substeps (without tilt every bristle takes the step whole: tens of ms)
    c.work_budget = 1000000000;  // all of them (about 9e8 units: 51 000 sliding bristles, each at every substep)
  }));
  // skidding at half the rolling speed, so that every bristle slides and takes the substeps (adhering ones take the
  // step in closed form along their arcs: at 5 % slip the update took 0.7 s)
  odom_pub_.publish(odometry(g_clock, 1.0, 0.0, 0.5, 0.0, 0.0));
  ASSERT_TRUE(waitFor([&] { return estimates_.size() == 1; }, 10.0));
  int before = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    before = diagnostics_count_;
  }
  const ros::WallTime start = ros::WallTime::now();
  odom_pub_.publish(odometry(g_clock + 0.07, 1.0, 0.0, 0.5, 0.0, 0.0));  // ~1800 substeps of a 256^2 lattice
  ASSERT_TRUE(waitFor([&] { return estimates_.size() == 2; }, 60.0));
  const double busy = (ros::WallTime::now() - start).toSec();
  int during = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    during = diagnostics_count_ - before;
  }
  std::printf("an update of %.2f s: %d diagnostics reports during it\n", busy, during);
  // reports every 0.25 s; allow for half of them (a loaded machine). An update of two periods or more tests it (since
  // the adhering bristles' closed forms along their arcs it takes 1-2 s: all 9e8 units of it sliding)
  if (busy > 0.5)
    EXPECT_GE(during, static_cast<int>(busy / 0.25 / 2.0)) << "over an update of " << busy << " s";
  else
    ADD_FAILURE() << "the update took only " << busy << " s: it does not test the diagnostics' independence";
  EXPECT_TRUE(reconfigure([&](sce::ContactEstimatorConfig& c) { c = original; }));
  g_clock += 2.0;
}

// tf that stops: its last transform is used up to tf_max_age (0.5 s in config/contact_estimator.yaml) past it, then
// the odometry's own orientation, flagged, and the tf diagnostic warns. (Last: the node keeps the transform.)
TEST_F(EstimatorIo, ATransformThatStoppedIsNotUsedPastItsAge)
{
  ros::Publisher tf_pub = nh_.advertise<tf2_msgs::TFMessage>("/tf", 100);
  ASSERT_TRUE(waitFor([&] { return tf_pub.getNumSubscribers() > 0; }, 10.0));
  // the body yawed by 90 degrees in odom from g_clock to g_clock + 1; the odometry's own pose says 0
  for (int i = 0; i <= 100; ++i)
  {
    tf2_msgs::TFMessage m;
    m.transforms.resize(1);
    geometry_msgs::TransformStamped& x = m.transforms[0];
    x.header.stamp = ros::Time(g_clock + 0.01 * i);
    x.header.frame_id = "odom";
    x.child_frame_id = "base_link";
    x.transform.rotation.z = std::sin(0.25 * M_PI);
    x.transform.rotation.w = std::cos(0.25 * M_PI);
    tf_pub.publish(m);
  }
  ros::WallDuration(0.5).sleep();  // in the node's buffer
  odom_pub_.publish(odometry(g_clock + 0.5, 1.0, 0.0, 0.0, 0.0, 0.0));  // tf at the stamp
  odom_pub_.publish(odometry(g_clock + 1.2, 1.0, 0.0, 0.0, 0.0, 0.0));  // tf's latest, 0.2 s old
  odom_pub_.publish(odometry(g_clock + 2.0, 1.0, 0.0, 0.0, 0.0, 0.0));  // 1 s old: not used
  ASSERT_TRUE(waitFor([&] { return estimates_.size() >= 3; }, 10.0));
  ASSERT_TRUE(waitFor([&] {
    const auto it = diagnostics_.find(kNode.substr(1) + ": tf");
    return it != diagnostics_.end() && it->second.level == diagnostic_msgs::DiagnosticStatus::WARN &&
           it->second.message.find("stale") != std::string::npos;
  }, 10.0)) << "the tf diagnostic did not warn";
  std::lock_guard<std::mutex> lock(mutex_);
  const sce::ContactEstimate* at_stamp = estimateAt(ros::Time(g_clock + 0.5));
  const sce::ContactEstimate* latest = estimateAt(ros::Time(g_clock + 1.2));
  const sce::ContactEstimate* stale = estimateAt(ros::Time(g_clock + 2.0));
  ASSERT_TRUE(at_stamp && latest && stale);
  EXPECT_NEAR(at_stamp->heading, 0.5 * M_PI, 1e-6);
  EXPECT_NEAR(latest->heading, 0.5 * M_PI, 1e-6);
  EXPECT_FALSE(latest->flags & (sce::ContactEstimate::FLAG_TF_STALE | sce::ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY));
  EXPECT_NEAR(stale->heading, 0.0, 1e-6);
  EXPECT_TRUE(stale->flags & sce::ContactEstimate::FLAG_TF_STALE);
  EXPECT_TRUE(stale->flags & sce::ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY);
  g_clock += 3.0;
}

}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_estimator_io");
  ros::NodeHandle keep_alive;
  ros::AsyncSpinner spinner(2);  // the dynamic_reconfigure client waits on callbacks
  spinner.start();
  {
    // the node's first message, at kEpoch: its clock's origin (answered, so that the node has taken it)
    ros::Publisher pub = keep_alive.advertise<nav_msgs::Odometry>("odom", 10);
    std::mutex mutex;
    bool answered = false;
    ros::Subscriber sub = keep_alive.subscribe<sphere_contact_estimator::ContactEstimate>(
        "contact_estimate", 10, [&](const sphere_contact_estimator::ContactEstimate::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          answered = answered || m->header.stamp == kEpoch;
        });
    nav_msgs::Odometry first;
    first.header.stamp = kEpoch;
    first.header.frame_id = "odom";
    first.child_frame_id = "base_link";
    first.pose.pose.orientation.w = 1.0;
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
    while (ros::ok() && ros::WallTime::now() < deadline && (pub.getNumSubscribers() == 0 || sub.getNumPublishers() == 0))
      ros::WallDuration(0.05).sleep();
    pub.publish(first);
    if (!sphere_contact_estimator::test::waitFor(mutex, [&] { return answered; }, 10.0))
    {
      std::fprintf(stderr, "test_estimator_io: the node did not answer its first message\n");
      return 1;
    }
  }
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
