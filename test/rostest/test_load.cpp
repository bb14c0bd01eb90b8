// Load test of the contact estimator (node or nodelet) over roscpp: odometry at a high rate (10 kHz for
// 60 s in load.test) through a manoeuvre that visits every branch (rolling, turning, standstill, pure
// spin, huge slips, past the critical speed, non-finite input), with dynamic_reconfigure changes all the
// while. Asserts: every published number finite, every brush and rolling-resistance model was in force,
// bounded latency (a queue that grows shows as a latency that grows), bounded resident memory of the
// process that hosts the estimator, and the node still answering at the end. scripts/test_tsan.sh runs
// the same test against a ThreadSanitizer build of the nodelet in a multi-threaded manager.

// STL
#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

// GTest
#include <gtest/gtest.h>

// ROS
#include <dynamic_reconfigure/client.h>
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpc.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/ContactEstimatorConfig.h"

namespace sce = sphere_contact_estimator;

namespace
{
struct LoadOptions
{
  double rate = 10000.0;            // odometry messages per second
  double duration = 60.0;           // [s]
  double warmup = 10.0;             // memory and latency are judged after this [s]
  double reconfigure_period = 0.5;  // [s]
  double max_rss_growth_mb = 16.0;  // resident memory growth allowed after the warm-up
  double max_latency = 1.0;         // 99th percentile of odometry -> estimate [s]
  double min_delivered = 0.2;       // share of the valid odometry that must come out as estimates
  std::string node = "/contact_estimator";  // the estimator's namespace (reconfigure server)
  std::string process = "/contact_estimator";  // the node whose process hosts it (the manager for a nodelet)
};

/// The process id of a ROS node, by the slave API's getPid (what rosnode info does); -1 if unknown.
int nodePid(const std::string& node)
{
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, false) || result.size() < 3)
    return -1;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(result[2]), host, port))
    return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue pid_args, pid_result;
  pid_args[0] = ros::this_node::getName();
  if (!client.execute("getPid", pid_args, pid_result) || pid_result.size() < 3)
    return -1;
  return static_cast<int>(pid_result[2]);
}

/// A field of /proc/<pid>/status in MB (VmRSS, VmHWM); NaN if the process is gone.
double procStatusMb(int pid, const std::string& field)
{
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.compare(0, field.size() + 1, field + ":") == 0)
    {
      std::istringstream in(line.substr(field.size() + 1));
      double kb = 0.0;
      in >> kb;
      return kb / 1024.0;
    }
  return std::nan("");
}

