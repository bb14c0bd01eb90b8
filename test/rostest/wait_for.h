#pragma once
// Shared by the rostests: wait on the wall clock for a condition that subscriber callbacks (on an AsyncSpinner)
// make true, checking it under the lock the callbacks take.

// STL
#include <functional>
#include <mutex>

// ROS
#include <ros/ros.h>

namespace sphere_contact_estimator::test
{
inline bool waitFor(std::mutex& mutex, const std::function<bool()>& done, double seconds, double poll = 0.002)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && ros::WallTime::now() < end)
  {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (done())
        return true;
    }
    ros::WallDuration(poll).sleep();
  }
  std::lock_guard<std::mutex> lock(mutex);
  return done();
}
}  // namespace sphere_contact_estimator::test
