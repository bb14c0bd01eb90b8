// The nodelet publishes its messages by shared pointer, so a consumer in the same nodelet manager gets the
// very object the estimator filled, not a deserialised copy. The estimator nodelet is loaded into this test's
// process (what a manager does); a message received here and held is still held by the estimator's pool
// (use_count 2), which a copy never is (use_count 1).

// STL
#include <functional>
#include <mutex>
#include <vector>

// GTest
#include <gtest/gtest.h>

// ROS
#include <geometry_msgs/WrenchStamped.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/loader.h>
#include <ros/ros.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "rolling_odometry.h"
#include "wait_for.h"

namespace sce = sphere_contact_estimator;

namespace
{
TEST(NodeletZeroCopy, EstimatesArriveByPointer)
{
  nodelet::Loader loader(false);  // no load/unload services: this process is the manager
  ASSERT_TRUE(loader.load("/contact_estimator", "sphere_contact_estimator/ContactEstimatorNodelet", {}, {}));

  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<sce::ContactEstimate::ConstPtr> estimates;
  std::vector<geometry_msgs::WrenchStamped::ConstPtr> wrenches;
  ros::Subscriber estimate_sub = nh.subscribe<sce::ContactEstimate>(
      "contact_estimate", 1000, [&](const sce::ContactEstimate::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        estimates.push_back(m);
      });
  ros::Subscriber wrench_sub = nh.subscribe<geometry_msgs::WrenchStamped>(
      "brush_wrench", 1000, [&](const geometry_msgs::WrenchStamped::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        wrenches.push_back(m);
      });
  ros::Publisher odom_pub = nh.advertise<nav_msgs::Odometry>("odom", 1000);
  const auto wait = [&](double seconds, const std::function<bool()>& done) {
    return sphere_contact_estimator::test::waitFor(mutex, done, seconds, 0.005);
  };
  ASSERT_TRUE(wait(20.0, [&] { return odom_pub.getNumSubscribers() > 0 && estimate_sub.getNumPublishers() > 0; }));

  nav_msgs::Odometry o = sphere_contact_estimator::test::rollingOdometry(1.02);
  const int n = 20;
  for (int i = 0; i < n; ++i)
  {
    o.header.stamp = ros::Time(10.0 + 0.01 * i);
    odom_pub.publish(o);
    ros::WallDuration(0.01).sleep();
  }
  ASSERT_TRUE(wait(10.0, [&] { return static_cast<int>(estimates.size()) == n && static_cast<int>(wrenches.size()) == n; }));
  ros::WallDuration(0.2).sleep();  // roscpp has let go of every message by now
  std::lock_guard<std::mutex> lock(mutex);
  for (int i = 0; i < n; ++i)
  {
    EXPECT_EQ(estimates[i]->header.stamp, ros::Time(10.0 + 0.01 * i));
    // this test and the estimator's pool: the same object, never copied
    EXPECT_EQ(estimates[i].use_count(), 2) << i;
    EXPECT_EQ(wrenches[i].use_count(), 2) << i;
  }
  estimates.clear();
  wrenches.clear();
  loader.unload("/contact_estimator");
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_nodelet_zero_copy");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int rc = RUN_ALL_TESTS();
  spinner.stop();
  return rc;
}
