// calibration_bag: a recorded run of a spherical robot with known contact parameters, as calibrate reads one. The
// odometry (nav_msgs/Odometry on /odom, twist in the body frame with the demo's noise and its covariance) and an IMU at
// the sphere's centre (sensor_msgs/Imu on /imu: the specific force of the models' force over the robot's mass, gravity
// included, in the body frame, with noise and its covariance; the body's orientation), from the bundled calibration
// manoeuvre (src/scenario/calibration_run.h). Errors: a message on stderr and exit status 2.
//
//   calibration_bag --params truth.yaml --output run.bag [--seed 1] [--rate 100] [--imu-noise 0.05] [--imu-bias X,Y]

// STL
#include <cmath>
#include <iostream>

// CLI11
#include <CLI/CLI.hpp>

// ROS
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>

// Package
#include "calibration_run.h"
#include "sphere_contact_estimator/ros/config_file.h"
#include "sphere_contact_estimator/ros/config_settings.h"

namespace sce = sphere_contact_estimator;

int main(int argc, char** argv)
{
  CLI::App app{ "calibration_bag: a recorded run (odometry and IMU) of a spherical robot with known contact parameters, "
                "for calibrate" };
  std::string params, output;
  sce::CalibrationNoise noise;
  double rate = 100.0, duration_scale = 1.0;
  std::vector<double> bias;
  std::vector<std::string> sets;
  app.add_option("--params,-p", params, "the robot's true parameters (the node's format; default: the package's)");
  app.add_option("--set", sets, "NAME=VALUE: one parameter, after the file (repeatable)");
  app.add_option("--output,-o", output, "bag to write")->required();
  app.add_option("--seed", noise.seed, "of the noise");
  app.add_option("--rate", rate, "odometry and IMU rate [Hz]")->check(CLI::PositiveNumber);
  app.add_option("--imu-noise", noise.imu, "IMU noise, sd on each axis [m/s^2]")->check(CLI::NonNegativeNumber);
  app.add_option("--odom-noise", noise.velocity, "odometry velocity noise, sd [m/s] (angular: 4x this in rad/s)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--imu-bias", bias, "a constant bias on the IMU's horizontal axes, X,Y [m/s^2]")->delimiter(',')->expected(2);
  app.add_option("--duration-scale", duration_scale, "every segment this many times as long")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  noise.omega = 4.0 * noise.velocity;
  if (bias.size() == 2)
    noise.imu_bias = Eigen::Vector2d(bias[0], bias[1]);
  try
  {
    ros::Time::init();
    sce::ContactEstimatorConfig config = sce::ContactEstimatorConfig::__getDefault__();
    if (params.empty())
      params = sce::defaultParameterFile();
    sce::applyParameterFile(config, params);
    sce::applyParameterSets(config, sets);
    const sce::EstimatorSettings truth = sce::settingsFromConfig(config);
    std::vector<sce::ScenarioSegment> segments = sce::calibrationSegments();
    for (auto& s : segments)
      s.duration *= duration_scale;
    const sce::Scenario scenario(segments, truth.rolling_radius);
    const std::vector<sce::CalibrationMessage> run = sce::calibrationRun(scenario, truth, rate, noise);

    rosbag::Bag bag;
    bag.open(output, rosbag::bagmode::Write);
    bag.setCompression(rosbag::compression::BZ2);  // a tenth of the size, for a bag bundled with the package
    std::uint32_t seq = 0;
    for (const sce::CalibrationMessage& m : run)
    {
      const ros::Time stamp(m.stamp);
      const double h = 0.5 * m.yaw;
      nav_msgs::Odometry o;
      o.header.stamp = stamp;
      o.header.seq = seq;
      o.header.frame_id = "odom";
      o.child_frame_id = "base_link";
      o.pose.pose.position.x = m.position.x();
      o.pose.pose.position.y = m.position.y();
      o.pose.pose.position.z = truth.rolling_radius;
      o.pose.pose.orientation.z = std::sin(h);
      o.pose.pose.orientation.w = std::cos(h);
      o.twist.twist.linear.x = m.velocity_body.x();
      o.twist.twist.linear.y = m.velocity_body.y();
      o.twist.twist.linear.z = m.velocity_body.z();
      o.twist.twist.angular.x = m.omega_body.x();
      o.twist.twist.angular.y = m.omega_body.y();
      o.twist.twist.angular.z = m.omega_body.z();
      for (int i = 0; i < 3; ++i)
      {
        o.twist.covariance[i * 7] = noise.velocity * noise.velocity;
        o.twist.covariance[(i + 3) * 7] = noise.omega * noise.omega;
      }
      bag.write("/odom", stamp, o);
      sensor_msgs::Imu imu;
      imu.header.stamp = stamp;
      imu.header.seq = seq++;
      imu.header.frame_id = "base_link";
      imu.orientation = o.pose.pose.orientation;
      imu.orientation_covariance[0] = imu.orientation_covariance[4] = imu.orientation_covariance[8] = 1e-6;
      imu.linear_acceleration.x = m.specific_force_body.x();
      imu.linear_acceleration.y = m.specific_force_body.y();
      imu.linear_acceleration.z = m.specific_force_body.z();
      const double var = std::max(noise.imu * noise.imu, 1e-12);
      imu.linear_acceleration_covariance[0] = imu.linear_acceleration_covariance[4] =
          imu.linear_acceleration_covariance[8] = var;
      imu.angular_velocity_covariance[0] = -1.0;  // not given
      bag.write("/imu", stamp, imu);
    }
    bag.close();
    std::printf("calibration_bag: %zu odometry and IMU messages (%.1f s at %.0f Hz) written to %s; truth: "
                "bristle_stiffness %.6g, friction %.6g\n",
                run.size(), scenario.duration(), rate, output.c_str(), truth.bristle_stiffness, truth.friction);
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "calibration_bag: error: " << e.what() << "\n";
    return 2;
  }
}
