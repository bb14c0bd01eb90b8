// demo_scenario: the odometry of a spherical robot manoeuvre (accelerate, cruise, turn, brake with slip,
// spin in place), with sensor noise, published into the contact estimator; it records every estimate,
// prints a summary per phase, writes a CSV, and ends the launch when done (endLaunch).
//
// Private parameters: rate [Hz], rolling_radius [m], noise_omega [rad/s], noise_velocity [m/s], seed,
// frame_id, child_frame_id, publish_tf, output_csv (empty: none), subscriber_timeout [s], odom_subscribers
// (to wait for; 1), and segments: a
// list of {name, duration, speed: [start, end], sliding: [start, end], lateral_sliding, yaw_rate, spin_rate}
// (see config/demo_scenario.yaml); without it, Scenario::defaultSegments().

// STL
#include <algorithm>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

// POSIX
#include <unistd.h>

// ROS
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "scenario.h"

namespace sce = sphere_contact_estimator;

namespace
{
double number(XmlRpc::XmlRpcValue& v)
{
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt)
    return static_cast<int>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble)
    return static_cast<double>(v);
  throw std::invalid_argument("expected a number");
}

// {start, end} from a number or a two-element list
void range(XmlRpc::XmlRpcValue& segment, const char* key, double& start, double& end)
{
  if (!segment.hasMember(key))
    return;
  XmlRpc::XmlRpcValue& v = segment[key];
  if (v.getType() == XmlRpc::XmlRpcValue::TypeArray && v.size() == 2)
  {
    start = number(v[0]);
    end = number(v[1]);
  }
  else
    start = end = number(v);
}

std::vector<sce::ScenarioSegment> readSegments(const ros::NodeHandle& pnh)
{
  XmlRpc::XmlRpcValue list;
  if (!pnh.getParam("segments", list))
    return sce::Scenario::defaultSegments();
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray)
    throw std::invalid_argument("~segments must be a list");
  std::vector<sce::ScenarioSegment> out;
  for (int i = 0; i < list.size(); ++i)
  {
    XmlRpc::XmlRpcValue& s = list[i];
    sce::ScenarioSegment seg;
    seg.name = s.hasMember("name") ? static_cast<std::string>(s["name"]) : "segment " + std::to_string(i);
    if (s.hasMember("duration"))
      seg.duration = number(s["duration"]);
    range(s, "speed", seg.speed_start, seg.speed_end);
    range(s, "sliding", seg.sliding_start, seg.sliding_end);
    if (s.hasMember("lateral_sliding"))
      seg.lateral_sliding = number(s["lateral_sliding"]);
    if (s.hasMember("yaw_rate"))
      seg.yaw_rate = number(s["yaw_rate"]);
    if (s.hasMember("spin_rate"))
      seg.spin_rate = number(s["spin_rate"]);
    out.push_back(seg);
  }
  return out;
}

struct PhaseStats
{
  int sent = 0, received = 0, valid = 0;
  double speed = 0.0, slip_x = 0.0, spin = 0.0, brush_force_max = 0.0, sliding_max = 0.0, rr_force = 0.0, mu_max = 0.0;
  unsigned brush_flags = 0, rr_flags = 0, flags = 0;
};

