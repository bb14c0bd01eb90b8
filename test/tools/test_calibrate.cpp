// calibrate and calibration_bag as a user runs them (issue 23): a run of a robot with known parameters written as a bag,
// the fit from it, the parameter file the node loads (the round trip), the report, and the errors for bags it cannot
// use (no IMU topic, no odometry, an IMU at another rate).

// STL
#include <cmath>
#include <cstdio>
#include <string>

// GTest
#include <gtest/gtest.h>

// ROS
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>

// Package
#include "sphere_contact_estimator/core/calibration/contact_fit.h"
#include "sphere_contact_estimator/ros/calibration_recording.h"
#include "sphere_contact_estimator/ros/config_file.h"
#include "sphere_contact_estimator/ros/config_settings.h"
#include "../command_outcome.h"

namespace sce = sphere_contact_estimator;
using sce::test::Outcome;
using sce::test::runCommand;
using sce::test::slurp;

namespace
{
const std::string kDir = "/tmp/sce_test_calibrate";
const std::string kParams = std::string(PACKAGE_SOURCE_DIR) + "/config/contact_estimator.yaml";

// A copy of a bag with the odometry or the IMU left out, the IMU thinned to every imu_every-th message, and the IMU
// left out over [gap_from, gap_to) seconds after the bag's start.
void filterBag(const std::string& in, const std::string& out, bool keep_odometry, bool keep_imu, int imu_every = 1,
               double gap_from = 0.0, double gap_to = 0.0)
{
  rosbag::Bag src(in), dst(out, rosbag::bagmode::Write);
  rosbag::View all(src);
  const ros::Time start = all.getBeginTime();
  int n = 0;
  for (const rosbag::MessageInstance& m : all)
  {
    if (m.getTopic() == "/odom" && keep_odometry)
      dst.write(m.getTopic(), m.getTime(), m);
    const double t = (m.getTime() - start).toSec();
    if (m.getTopic() == "/imu" && keep_imu && n++ % imu_every == 0 && !(t >= gap_from && t < gap_to))
      dst.write(m.getTopic(), m.getTime(), m);
  }
}

class Calibrate : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    ros::Time::init();
    std::system(("mkdir -p " + kDir).c_str());
    // a 3-kg robot with k = 1.5e8, mu = 0.6, half the bundled manoeuvre
    const Outcome r = runCommand(std::string(CALIBRATION_BAG_PATH) + " -p " + kParams +
                                 " --set robot_mass=3 --set bristle_stiffness=1.5e8 --set friction=0.6 --seed 5"
                                 " --duration-scale 0.5 -o " + kDir + "/run.bag");
    ASSERT_EQ(r.status, 0) << r.out << r.err;
  }
};
}  // namespace

TEST_F(Calibrate, FitsARunAndTheNodeLoadsTheFile)
{
  const Outcome r = runCommand(std::string(CALIBRATE_PATH) + " -i " + kDir + "/run.bag -p " + kParams +
                               " --set robot_mass=3 --fit bristle_stiffness,friction,surface_damping -o " + kDir +
                               "/fitted.yaml --report " + kDir + "/report");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  for (const char* line : { "odometry messages in the fit", "not in the fit:", "bristle_stiffness", "friction",
                            "surface_damping", "surface_stiffness and surface_density: NOT determined (held)",
                            "reduced chi-square", "determined" })
    EXPECT_NE(r.out.find(line), std::string::npos) << line << " missing in\n" << r.out;
  // the file loads as the node's parameters, with the fitted values near the truth and the robot's own kept
  sce::ContactEstimatorConfig c = sce::ContactEstimatorConfig::__getDefault__();
  ASSERT_NO_THROW(sce::applyParameterFile(c, kDir + "/fitted.yaml"));
  EXPECT_NEAR(c.bristle_stiffness / 1.5e8, 1.0, 0.05) << slurp(kDir + "/fitted.yaml");
  EXPECT_NEAR(c.friction / 0.6, 1.0, 0.02);
  // the floor's damping (its relaxation time, the floor's stiffness held): the run's is the file's 1e5, within its
  // interval where determined, else the file's value as it was
  EXPECT_NEAR(c.surface_damping / 1e5, 1.0, 0.5) << slurp(kDir + "/fitted.yaml");
  EXPECT_EQ(c.robot_mass, 3.0);
  const std::string yaml = slurp(kDir + "/fitted.yaml");
  EXPECT_EQ(yaml.rfind("# Fitted by calibrate from 1 bag(s):\n", 0), 0u) << yaml.substr(0, 200);
  for (const char* part : { "speeds ", "slips up to", "reduced chi-square", "bristle_stiffness: ", "# fitted: sd " })
    EXPECT_NE(yaml.find(part), std::string::npos) << part;
  // the round trip: the node's estimator with the loaded file predicts the bag's forces (the IMU's) as well as the
  // fitted model does, and better than the file the fit started from (k 2e8, mu 0.8 and the floor as given)
  {
    sce::CalibrationReadOptions read;
    read.config = c;
    const sce::CalibrationRecording rec = sce::readCalibrationBags({ kDir + "/run.bag" }, read);
    sce::ContactEstimatorConfig start = sce::ContactEstimatorConfig::__getDefault__();
    sce::applyParameterFile(start, kParams);
    start.robot_mass = 3.0;
    const auto rms = [&](const sce::ContactEstimatorConfig& config) {
      const sce::Prediction p = sce::predictForces(rec.samples, sce::settingsFromConfig(config));
      double sum = 0.0;
      int n = 0;
      for (std::size_t i = 0; i < rec.samples.size(); ++i)
        if (p.answered[i] && rec.samples[i].has_force && p.sliding[i] > 0.5)  // where the slips' noise matters least
        {
          sum += (rec.samples[i].force - p.force[i]).squaredNorm();
          ++n;
        }
      EXPECT_GT(n, 50);
      return std::sqrt(sum / std::max(n, 1));
    };
    sce::ContactEstimatorConfig truth = start;
    truth.bristle_stiffness = 1.5e8;
    truth.friction = 0.6;
    // (the node predicts from the measured, noisy slips and lags in the speed's ramps, so even the truth's prediction
    // is off by more than the IMU's noise: the fitted file's is to match it)
    const double fitted = rms(c), before = rms(start), best = rms(truth);
    EXPECT_LT(fitted, 0.5 * before) << fitted << " N against " << before << " N";
    EXPECT_LT(fitted, 1.05 * best) << fitted << " N against the truth's " << best << " N";
  }
  // the report: every message in the CSV, and its figures
  const std::string csv = slurp(kDir + "/report/calibration.csv");
  EXPECT_NE(csv.find("\nt,used,rejection,speed,"), std::string::npos);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n') - std::count(csv.begin(), csv.end(), '#'), 977);  // 976 rows
  for (const char* png : { "force_time.png", "force_slip.png", "residuals.png", "coverage.png" })
    EXPECT_FALSE(slurp(kDir + "/report/" + png).empty()) << png;
}

