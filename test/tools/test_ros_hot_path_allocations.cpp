// The ROS layer's path allocates nothing per message either (docs/node.md): OdometryEstimator::process, which the node,
// the nodelet and bag_analyze run on every odometry message (frames from tf or from the odometry, the sequence's gaps,
// the core estimator, the conversions to messages), counted over the recorded manoeuvre's segments as odometry with the
// demo's noise, after one pass of the same stream; with tf absent, with tf at every stamp, and with a ground frame
// above the odometry's by a static transform. Every allocation is counted (test/support/allocation_count.h).
// Not here: a stamp past tf's newest transform (odometry ahead of tf), where the latest is looked up: tf2 allocates
// inside every lookup of its latest (getLatestCommonTime's own vector), which this package cannot avoid.

// STL
#include <cmath>
#include <random>
#include <string>
#include <vector>

// GTest
#include <gtest/gtest.h>

// ROS
#include <tf2/buffer_core.h>

// Package
#include "sphere_contact_estimator/ros/odometry_estimator.h"
#include "allocation_count.h"
#include "manoeuvre.h"
#include "scenario.h"

namespace sce = sphere_contact_estimator;

namespace
{
// The manoeuvre of config/manoeuvre_scenario.yaml, as its odometry at 100 Hz ("odom" -> "base_link", the twist in
// base_link with the demo's noise and its covariance), and the same poses as tf.
struct Recording
{
  std::vector<nav_msgs::Odometry> odometry;
  std::vector<geometry_msgs::TransformStamped> tf;
};

Recording manoeuvre()
{
  const sce::Scenario scenario(sce::test::manoeuvreSegments(), 0.1);
  const double noise_v = sce::test::kManoeuvreNoiseVelocity, noise_w = sce::test::kManoeuvreNoiseOmega;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  Recording r;
  std::uint32_t seq = 0;
  for (const sce::ScenarioSample& s : scenario.sample(0.01))
  {
    nav_msgs::Odometry o;
    o.header.seq = ++seq;
    o.header.stamp = ros::Time(100.0 + s.time);
    o.header.frame_id = "odom";
    o.child_frame_id = "base_link";
    o.pose.pose.position.x = s.position.x();
    o.pose.pose.position.y = s.position.y();
    o.pose.pose.position.z = s.position.z();
    o.pose.pose.orientation.z = std::sin(0.5 * s.yaw);
    o.pose.pose.orientation.w = std::cos(0.5 * s.yaw);
    o.twist.twist.linear.x = s.velocity_body.x() + noise_v * g(rng);
    o.twist.twist.linear.y = s.velocity_body.y() + noise_v * g(rng);
    o.twist.twist.angular.x = s.omega_body.x() + noise_w * g(rng);
    o.twist.twist.angular.y = s.omega_body.y() + noise_w * g(rng);
    o.twist.twist.angular.z = s.omega_body.z() + noise_w * g(rng);
    o.twist.covariance[0] = o.twist.covariance[7] = noise_v * noise_v;
    o.twist.covariance[21] = o.twist.covariance[28] = o.twist.covariance[35] = noise_w * noise_w;
    r.odometry.push_back(o);
    geometry_msgs::TransformStamped x;
    x.header.stamp = o.header.stamp;
    x.header.frame_id = "odom";
    x.child_frame_id = "base_link";
    x.transform.translation.x = s.position.x();
    x.transform.translation.y = s.position.y();
    x.transform.translation.z = s.position.z();
    x.transform.rotation = o.pose.pose.orientation;
    r.tf.push_back(x);
  }
  return r;
}

// The allocations of the second of two passes of the recording through one OdometryEstimator (the same stamps again,
// as a looping bag replays them: time goes back and the state is reset; header.seq goes on), and the messages that
// allocated.
long secondPassAllocations(const sce::ContactEstimatorConfig& config, const Recording& r, const tf2::BufferCore& tf,
                           std::string& where)
{
  sce::OdometryEstimator e(config);
  sce::SkipReason reason;
  const std::string publisher = "/odom";
  for (const nav_msgs::Odometry& o : r.odometry)
    e.process(o, tf, reason, publisher);
  long total = 0;
  nav_msgs::Odometry o;
  for (std::size_t i = 0; i < r.odometry.size(); ++i)
  {
    o = r.odometry[i];
    o.header.seq += r.odometry.size();
    long n;
    {
      const sce::test::AllocationCount count;
      const sce::EstimateOutputs* out = e.process(o, tf, reason, publisher);
      n = count.count();
      EXPECT_NE(out, nullptr) << "message " << i;
    }
    if (n > 0 && where.size() < 400)
      where += " message " + std::to_string(i) + ": " + std::to_string(n) + ";";
    total += n;
  }
  return total;
}

TEST(RosHotPath, ProcessingAnOdometryMessageAllocatesNothing)
{
  SCE_REQUIRE_ALLOCATION_COUNT();
  const Recording r = manoeuvre();
  const sce::ContactEstimatorConfig defaults = sce::ContactEstimatorConfig::__getDefault__();
  {
    // no tf: the odometry's own orientation (flagged), the reason kept
    const tf2::BufferCore none;
    std::string where;
    EXPECT_EQ(secondPassAllocations(defaults, r, none, where), 0) << "without tf:" << where;
  }
  // tf at every stamp
  tf2::BufferCore tf(ros::Duration(100.0));
  for (const geometry_msgs::TransformStamped& x : r.tf)
    ASSERT_TRUE(tf.setTransform(x, "test"));
  {
    std::string where;
    EXPECT_EQ(secondPassAllocations(defaults, r, tf, where), 0) << "with tf:" << where;
  }
  {
    // a ground frame above the odometry's: map -> odom static
    geometry_msgs::TransformStamped map;
    map.header.frame_id = "map";
    map.child_frame_id = "odom";
    map.transform.rotation.w = 1.0;
    map.transform.translation.x = 3.0;
    ASSERT_TRUE(tf.setTransform(map, "test", true));
    sce::ContactEstimatorConfig c = defaults;
    c.ground_frame = "map";
    std::string where;
    EXPECT_EQ(secondPassAllocations(c, r, tf, where), 0) << "ground frame map:" << where;
  }
}
}  // namespace