// The demo's normal end. roslaunch ends a launch by itself only when a required node ends, and reports that in red
// ("REQUIRED process has died"), as if it were a fault; a Ctrl-C ends it quietly. So, when the launch that started this
// node is roslaunch, the node asks it to end as Ctrl-C would and waits to be stopped with the rest; otherwise (or if
// that does not come) it ends, and the launch with it, as its required node.
void endLaunch()
{
  const pid_t parent = getppid();
  std::ifstream cmdline("/proc/" + std::to_string(parent) + "/cmdline");
  const std::string command((std::istreambuf_iterator<char>(cmdline)), std::istreambuf_iterator<char>());
  if (command.find("roslaunch") == std::string::npos || kill(parent, SIGINT) != 0)
  {
    std::printf("the demo is over (roslaunch reports its required node's end in red: that is how the demo ends)\n");
    return;
  }
  std::printf("the demo is over: ending the launch\n");
  std::fflush(stdout);
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && ros::WallTime::now() < give_up)
    ros::WallDuration(0.05).sleep();
}

}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "demo_scenario");
  ros::NodeHandle nh, pnh("~");
  const double rate = pnh.param("rate", 100.0);
  const double radius = pnh.param("rolling_radius", 0.1);
  const double noise_omega = pnh.param("noise_omega", 0.02), noise_velocity = pnh.param("noise_velocity", 0.005);
  const std::string frame_id = pnh.param<std::string>("frame_id", "odom");
  const std::string child_frame_id = pnh.param<std::string>("child_frame_id", "base_link");
  const bool publish_tf = pnh.param("publish_tf", true);
  const std::string csv_path = pnh.param<std::string>("output_csv", "");
  const bool ends_launch = pnh.param("ends_launch", false);  // the launch's required node (demo.launch without RViz)
  const double subscriber_timeout = pnh.param("subscriber_timeout", 10.0);
  // the estimator, and a recorder when there is one (demo.launch record:=...)
  const auto odom_subscribers = static_cast<std::uint32_t>(std::max(1, pnh.param("odom_subscribers", 1)));
  std::mt19937_64 rng(static_cast<unsigned long>(pnh.param("seed", 1)));

  std::vector<sce::ScenarioSample> samples;
  std::vector<sce::ScenarioSegment> segments;
  try
  {
    if (!(std::isfinite(rate) && rate > 0.0 && rate <= 1e5))
      throw std::invalid_argument("~rate must be in (0, 1e5] Hz");
    if (!(noise_omega >= 0.0 && noise_velocity >= 0.0))
      throw std::invalid_argument("~noise_omega and ~noise_velocity must be >= 0");
    const sce::Scenario scenario(readSegments(pnh), radius);
    segments = scenario.segments();
    samples = scenario.sample(1.0 / rate);
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("demo_scenario: %s", e.what());
    return 1;
  }

  ros::Publisher odom_pub = nh.advertise<nav_msgs::Odometry>("odom", 100);
  std::vector<sce::ContactEstimate> estimates(samples.size());
  std::vector<bool> got(samples.size(), false);
  std::map<ros::Time, std::size_t> index;  // stamp -> sample
  const auto on_estimate = [&](const sce::ContactEstimate::ConstPtr& m) {
    const auto it = index.find(m->header.stamp);
    if (it != index.end())
    {
      estimates[it->second] = *m;
      got[it->second] = true;
    }
  };
  ros::Subscriber sub = nh.subscribe<sce::ContactEstimate>("contact_estimate", 1000, on_estimate);
  tf2_ros::TransformBroadcaster broadcaster;

  // wait for the estimator, without busy-waiting forever
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(subscriber_timeout);
  while (ros::ok() && (odom_pub.getNumSubscribers() < odom_subscribers || sub.getNumPublishers() == 0) &&
         ros::WallTime::now() < deadline)
  {
    ros::spinOnce();
    ros::WallDuration(0.02).sleep();
  }
  if (odom_pub.getNumSubscribers() == 0)
  {
    ROS_FATAL("demo_scenario: nobody subscribes to %s after %.0f s", odom_pub.getTopic().c_str(), subscriber_timeout);
    return 1;
  }
  ROS_INFO("demo_scenario: %zu segments, %.1f s at %.0f Hz into %s", segments.size(), samples.back().time, rate,
           odom_pub.getTopic().c_str());

  std::normal_distribution<double> n_omega(0.0, noise_omega), n_velocity(0.0, noise_velocity);
  const ros::Time start = ros::Time::now();
  ros::Rate loop(rate);
  nav_msgs::Odometry odom;
  odom.header.frame_id = frame_id;
  odom.child_frame_id = child_frame_id;
  // the sensor noise is the odometry's own account of its uncertainty (row-major: linear x, y, z, angular x, y, z;
  // linear z is exactly 0)
  odom.twist.covariance[0] = odom.twist.covariance[7] = noise_velocity * noise_velocity;
  odom.twist.covariance[21] = odom.twist.covariance[28] = odom.twist.covariance[35] = noise_omega * noise_omega;
  for (std::size_t i = 0; i < samples.size() && ros::ok(); ++i)
  {
    const sce::ScenarioSample& s = samples[i];
    odom.header.stamp = start + ros::Duration(s.time);
    index[odom.header.stamp] = i;
    odom.pose.pose.position.x = s.position.x();
    odom.pose.pose.position.y = s.position.y();
    odom.pose.pose.position.z = radius;
    odom.pose.pose.orientation.z = std::sin(0.5 * s.yaw);
    odom.pose.pose.orientation.w = std::cos(0.5 * s.yaw);
    odom.twist.twist.angular.x = s.omega_body.x() + n_omega(rng);
    odom.twist.twist.angular.y = s.omega_body.y() + n_omega(rng);
    odom.twist.twist.angular.z = s.omega_body.z() + n_omega(rng);
    odom.twist.twist.linear.x = s.velocity_body.x() + n_velocity(rng);
    odom.twist.twist.linear.y = s.velocity_body.y() + n_velocity(rng);
    odom.twist.twist.linear.z = 0.0;
    if (publish_tf)
    {
      geometry_msgs::TransformStamped t;
      t.header = odom.header;
      t.child_frame_id = child_frame_id;
      t.transform.translation.x = odom.pose.pose.position.x;
      t.transform.translation.y = odom.pose.pose.position.y;
      t.transform.translation.z = odom.pose.pose.position.z;
      t.transform.rotation = odom.pose.pose.orientation;
      broadcaster.sendTransform(t);
    }
    odom_pub.publish(odom);
    ros::spinOnce();
    loop.sleep();
  }
  // collect the last estimates
  const ros::WallTime collect = ros::WallTime::now() + ros::WallDuration(2.0);
  while (ros::ok() && ros::WallTime::now() < collect && std::find(got.begin(), got.end(), false) != got.end())
  {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }

  std::vector<PhaseStats> phases(segments.size());
  std::ofstream csv;
  if (!csv_path.empty())
  {
    csv.open(csv_path);
    csv << "time,segment,rolling_speed,slip_x,slip_y,spin,brush_fx,brush_fy,brush_mz,sliding_fraction,max_utilisation,"
           "rr_force,mu_roll,h,regime,valid,flags,brush_flags,rr_flags,compute_time\n";
  }
  std::size_t received = 0;
  double compute = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    PhaseStats& p = phases[samples[i].segment];
    ++p.sent;
    if (!got[i])
      continue;
    ++received;
    const sce::ContactEstimate& e = estimates[i];
    ++p.received;
    p.valid += e.valid;
    p.speed += e.rolling_speed;
    p.slip_x += e.slip.x;
    p.spin += e.spin;
    p.brush_force_max = std::max(p.brush_force_max, std::hypot(e.brush_force.x, e.brush_force.y));
    p.sliding_max = std::max(p.sliding_max, e.sliding_fraction);
    p.rr_force += e.rolling_resistance.force;
    p.mu_max = std::max(p.mu_max, e.rolling_resistance.mu_roll);
    p.brush_flags |= e.brush_flags;
    p.rr_flags |= e.rolling_resistance.flags;
    p.flags |= e.flags;
    compute += e.compute_time;
    if (csv.is_open())
      csv << samples[i].time << ',' << samples[i].segment << ',' << e.rolling_speed << ',' << e.slip.x << ',' << e.slip.y
          << ',' << e.spin << ',' << e.brush_force.x << ',' << e.brush_force.y << ',' << e.brush_moment << ','
          << e.sliding_fraction << ',' << e.max_utilisation << ',' << e.rolling_resistance.force << ','
          << e.rolling_resistance.mu_roll << ',' << e.rolling_resistance.h << ',' << int(e.rolling_resistance.regime)
          << ',' << int(e.valid) << ',' << e.flags << ',' << e.brush_flags << ',' << e.rolling_resistance.flags << ','
          << e.compute_time << '\n';
  }

  std::printf("\ncontact estimator demo: %zu odometry messages, %zu estimates, mean compute time %.1f us\n",
              samples.size(), received, received ? 1e6 * compute / received : 0.0);
  std::printf("means and maxima per phase: V_r [m/s], slip_x [-], spin [1/m], |F_t| max [N], sliding share max, "
              "F_R [N], mu_roll max [mm], valid [%%]\n");
  std::printf("%-16s %5s %6s %7s %8s %9s %9s %8s %9s %6s\n", "phase", "msgs", "V_r", "slip_x", "spin", "|F_t|max",
              "sliding", "F_R", "mu_roll", "valid");
  for (std::size_t k = 0; k < phases.size(); ++k)
  {
    const PhaseStats& p = phases[k];
    const double n = std::max(p.received, 1);
    std::printf("%-16s %5d %6.2f %7.3f %8.3f %9.1f %9.2f %8.2f %9.3f %6.0f\n", segments[k].name.c_str(), p.received,
                p.speed / n, p.slip_x / n, p.spin / n, p.brush_force_max, p.sliding_max, p.rr_force / n,
                1e3 * p.mu_max, 100.0 * p.valid / n);
  }
  if (csv.is_open())
    std::printf("estimates written to %s\n", csv_path.c_str());
  const bool complete = received == samples.size();
  std::fflush(stdout);
  if (!complete)
    ROS_ERROR("demo_scenario: %zu of %zu estimates missing", samples.size() - received, samples.size());
  else if (ends_launch)
    endLaunch();
  ros::shutdown();
  return complete ? 0 : 2;
}
