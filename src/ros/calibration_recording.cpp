#include "sphere_contact_estimator/ros/calibration_recording.h"

// STL
#include <algorithm>
#include <cmath>
#include <stdexcept>

// ROS
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/Imu.h>
#include <tf2/exceptions.h>
#include <tf2_eigen/tf2_eigen.h>

// Package
#include "sphere_contact_estimator/ros/bag_reading.h"
#include "sphere_contact_estimator/ros/config_settings.h"
#include "sphere_contact_estimator/ros/odometry_estimator.h"

namespace sphere_contact_estimator
{
namespace
{
struct ImuSample
{
  double t;
  Eigen::Vector3d f;  // specific force, ground frame [m/s^2]
  double variance;    // the message's, mean of x and y (0: none given)
};

double median(std::vector<double> v)
{
  if (v.empty())
    return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
}  // namespace

CalibrationRecording readCalibrationBags(const std::vector<std::string>& bags, const CalibrationReadOptions& options)
{
  CalibrationRecording out;
  const EstimatorSettings settings = settingsFromConfig(options.config);
  const double mass = settings.load > 0.0 ? settings.load / settings.gravity : settings.robot_mass;
  std::vector<double> variances, differences, periods;
  double offset = 0.0;  // added to each bag's stamps: the next bag starts after a gap
  for (std::size_t b = 0; b < bags.size(); ++b)
  {
    const std::string& path = bags[b];
    out.bags.push_back(path);
    const BagPtr bag = openBag(path);
    rosbag::View all(*bag);
    std::string odom_topic, imu_topic;
    try
    {
      odom_topic = topicOfType(all, "nav_msgs/Odometry", options.odom_topic, "--odom-topic");
      imu_topic = topicOfType(all, "sensor_msgs/Imu", options.imu_topic, "--imu-topic");
    }
    catch (const std::runtime_error& e)
    {
      throw std::runtime_error(path + ": " + e.what());
    }
    if (b == 0)
    {
      out.odom_topic = odom_topic;
      out.imu_topic = imu_topic;
    }
    // tf first (static and dynamic: the bag is read whole, so every transform is there when asked)
    tf2::BufferCore tf(ros::Duration(std::max(60.0, (all.getEndTime() - all.getBeginTime()).toSec() + 1.0)));
    for (const rosbag::MessageInstance& m : rosbag::View(*bag, rosbag::TopicQuery(std::vector<std::string>{ "/tf", "/tf_static" })))
      if (const auto msg = m.instantiate<tf2_msgs::TFMessage>())
        addTransforms(tf, *msg, m.getTopic() == "/tf_static");

    OdometryEstimator odometry(options.config);
    std::vector<ImuSample> imu;
    std::vector<nav_msgs::Odometry::ConstPtr> odom;
    // the ground frame: the parameters', else the odometry's (needed before the first IMU sample's tf lookup)
    std::string ground = options.config.ground_frame;
    for (const rosbag::MessageInstance& m : rosbag::View(*bag, rosbag::TopicQuery(odom_topic)))
      if (const auto o = m.instantiate<nav_msgs::Odometry>(); o && ground.empty())
      {
        ground = o->header.frame_id;
        break;
      }
    for (const rosbag::MessageInstance& m : rosbag::View(*bag, rosbag::TopicQuery(std::vector<std::string>{ odom_topic, imu_topic })))
    {
      if (m.getTopic() == odom_topic)
      {
        if (const auto o = m.instantiate<nav_msgs::Odometry>())
          odom.push_back(o);
        continue;
      }
      const auto msg = m.instantiate<sensor_msgs::Imu>();
      if (!msg)
        continue;
      ++out.imu_messages;
      Eigen::Quaterniond q;
      const auto& o = msg->orientation;
      const double norm = std::sqrt(o.x * o.x + o.y * o.y + o.z * o.z + o.w * o.w);
      if (msg->orientation_covariance[0] != -1.0 && std::abs(norm - 1.0) < 1e-3)
        q = Eigen::Quaterniond(o.w, o.x, o.y, o.z).normalized();
      else
      {
        // the IMU's frame in the ground frame from tf (the ground frame: the odometry's, which may come later)
        try
        {
          const auto t = tf.lookupTransform(ground, msg->header.frame_id, msg->header.stamp);
          q = tf2::transformToEigen(t).rotation();
        }
        catch (const tf2::TransformException&)
        {
          ++out.imu_without_orientation;
          continue;
        }
      }
      const Eigen::Vector3d a(msg->linear_acceleration.x, msg->linear_acceleration.y, msg->linear_acceleration.z);
      const double var = 0.5 * (msg->linear_acceleration_covariance[0] + msg->linear_acceleration_covariance[4]);
      imu.push_back({ odometry.secondsSinceEpoch(msg->header.stamp), q * a, var > 0.0 ? var : 0.0 });  // (the odometry's clock)
    }
    if (odom.empty())
      throw std::runtime_error(path + ": no message on the odometry topic " + odom_topic);
    if (imu.empty())
      throw std::runtime_error(path + ": no usable message on the IMU topic " + imu_topic +
                               (out.imu_without_orientation > 0 ? " (none had an orientation, in the message or in tf)" : ""));
    std::sort(imu.begin(), imu.end(), [](const ImuSample& x, const ImuSample& y) { return x.t < y.t; });
    for (std::size_t i = 0; i < imu.size(); ++i)
    {
      if (imu[i].variance > 0.0)
        variances.push_back(imu[i].variance);
      if (i > 0)
      {
        periods.push_back(imu[i].t - imu[i - 1].t);
        differences.push_back(std::abs(imu[i].f.x() - imu[i - 1].f.x()));
        differences.push_back(std::abs(imu[i].f.y() - imu[i - 1].f.y()));
      }
    }
    // each odometry message, and the IMU interpolated to its stamp
    const double first = odometry.secondsSinceEpoch(odom.front()->header.stamp);
    const double start = b == 0 ? 0.0 : offset;
    double last = first;
    std::size_t j = 0;
    for (const auto& o : odom)
    {
      CalibrationSample s;
      Eigen::Vector3d centre;
      bool have_centre = false;
      if (!odometry.toInput(*o, tf, s.input, centre, have_centre))
      {
        ++out.odometry_without_orientation;
        continue;
      }
      const double t = s.input.stamp;
      while (j + 1 < imu.size() && imu[j + 1].t < t)
        ++j;
      if (j + 1 < imu.size() && imu[j].t <= t && imu[j + 1].t >= t && imu[j + 1].t - imu[j].t <= 2.0 * options.max_imu_gap &&
          std::min(t - imu[j].t, imu[j + 1].t - t) <= options.max_imu_gap)
      {
        const double w = imu[j + 1].t > imu[j].t ? (t - imu[j].t) / (imu[j + 1].t - imu[j].t) : 0.0;
        const Eigen::Vector3d f = (1.0 - w) * imu[j].f + w * imu[j + 1].f;
        s.force = forceFromSpecificForce(f, mass);
        s.has_force = true;
      }
      s.input.stamp = t - first + start;
      last = t;
      out.samples.push_back(s);
      out.time.push_back(t - first);
      out.bag.push_back(static_cast<int>(b));
    }
    offset = start + (last - first) + 2.0 * settings.max_step + 1.0;
  }
  // the IMU's noise: as asked, as the messages declare it, or from the run (successive differences of a slowly
  // changing signal: their spread is sqrt(2) times the noise's; the median is robust to the manoeuvres' steps)
  if (options.imu_noise > 0.0)
  {
    out.imu_noise = options.imu_noise;
    out.imu_noise_source = "option";
  }
  else if (!variances.empty())
  {
    out.imu_noise = std::sqrt(median(variances));
    out.imu_noise_source = "messages' covariance";
  }
  else
  {
    out.imu_noise = 1.4826 * median(differences) / std::sqrt(2.0);
    out.imu_noise_source = "estimated from the run";
  }
  if (!(out.imu_noise > 0.0))
    throw std::runtime_error("the IMU's noise is zero or unknown: give --imu-noise");
  out.imu_rate = periods.empty() ? 0.0 : 1.0 / std::max(median(periods), 1e-9);
  for (CalibrationSample& s : out.samples)
    s.force_sd = mass * out.imu_noise;
  return out;
}

}  // namespace sphere_contact_estimator