TEST_F(Calibrate, SaysWhatIsWrongWithABag)
{
  const std::string tool = std::string(CALIBRATE_PATH) + " -p " + kParams + " -o " + kDir + "/x.yaml -i ";
  filterBag(kDir + "/run.bag", kDir + "/no_imu.bag", true, false);
  Outcome r = runCommand(tool + kDir + "/no_imu.bag");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no sensor_msgs/Imu topic in the bag"), std::string::npos) << r.err;
  r = runCommand(tool + kDir + "/run.bag --imu-topic /imu_nope");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no sensor_msgs/Imu topic /imu_nope"), std::string::npos) << r.err;
  filterBag(kDir + "/run.bag", kDir + "/no_odom.bag", false, true);
  r = runCommand(tool + kDir + "/no_odom.bag");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no nav_msgs/Odometry topic in the bag"), std::string::npos) << r.err;
  r = runCommand(tool + kDir + "/missing.bag");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no such bag or directory: " + kDir + "/missing.bag"), std::string::npos) << r.err;
}

TEST_F(Calibrate, AnImuAtAnotherRateIsInterpolatedToTheOdometry)
{
  // the IMU at a third of the odometry's rate (33 Hz): each odometry stamp between two IMU samples within the gap
  filterBag(kDir + "/run.bag", kDir + "/slow_imu.bag", true, true, 3);
  const Outcome r = runCommand(std::string(CALIBRATE_PATH) + " -i " + kDir + "/slow_imu.bag -p " + kParams +
                               " --set robot_mass=3 --set friction=0.6 --fit bristle_stiffness -o " + kDir + "/slow.yaml");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("IMU 33 Hz"), std::string::npos) << r.out;
  sce::ContactEstimatorConfig c = sce::ContactEstimatorConfig::__getDefault__();
  sce::applyParameterFile(c, kDir + "/slow.yaml");
  EXPECT_NEAR(c.bristle_stiffness / 1.5e8, 1.0, 0.1);
  EXPECT_EQ(c.friction, 0.6) << "not fitted: as given";
}

TEST_F(Calibrate, AWrongRollingRadiusIsCalledOut)
{
  // the run's sphere is 0.1 m; a parameter file that says 0.1005 biases every slip by half a per cent, which the fit
  // can only read as stiffness: the values come out wrong, and the summary and the file say the run is not the model's
  const std::string tool = std::string(CALIBRATE_PATH) + " -i " + kDir + "/run.bag -p " + kParams +
                           " --set robot_mass=3 --set friction=0.6 --fit bristle_stiffness";
  const Outcome ok = runCommand(tool + " -o " + kDir + "/right.yaml");
  ASSERT_EQ(ok.status, 0) << ok.out << ok.err;
  EXPECT_EQ(ok.out.find("WARNING"), std::string::npos) << ok.out;
  const Outcome r = runCommand(tool + " --set rolling_radius=0.1005 -o " + kDir + "/wrong_radius.yaml");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("WARNING: the reduced chi-square is"), std::string::npos) << r.out;
  EXPECT_NE(slurp(kDir + "/wrong_radius.yaml").find("# WARNING: the reduced chi-square is"), std::string::npos);
}

TEST_F(Calibrate, GapsInTheImuAreCountedAndNamed)
{
  // the IMU silent for a second in the middle of the run: the odometry there has nothing to compare with
  filterBag(kDir + "/run.bag", kDir + "/imu_gap.bag", true, true, 1, 4.0, 5.0);
  const Outcome r = runCommand(std::string(CALIBRATE_PATH) + " -i " + kDir + "/imu_gap.bag -p " + kParams +
                               " --set robot_mass=3 --set friction=0.6 --fit bristle_stiffness -o " + kDir +
                               "/gap.yaml");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("no IMU sample paired"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("have no IMU sample on /imu within 50 ms"), std::string::npos) << r.out;
  EXPECT_NE(slurp(kDir + "/gap.yaml").find("# WARNING: "), std::string::npos);
  // about a second at 100 Hz (the interpolation reaches 50 ms into the gap from each side)
  const std::size_t at = r.out.find(" odometry messages (");
  ASSERT_NE(at, std::string::npos);
  const int count = std::atoi(r.out.c_str() + r.out.rfind(' ', at - 1) + 1);
  EXPECT_GE(count, 85) << r.out;
  EXPECT_LE(count, 105) << r.out;
}
