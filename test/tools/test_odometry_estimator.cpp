// The ROS layer's handling of a real stream, without a node: gaps in header.seq counted per publisher, a transform
// that stopped used only up to tf_max_age, and steps timed exactly whatever the stamps' epoch (OdometryEstimator,
// shared by the node and bag_analyze).

// STL
#include <cmath>
#include <string>
#include <vector>

// GTest
#include <gtest/gtest.h>

// ROS
#include <tf2/buffer_core.h>

// Package
#include "sphere_contact_estimator/ros/odometry_estimator.h"

namespace sce = sphere_contact_estimator;

namespace
{
// Rolling forward at 1 m/s in the body frame, the pose yawed by `yaw` in "odom".
nav_msgs::Odometry odometry(double stamp, std::uint32_t seq, double yaw = 0.0)
{
  nav_msgs::Odometry o;
  o.header.seq = seq;
  o.header.stamp = ros::Time(stamp);
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.pose.pose.orientation.z = std::sin(0.5 * yaw);
  o.pose.pose.orientation.w = std::cos(0.5 * yaw);
  o.twist.twist.angular.y = 1.0 / 0.1;  // the default rolling radius
  o.twist.twist.linear.x = 1.0;
  return o;
}

sce::ContactEstimatorConfig config()
{
  sce::ContactEstimatorConfig c = sce::ContactEstimatorConfig::__getDefault__();
  c.brush_model = 1;  // linear: the stream's handling is under test, not the models
  return c;
}

TEST(OdometryEstimator, GapsInTheSequenceAreCountedPerPublisher)
{
  sce::OdometryEstimator e(config());
  tf2::BufferCore tf;
  sce::SkipReason reason;
  double t = 10.0;
  const auto send = [&](std::uint32_t seq, const std::string& publisher) {
    t += 0.01;
    const sce::EstimateOutputs* out = e.process(odometry(t, seq), tf, reason, publisher);
    EXPECT_NE(out, nullptr);
    return out ? out->estimate : sce::ContactEstimate();
  };
  EXPECT_EQ(send(7, "/a").messages_dropped, 0u);  // a publisher's first message: nothing to compare with
  EXPECT_EQ(send(8, "/a").messages_dropped, 0u);
  // a second publisher on the topic, its own count: no gap where the two interleave
  EXPECT_EQ(send(500, "/b").messages_dropped, 0u);
  const sce::ContactEstimate gap = send(11, "/a");  // 9 and 10 lost
  EXPECT_EQ(gap.messages_dropped, 2u);
  EXPECT_TRUE(gap.flags & sce::ContactEstimate::FLAG_MESSAGES_DROPPED);
  EXPECT_EQ(send(501, "/b").messages_dropped, 0u);
  const sce::ContactEstimate next = send(12, "/a");
  EXPECT_EQ(next.messages_dropped, 0u);
  EXPECT_FALSE(next.flags & sce::ContactEstimate::FLAG_MESSAGES_DROPPED);
  // a restarted publisher (seq from 0 again), a source that leaves seq at 0, a wrap past 2^32: nothing lost
  EXPECT_EQ(send(0, "/a").messages_dropped, 0u);
  EXPECT_EQ(send(0, "/a").messages_dropped, 0u);
  EXPECT_EQ(send(4294967295u, "/c").messages_dropped, 0u);
  EXPECT_EQ(send(1, "/c").messages_dropped, 1u);  // seq 0 lost across the wrap
  EXPECT_EQ(e.counters().dropped, 3u);
  // more publishers than slots: the longest unseen is forgotten, and counts afresh (no false gap)
  for (int k = 0; k < 10; ++k)
    EXPECT_EQ(send(1000 + 7 * k, "/p" + std::to_string(k)).messages_dropped, 0u);
  EXPECT_EQ(send(3, "/a").messages_dropped, 0u);  // "/a" was forgotten: its first message again
  EXPECT_EQ(e.counters().dropped, 3u);
}

TEST(OdometryEstimator, ATransformThatStoppedIsUsedOnlyUpToItsAge)
{
  sce::ContactEstimatorConfig c = config();
  c.tf_max_age = 0.5;
  sce::OdometryEstimator e(c);
  tf2::BufferCore tf;
  // tf yaws the body by 90 degrees in odom from stamp 10 to 11, then stops; the odometry's own pose says 0
  for (int i = 0; i <= 10; ++i)
  {
    geometry_msgs::TransformStamped x;
    x.header.stamp = ros::Time(10.0 + 0.1 * i);
    x.header.frame_id = "odom";
    x.child_frame_id = "base_link";
    x.transform.rotation.z = std::sin(0.25 * M_PI);
    x.transform.rotation.w = std::cos(0.25 * M_PI);
    ASSERT_TRUE(tf.setTransform(x, "test"));
  }
  sce::SkipReason reason;
  std::uint32_t seq = 0;
  // at a stamp with a transform: tf's heading (rolling along the body's x, which tf turns to odom's y)
  const sce::EstimateOutputs* out = e.process(odometry(10.55, ++seq), tf, reason);
  ASSERT_NE(out, nullptr);
  EXPECT_NEAR(out->estimate.heading, 0.5 * M_PI, 1e-9);
  EXPECT_FALSE(out->estimate.flags & sce::ContactEstimate::FLAG_TF_STALE);
  // past the last transform, within tf_max_age: tf's latest, still
  out = e.process(odometry(11.4, ++seq), tf, reason);
  ASSERT_NE(out, nullptr);
  EXPECT_NEAR(out->estimate.heading, 0.5 * M_PI, 1e-9);
  EXPECT_FALSE(out->estimate.flags & (sce::ContactEstimate::FLAG_TF_STALE | sce::ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY));
  EXPECT_EQ(e.counters().tf_latest, 1u);
  // beyond it: the odometry's own orientation, flagged, and why
  out = e.process(odometry(11.6, ++seq), tf, reason);
  ASSERT_NE(out, nullptr);
  EXPECT_NEAR(out->estimate.heading, 0.0, 1e-9);
  EXPECT_TRUE(out->estimate.flags & sce::ContactEstimate::FLAG_TF_STALE);
  EXPECT_TRUE(out->estimate.flags & sce::ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY);
  EXPECT_EQ(e.counters().tf_stale, 1u);
  EXPECT_NE(e.lastTfError().find("tf_max_age"), std::string::npos) << e.lastTfError();
  // with no valid orientation of its own, such a message is skipped, not turned by the old transform
  nav_msgs::Odometry bare = odometry(11.7, ++seq);
  bare.pose.pose.orientation = geometry_msgs::Quaternion();
  EXPECT_EQ(e.process(bare, tf, reason), nullptr);
  EXPECT_EQ(reason, sce::SkipReason::NoOrientation);
  // a larger tf_max_age takes the old transform again
  c.tf_max_age = 10.0;
  e.configure(c);
  out = e.process(odometry(11.8, ++seq), tf, reason);
  ASSERT_NE(out, nullptr);
  EXPECT_FALSE(out->estimate.flags & sce::ContactEstimate::FLAG_TF_STALE);
}
TEST(OdometryEstimator, StepsAreTimedExactlyWhateverTheStampsEpoch)
{
  // The same 1 kHz stream (stamps 1 ms apart to the nanosecond, the twist wobbling: slip, spin and the default auto
  // model at work) sent with two epochs, as two recordings of one scenario: every step is 1 ms, and the two give the
  // same answers bit for bit. (With a stamp's seconds since 1970 as a double, steps were off by up to 2.4e-7 s, and
  // the two recordings' forces parted at the first message: 1e-4 of mu F_z, then flags and resolutions.)
  const auto run = [](const ros::Time& epoch) {
    sce::OdometryEstimator e(sce::ContactEstimatorConfig::__getDefault__());
    tf2::BufferCore tf;
    sce::SkipReason reason;
    std::vector<sce::ContactEstimate> out;
    for (int k = 0; k < 300; ++k)
    {
      nav_msgs::Odometry o = odometry(0.0, static_cast<std::uint32_t>(k));
      o.header.stamp = epoch + ros::Duration(0, 1000000) * k;
      o.twist.twist.angular.y = (1.0 + 0.2 * std::sin(0.05 * k)) / 0.1;
      o.twist.twist.angular.z = 3.0 * std::cos(0.03 * k);
      o.twist.twist.linear.y = 0.05 * std::sin(0.07 * k);
      const sce::EstimateOutputs* r = e.process(o, tf, reason);
      EXPECT_NE(r, nullptr);
      if (!r)
        return out;
      if (k > 0)
      {
        EXPECT_NEAR(r->data->dt, 1e-3, 1e-12) << "message " << k;
      }
      out.push_back(r->estimate);
    }
    return out;
  };
  const std::vector<sce::ContactEstimate> a = run(ros::Time(1700000000, 123456789));
  const std::vector<sce::ContactEstimate> b = run(ros::Time(1800000000, 987654321));
  ASSERT_EQ(a.size(), b.size());
  int differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    differing += a[k].brush_force.x != b[k].brush_force.x || a[k].brush_force.y != b[k].brush_force.y ||
                 a[k].brush_moment != b[k].brush_moment || a[k].brush_flags != b[k].brush_flags ||
                 a[k].brush_error_estimate != b[k].brush_error_estimate;
  EXPECT_EQ(differing, 0);
  EXPECT_NE(a.back().brush_force.x, 0.0);  // the brush was at work
}
}  // namespace
