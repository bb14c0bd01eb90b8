// Under sim time with a paused /clock, the node's stale-input diagnostic still fires: staleness is measured
// on the wall clock, and the diagnostics are published on a wall timer (a paused ROS clock froze both).

// STL
#include <functional>
#include <map>
#include <mutex>
#include <string>

// GTest
#include <gtest/gtest.h>

// ROS
#include <diagnostic_msgs/DiagnosticArray.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

// Package
#include "rolling_odometry.h"
#include "wait_for.h"

namespace
{
TEST(StaleClock, StaleInputIsReportedWhileTheClockIsPaused)
{
  ros::NodeHandle nh;
  std::mutex mutex;
  diagnostic_msgs::DiagnosticStatus input;
  bool have_input = false;
  ros::Subscriber diag_sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& s : m->status)
          if (s.name == "contact_estimator: odometry input")
          {
            input = s;
            have_input = true;
          }
      });
  ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 10, true);  // latched: the last time holds
  ros::Publisher odom_pub = nh.advertise<nav_msgs::Odometry>("odom", 100);
  const auto wait = [&](double seconds, const std::function<bool()>& done) {
    return sphere_contact_estimator::test::waitFor(mutex, done, seconds, 0.005);
  };
  ASSERT_TRUE(wait(20.0, [&] { return odom_pub.getNumSubscribers() > 0 && clock_pub.getNumSubscribers() > 0; }));

  // odometry at 100 Hz for half a second while the clock runs, then the clock and the odometry stop
  rosgraph_msgs::Clock clock;
  nav_msgs::Odometry o = sphere_contact_estimator::test::rollingOdometry(1.0);
  for (int i = 0; i < 50; ++i)
  {
    clock.clock = ros::Time(100.0 + 0.01 * i);
    clock_pub.publish(clock);
    o.header.stamp = clock.clock;
    odom_pub.publish(o);
    ros::WallDuration(0.01).sleep();
  }
  ASSERT_TRUE(wait(10.0, [&] {
    return have_input && input.level == diagnostic_msgs::DiagnosticStatus::OK;
  })) << "the input diagnostic never said OK while odometry arrived: " << input.message;
  // the parameter file's stale_timeout is 1 s: within a few wall seconds the paused clock must not hide it
  EXPECT_TRUE(wait(10.0, [&] {
    return input.level == diagnostic_msgs::DiagnosticStatus::WARN && input.message.find("stale input") != std::string::npos;
  })) << "last input diagnostic: " << input.message;
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_stale_clock");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
