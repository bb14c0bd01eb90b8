#pragma once
// Shared by the rostests: the odometry of the demo robot rolling forwards (config/contact_estimator.yaml).

// ROS
#include <nav_msgs/Odometry.h>

namespace sphere_contact_estimator::test
{
/// Rolling about +y at 10 rad/s (1 m/s at the parameter file's rolling radius) with the contact centre moving at
/// `v_x` [m/s] along x (1.0: no longitudinal slip), in frame odom / base_link with an identity orientation.
inline nav_msgs::Odometry rollingOdometry(double v_x)
{
  nav_msgs::Odometry o;
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.pose.pose.orientation.w = 1.0;
  o.twist.twist.angular.y = 10.0;
  o.twist.twist.linear.x = v_x;
  return o;
}
}  // namespace sphere_contact_estimator::test