bool finite(const geometry_msgs::Vector3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Every floating-point field of the estimate.
bool finite(const sce::ContactEstimate& e)
{
  const auto& r = e.rolling_resistance;
  for (double x : { e.rolling_speed, e.heading, e.turn_rate, e.spin, e.spin_tilt, e.spin_turn, e.tilt_ratio,
                    e.patch_radius, e.load, e.brush_moment, e.sliding_fraction, e.max_utilisation, e.brush_error_estimate,
                    e.compute_time,
                    r.speed, r.h, r.xi_plus, r.xi_minus, r.force, r.torque, r.mu_roll })
    if (!std::isfinite(x))
      return false;
  return finite(e.sliding_velocity) && finite(e.slip) && finite(e.epsilon) && finite(e.brush_force);
}

bool finite(const geometry_msgs::WrenchStamped& w)
{
  return finite(w.wrench.force) && finite(w.wrench.torque);
}

bool injectedNan(std::size_t n)
{
  return n % 997 == 996;
}

/// Odometry of the n-th message of a manoeuvre that cycles every 8 s through rolling and turning with slip,
/// braking to standstill, spinning in place, skidding on ice, and a dash past the critical speed; every
/// 997th message has a NaN twist, which the node must reject. The body frame is yawed along the path.
nav_msgs::Odometry odometry(std::size_t n, double t, const ros::Time& stamp)
{
  const double R = 0.1;  // rolling radius of config/contact_estimator.yaml
  const double phase = std::fmod(t, 8.0);
  double v = 1.0 + 0.5 * std::sin(t), along = 0.01, left = 0.02 * std::sin(3.0 * t), omega_z = 0.3;
  if (phase > 2.0 && phase < 3.0)  // braking to standstill
    v = std::max(0.0, 1.0 - (phase - 2.0) * 1.2), along = left = 0.0;
  else if (phase >= 3.0 && phase < 4.0)  // pure spin
    v = 0.0, along = left = 0.0, omega_z = 20.0 * std::sin(M_PI * (phase - 3.0));
  else if (phase >= 4.0 && phase < 5.0)  // ice: the centre slides far faster than the sphere rolls
    v = 0.5, along = 5.0, left = -3.0, omega_z = 50.0;
  else if (phase >= 5.0 && phase < 6.0)  // far past the critical speed
    v = 40.0 * std::sin(M_PI * (phase - 5.0));
  const double yaw = 0.3 * t;
  nav_msgs::Odometry o;
  o.header.stamp = stamp;
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.pose.pose.orientation.z = std::sin(0.5 * yaw);
  o.pose.pose.orientation.w = std::cos(0.5 * yaw);
  o.twist.twist.angular.y = v / R;
  o.twist.twist.angular.z = omega_z;
  o.twist.twist.linear.x = v + along;
  o.twist.twist.linear.y = left;
  if (injectedNan(n))
    o.twist.twist.linear.x = std::nan("");
  return o;
}

/// The k-th configuration change: every brush and rolling-resistance model, friction down to the .cfg's least (0.001), tilt,
/// resolution, pressure, and surface parameters (which rebuild the rolling-resistance table).
void change(std::size_t k, sce::ContactEstimatorConfig& c)
{
  c.brush_model = static_cast<int>(k % 5);
  c.rolling_resistance_model = static_cast<int>((k / 2) % 4);
  c.friction = std::vector<double>{ 0.8, 0.3, 0.001, 1.5 }[k % 4];
  c.tilt = (k / 3) % 2 == 1;
  c.resolution = std::vector<int>{ 16, 8, 32, 12 }[(k / 5) % 4];
  c.pressure = static_cast<int>((k / 7) % 3);
  c.surface_damping = std::vector<double>{ 1e5, 2e5, 5e4 }[(k / 11) % 3];
  c.accuracy_target = std::vector<double>{ 0.01, 0.05 }[(k / 13) % 2];
}

class Load : public ::testing::Test
{
protected:
  void SetUp() override
  {
    ros::NodeHandle pnh("~");
    pnh.param("rate", options_.rate, options_.rate);
    pnh.param("duration", options_.duration, options_.duration);
    pnh.param("warmup", options_.warmup, options_.warmup);
    pnh.param("reconfigure_period", options_.reconfigure_period, options_.reconfigure_period);
    pnh.param("max_rss_growth_mb", options_.max_rss_growth_mb, options_.max_rss_growth_mb);
    pnh.param("max_latency", options_.max_latency, options_.max_latency);
    pnh.param("min_delivered", options_.min_delivered, options_.min_delivered);
    pnh.param("node", options_.node, options_.node);
    pnh.param("process", options_.process, options_.process);
    ASSERT_GT(options_.rate, 0.0);
    ASSERT_GT(options_.duration, options_.warmup);
  }

  LoadOptions options_;
};

TEST_F(Load, HighRateOdometryWithReconfigureChanges)
{
  const LoadOptions& o = options_;
  ros::NodeHandle nh;
  const std::size_t total = static_cast<std::size_t>(o.rate * o.duration);
  // Preallocated: this process must not disturb the memory it measures in the other one.
  std::vector<double> sent_at(total + 1, std::nan(""));  // wall time of each message
  std::vector<float> latency;
  latency.reserve(total);
  std::mutex mutex;  // guards latency and the sets below
  std::set<int> brush_models_seen, rr_models_seen;
  std::atomic<std::size_t> estimates{ 0 }, nonfinite{ 0 }, nan_passed{ 0 }, wrenches{ 0 }, nonfinite_wrenches{ 0 };
  const ros::Time t0(1000.0);  // stamps: t0 + n / rate
  const double dt = 1.0 / o.rate;
  const auto index = [&](const ros::Time& stamp) {
    return static_cast<std::size_t>(std::llround((stamp - t0).toSec() * o.rate));
  };

  ros::Publisher odom_pub = nh.advertise<nav_msgs::Odometry>("odom", 10000);
  ros::Subscriber estimate_sub = nh.subscribe<sce::ContactEstimate>(
      "contact_estimate", 10000, [&](const sce::ContactEstimate::ConstPtr& e) {
        const double now = ros::WallTime::now().toSec();
        if (!finite(*e))
          ++nonfinite;
        const std::size_t n = index(e->header.stamp);
        if (n < total)  // the probe sent after the load is not one of the load's messages
          ++estimates;
        if (n < total && injectedNan(n))
          ++nan_passed;
        std::lock_guard<std::mutex> lock(mutex);
        if (n < total && std::isfinite(sent_at[n]) && sent_at[n] - sent_at[0] > o.warmup)
          latency.push_back(static_cast<float>(now - sent_at[n]));
        brush_models_seen.insert(e->brush_model_used);
        rr_models_seen.insert(e->rolling_resistance.model);
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  const auto on_wrench = [&](const geometry_msgs::WrenchStamped::ConstPtr& w) {
    ++wrenches;
    if (!finite(*w))
      ++nonfinite_wrenches;
  };
  ros::Subscriber brush_sub = nh.subscribe<geometry_msgs::WrenchStamped>("brush_wrench", 10000, on_wrench);
  ros::Subscriber rr_sub = nh.subscribe<geometry_msgs::WrenchStamped>("rolling_resistance_wrench", 10000, on_wrench);

  const auto wait = [](const std::function<bool()>& done, double seconds) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::ok() && !done() && ros::WallTime::now() < end)
      ros::WallDuration(0.01).sleep();
    return done();
  };
  ASSERT_TRUE(wait([&] { return odom_pub.getNumSubscribers() > 0 && estimate_sub.getNumPublishers() > 0 &&
                                brush_sub.getNumPublishers() > 0 && rr_sub.getNumPublishers() > 0; }, 30.0));
  dynamic_reconfigure::Client<sce::ContactEstimatorConfig> client(o.node);
  sce::ContactEstimatorConfig config;
  ASSERT_TRUE(client.getCurrentConfiguration(config, ros::Duration(20.0)));
  const int pid = nodePid(o.process);
  ASSERT_GT(pid, 0) << "no pid for " << o.process;
  const double rss_start = procStatusMb(pid, "VmRSS");

  // odometry: catch up with the wall clock every half millisecond, so the rate holds on average
  std::atomic<bool> done{ false };
  std::atomic<std::size_t> sent{ 0 };
  std::thread publisher([&] {
    const double start = ros::WallTime::now().toSec();
    std::size_t n = 0;
    while (n < total && ros::ok())
    {
      const double now = ros::WallTime::now().toSec();
      const std::size_t due = std::min(total, static_cast<std::size_t>((now - start) * o.rate) + 1);
      for (; n < due; ++n)
      {
        {
          std::lock_guard<std::mutex> lock(mutex);
          sent_at[n] = ros::WallTime::now().toSec();
        }
        odom_pub.publish(odometry(n, n * dt, t0 + ros::Duration(n * dt)));
      }
      sent = n;
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    done = true;
  });

  // reconfigure changes, and the host process's memory once a second
  std::size_t changes = 0, refused = 0;
  std::vector<std::pair<double, double>> rss;  // (time [s], VmRSS [MB])
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTime next_sample = start;
  while (!done && ros::ok())
  {
    change(changes, config);
    if (client.setConfiguration(config))
      ++changes;
    else
      ++refused, ++changes;
    if (ros::WallTime::now() >= next_sample)
    {
      rss.emplace_back((ros::WallTime::now() - start).toSec(), procStatusMb(pid, "VmRSS"));
      next_sample += ros::WallDuration(1.0);
    }
    ros::WallDuration(o.reconfigure_period).sleep();
  }
  publisher.join();
  const double elapsed = (ros::WallTime::now() - start).toSec();
  ros::WallDuration(2.0).sleep();  // the queues drain
  rss.emplace_back((ros::WallTime::now() - start).toSec(), procStatusMb(pid, "VmRSS"));

  // still running and answering: one more message, its estimate, and reconfigure
  const ros::Time last = t0 + ros::Duration(total * dt + 10.0);
  std::atomic<bool> got_last{ false };
  ros::Subscriber last_sub = nh.subscribe<sce::ContactEstimate>(
      "contact_estimate", 10, [&](const sce::ContactEstimate::ConstPtr& e) { got_last = got_last || e->header.stamp == last; });
  wait([&] { return last_sub.getNumPublishers() > 0; }, 5.0);
  odom_pub.publish(odometry(1, 1.0, last));
  EXPECT_TRUE(wait([&] { return got_last.load(); }, 10.0)) << "no estimate after the load";
  EXPECT_TRUE(client.getCurrentConfiguration(config, ros::Duration(10.0))) << "reconfigure server gone";
  EXPECT_EQ(nodePid(o.process), pid) << "the estimator's process restarted";

  std::lock_guard<std::mutex> lock(mutex);
  const std::size_t valid_sent = total - total / 997;
  const double delivered = static_cast<double>(estimates) / valid_sent;
  std::sort(latency.begin(), latency.end());
  const double p99 = latency.empty() ? std::nan("") : latency[latency.size() * 99 / 100];
  const double lmax = latency.empty() ? std::nan("") : latency.back();
  // memory after the warm-up: its growth, sampled once a second
  double rss_warm = std::nan(""), rss_max = 0.0;
  for (const auto& s : rss)
  {
    if (s.first >= o.warmup && std::isnan(rss_warm))
      rss_warm = s.second;
    if (s.first >= o.warmup)
      rss_max = std::max(rss_max, s.second);
  }
  std::printf("load: %zu odometry messages in %.1f s (%.0f Hz), %zu estimates (%.1f %% of the valid ones), "
              "%zu wrenches\n", static_cast<std::size_t>(sent), elapsed, sent / elapsed, estimates.load(),
              100.0 * delivered, wrenches.load());
  std::printf("load: %zu reconfigure changes (%zu refused); brush models seen %zu, rolling-resistance models %zu\n",
              changes, refused, brush_models_seen.size(), rr_models_seen.size());
  std::printf("load: latency after warm-up: p99 %.4f s, max %.4f s\n", p99, lmax);
  std::printf("load: VmRSS of %s (pid %d): %.1f MB at start, %.1f MB after %.0f s, at most %.1f MB after; "
              "VmHWM %.1f MB\n", o.process.c_str(), pid, rss_start, rss_warm, o.warmup, rss_max,
              procStatusMb(pid, "VmHWM"));

  EXPECT_EQ(sent.load(), total) << "the publisher stopped early";
  EXPECT_EQ(nonfinite.load(), 0u) << "non-finite numbers in published estimates";
  EXPECT_EQ(nonfinite_wrenches.load(), 0u) << "non-finite numbers in published wrenches";
  EXPECT_EQ(nan_passed.load(), 0u) << "estimates published for odometry with a NaN twist";
  EXPECT_GE(delivered, o.min_delivered);
  EXPECT_LE(delivered, 1.0 + 1e-9) << "more estimates than valid odometry messages";
  EXPECT_GT(changes, static_cast<std::size_t>(o.duration / o.reconfigure_period / 2)) << "reconfigure stalled";
  // every model was in force at some point (the server's changes reached the estimator under load)
  EXPECT_EQ(brush_models_seen, (std::set<int>{ 0, 1, 2, 3 })) << "brush models used (auto runs 1-3)";
  EXPECT_EQ(rr_models_seen, (std::set<int>{ 0, 1, 2, 3 }));
  EXPECT_LE(p99, o.max_latency) << "estimates fall behind: a queue grows";
  ASSERT_TRUE(std::isfinite(rss_warm)) << "no memory sample after the warm-up";
  EXPECT_LE(rss_max - rss_warm, o.max_rss_growth_mb) << "resident memory grows under load";
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_load");
  ros::AsyncSpinner spinner(3);
  spinner.start();
  return RUN_ALL_TESTS();
}
