// The mistakes a new user makes in the first hour are said, not swallowed (issue 22): an unknown parameter, the
// effective configuration, the launch file's arguments, the shipped parameter file through `dynparam load`, every
// enum name through `dynparam set`, what a reconfiguration changed, a value the server set to an end of its range,
// the body's yaw rate published as the shell's omega, and a reset's heading.

// STL
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <functional>
#include <mutex>
#include <string>
#include <unistd.h>
#include <vector>

// GTest
#include <gtest/gtest.h>

// ROS
#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/ros/parameter_enum.h"
#include "rolling_odometry.h"
#include "wait_for.h"

namespace sce = sphere_contact_estimator;

namespace
{
// What the test sees of the node: the log (/rosout), the server's configuration, the estimates, the diagnostics.
struct Watch
{
  std::mutex mutex;
  std::vector<rosgraph_msgs::Log> log;
  dynamic_reconfigure::Config config;
  bool have_config = false;
  std::vector<sce::ContactEstimate> estimates;
  diagnostic_msgs::DiagnosticStatus input;
  ros::Subscriber log_sub, config_sub, estimate_sub, diag_sub;

  explicit Watch(ros::NodeHandle& nh)
  {
    log_sub = nh.subscribe<rosgraph_msgs::Log>("/rosout", 1000, [this](const rosgraph_msgs::Log::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      log.push_back(*m);
    });
    config_sub = nh.subscribe<dynamic_reconfigure::Config>(
        "/contact_estimator/parameter_updates", 10, [this](const dynamic_reconfigure::Config::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          config = *m;
          have_config = true;
        });
    estimate_sub = nh.subscribe<sce::ContactEstimate>("/contact_estimate", 1000, [this](const sce::ContactEstimate::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      estimates.push_back(*m);
    });
    diag_sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 100, [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          for (const auto& s : m->status)
            if (s.name == "contact_estimator: odometry input")
              input = s;
        });
  }
  bool wait(double seconds, const std::function<bool()>& done) { return sce::test::waitFor(mutex, done, seconds, 0.01); }
  // a log line of `node` at `level` holding every one of `parts` (under the lock)
  bool logged(const std::string& node, std::uint8_t level, const std::vector<std::string>& parts) const
  {
    for (const rosgraph_msgs::Log& m : log)
    {
      if (m.name != node || m.level != level)
        continue;
      bool all = true;
      for (const std::string& p : parts)
        all = all && m.msg.find(p) != std::string::npos;
      if (all)
        return true;
    }
    return false;
  }
  std::string logText() const
  {
    std::string text;
    for (const rosgraph_msgs::Log& m : log)
      text += m.name + ": " + m.msg + "\n";
    return text;
  }
  double number(const std::string& name) const
  {
    for (const auto& d : config.doubles)
      if (d.name == name)
        return d.value;
    for (const auto& i : config.ints)
      if (i.name == name)
        return i.value;
    return NAN;
  }
};

// dynparam with Debian's python (a python3 first on PATH, pyenv or conda, lacks the ROS modules)
int dynparam(const std::string& args)
{
  const std::string python = access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
  return std::system(("rosrun --prefix '" + python + "' dynamic_reconfigure dynparam " + args + " > /dev/null 2>&1").c_str());
}

class FirstHour : public testing::Test
{
protected:
  ros::NodeHandle nh;
  Watch watch{ nh };
  void SetUp() override
  {
    ASSERT_TRUE(watch.wait(30.0, [&] { return watch.have_config; })) << "no configuration from the node";
  }
};

TEST_F(FirstHour, TheLaunchFilesArgumentsApply)
{
  std::lock_guard<std::mutex> lock(watch.mutex);
  EXPECT_EQ(watch.number("rolling_radius"), 0.15);
  EXPECT_EQ(watch.number("robot_mass"), 3.0);
  EXPECT_EQ(watch.number("brush_model"), 2.0);
  EXPECT_EQ(watch.number("friction"), 0.8);  // not an argument given: the parameter file's
}

// The node's own console output (a node's first lines reach /rosout only once a subscriber has connected).
std::string readFile(const std::string& path)
{
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool holdsAll(const std::string& text, const std::vector<std::string>& parts)
{
  return std::all_of(parts.begin(), parts.end(),
                     [&](const std::string& p) { return text.find(p) != std::string::npos; });
}

TEST_F(FirstHour, AnUnknownParameterIsAWarningThatNamesTheNearestAndTheConfigurationIsLogged)
{
  // a second node, as a user would start it by hand with a typo
  const std::string base = "/tmp/sce_typo_node_" + std::to_string(getpid()), out = base + ".log", pid = base + ".pid";
  ASSERT_EQ(std::system(("stdbuf -oL rosrun sphere_contact_estimator contact_estimator_node __name:=typo_node _rolling_raduis:=0.15 "
                         "_robot_mass:=3 odom:=/typo_odom > " + out + " 2>&1 & echo $! > " + pid).c_str()),
            0);
  const auto has = [&](const std::vector<std::string>& parts) { return holdsAll(readFile(out), parts); };
  const bool warned = watch.wait(30.0, [&] { return has({ "WARN", "unknown parameter /typo_node/rolling_raduis ignored; did you mean rolling_radius?" }); });
  const bool configured = watch.wait(10.0, [&] { return has({ "configuration (R_r = 0.1 m, F_z = 29.43 N", "robot_mass 3,", "brush_model auto," }); });
  const std::string text = readFile(out);
  std::system(("kill -INT $(cat " + pid + ") 2> /dev/null; rm -f " + pid + " " + out).c_str());
  EXPECT_TRUE(warned) << text;
  EXPECT_TRUE(configured) << text;
}

TEST_F(FirstHour, ParametersRejectedAtStartUpAreAnErrorInTheDiagnosticsUntilAConfigurationIsAccepted)
{
  // A second node started with parameters the estimator rejects as a whole (a fixed transient lattice with tilt that
  // the default work budget cannot pay for, beside a friction of 0.5): the log says why and that none of them is in
  // force, and the diagnostics say so as an ERROR until a configuration is accepted (before, one log line, and the
  // node ran on the defaults: a friction of 0.8).
  const std::string base = "/tmp/sce_rejected_node_" + std::to_string(getpid());
  const std::string out = base + ".log", pid = base + ".pid";
  std::mutex mutex;
  diagnostic_msgs::DiagnosticStatus models;
  bool seen = false;
  ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& s : m->status)
          if (s.name == "rejected_node: contact models")
          {
            models = s;
            seen = true;
          }
      });
  ASSERT_EQ(std::system(("stdbuf -oL rosrun sphere_contact_estimator contact_estimator_node __name:=rejected_node "
                         "_brush_model:=3 _resolution:=64 _tilt:=true _friction:=0.5 odom:=/rejected_odom > " + out +
                         " 2>&1 & echo $! > " + pid).c_str()),
            0);
  const auto has = [&](const std::vector<std::string>& parts) { return holdsAll(readFile(out), parts); };
  const bool logged = watch.wait(30.0, [&] {
    return has({ "ERROR", "configuration rejected", "work_budget = 100000", "resolution 64 with tilt",
                 "it needs at least 111334", "none of the parameters is in force" });
  });
  const auto level = [&](std::uint8_t wanted, const std::string& part) {
    return sce::test::waitFor(mutex, [&] { return seen && models.level == wanted &&
                                                  models.message.find(part) != std::string::npos; }, 10.0, 0.01);
  };
  const bool error = level(diagnostic_msgs::DiagnosticStatus::ERROR, "rejected at start-up");
  // a configuration accepted (the defaults with another budget): the ERROR goes
  const bool set = dynparam("set /rejected_node work_budget 200000") == 0;
  const bool cleared = sce::test::waitFor(
      mutex, [&] { return seen && models.level != diagnostic_msgs::DiagnosticStatus::ERROR; }, 10.0, 0.01);
  const std::string text = readFile(out);
  std::system(("kill -INT $(cat " + pid + ") 2> /dev/null; rm -f " + pid + " " + out).c_str());
  EXPECT_TRUE(logged) << text;
  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_TRUE(error) << "level " << static_cast<int>(models.level) << ": " << models.message;
  EXPECT_TRUE(set);
  EXPECT_TRUE(cleared) << "level " << static_cast<int>(models.level) << ": " << models.message;
}

TEST_F(FirstHour, EveryEnumIsADropDownInTheDescriptionRqtReads)
{
  // rqt_reconfigure draws a drop-down for a parameter whose published edit_method is set, and fills it with the
  // 'name' and 'value' of each entry of its 'enum' list: the description the node latches, as rqt receives it
  dynamic_reconfigure::ConfigDescription description;
  bool received = false;
  std::mutex mutex;
  ros::Subscriber sub = nh.subscribe<dynamic_reconfigure::ConfigDescription>(
      "/contact_estimator/parameter_descriptions", 1, [&](const dynamic_reconfigure::ConfigDescription::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        description = *m;
        received = true;
      });
  ASSERT_TRUE(sce::test::waitFor(mutex, [&] { return received; }, 10.0, 0.01)) << "no description latched";
  std::lock_guard<std::mutex> lock(mutex);
  std::vector<std::string> drop_downs;
  for (const auto& group : description.groups)
    for (const auto& parameter : group.parameters)
      if (!parameter.edit_method.empty())
      {
        EXPECT_EQ(parameter.type, "int") << parameter.name;
        const std::vector<sce::EnumValue> values = sce::enumValues(parameter.edit_method);
        EXPECT_GE(values.size(), 2u) << parameter.name << ": " << parameter.edit_method;
        EXPECT_NE(parameter.edit_method.find("'enum'"), std::string::npos) << parameter.edit_method;
        drop_downs.push_back(parameter.name);
      }
  // the .cfg's five enums, and only they
  std::sort(drop_downs.begin(), drop_downs.end());
  EXPECT_EQ(drop_downs, (std::vector<std::string>{ "brush_model", "pressure", "rolling_resistance_model", "sliding_law",
                                                    "tilt_ratio_source" }));
}

TEST_F(FirstHour, TheShippedParameterFileLoadsWithDynparamAndEveryEnumNameWorks)
{
  std::string package_dir;
  ASSERT_TRUE(ros::param::get("~package_dir", package_dir));
  ASSERT_EQ(dynparam("load /contact_estimator " + package_dir + "/config/contact_estimator.yaml"), 0);
  EXPECT_TRUE(watch.wait(10.0, [&] { return watch.number("rolling_radius") == 0.1 && watch.number("robot_mass") == 5.0; }))
      << "the file's values did not arrive";
  {
    std::lock_guard<std::mutex> lock(watch.mutex);
    EXPECT_EQ(watch.number("brush_model"), 4.0);  // auto, by name in the file
  }
  // every name of every enum of the .cfg, in lower case as the README lists them
  for (const auto& d : sce::ContactEstimatorConfig::__getParamDescriptions__())
    for (const sce::EnumValue& v : sce::enumValues(d->edit_method))
    {
      std::string name = v.name;
      for (char& c : name)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      // away from the value first, so that the update shows the name's own
      const sce::EnumValue other = sce::enumValues(d->edit_method).at(v.value == 0 ? 1 : 0);
      bool there = false;
      {
        std::lock_guard<std::mutex> lock(watch.mutex);
        there = watch.number(d->name) == v.value;
      }
      if (there)
      {
        ASSERT_EQ(dynparam("set /contact_estimator " + d->name + " " + std::to_string(other.value)), 0);
        ASSERT_TRUE(watch.wait(10.0, [&] { return watch.number(d->name) == other.value; })) << d->name;
      }
      EXPECT_EQ(dynparam("set /contact_estimator " + d->name + " " + name), 0) << d->name << " " << name;
      EXPECT_TRUE(watch.wait(10.0, [&] { return watch.number(d->name) == v.value; })) << d->name << " " << name;
    }
}

TEST_F(FirstHour, AReconfigurationSaysWhatChangedAndWhenTheServerSetARangesEnd)
{
  ASSERT_EQ(dynparam("set /contact_estimator friction 0.55"), 0);
  ASSERT_TRUE(watch.wait(10.0, [&] { return watch.number("friction") == 0.55; }));
  ASSERT_EQ(dynparam("set /contact_estimator friction 0.65"), 0);
  EXPECT_TRUE(watch.wait(10.0, [&] {
    return watch.logged("/contact_estimator", rosgraph_msgs::Log::INFO, { "reconfigured: friction 0.55 -> 0.65" });
  })) << watch.logText();
  // a friction of -1: the server sets the range's end before the node sees it; the node says so
  ASSERT_EQ(dynparam("set /contact_estimator friction -1"), 0);
  EXPECT_TRUE(watch.wait(10.0, [&] {
    return watch.logged("/contact_estimator", rosgraph_msgs::Log::WARN, { "friction is now 0.001", "end of its range" });
  })) << watch.logText();
  ASSERT_EQ(dynparam("set /contact_estimator friction 0.8"), 0);
  ASSERT_TRUE(watch.wait(10.0, [&] { return watch.number("friction") == 0.8; }));
}

TEST_F(FirstHour, TheBodysYawRateAsTheShellsOmegaIsAWarning)
{
  ros::Publisher odom = nh.advertise<nav_msgs::Odometry>("/odom", 100);
  ASSERT_TRUE(watch.wait(20.0, [&] { return odom.getNumSubscribers() > 0; }));
  // what a differential-drive robot publishes: the body's velocity and its yaw rate
  nav_msgs::Odometry o;
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.pose.pose.orientation.w = 1.0;
  o.twist.twist.linear.x = 0.8;
  o.twist.twist.angular.z = 0.3;
  const ros::Time start(1000.0);
  for (int i = 0; i < 200; ++i)
  {
    o.header.stamp = start + ros::Duration(0.01 * i);
    odom.publish(o);
    ros::WallDuration(0.002).sleep();
  }
  EXPECT_TRUE(watch.wait(20.0, [&] {
    return watch.logged("/contact_estimator", rosgraph_msgs::Log::WARN, { "shell does not roll", "twist.angular" });
  })) << watch.logText();
  EXPECT_TRUE(watch.wait(10.0, [&] {
    return watch.input.level == diagnostic_msgs::DiagnosticStatus::WARN &&
           watch.input.message.find("shell does not roll") != std::string::npos;
  })) << watch.input.message;
  std::lock_guard<std::mutex> lock(watch.mutex);
  int flagged = 0;
  for (const sce::ContactEstimate& e : watch.estimates)
    flagged += (e.flags & sce::ContactEstimate::FLAG_NOT_ROLLING) != 0;
  EXPECT_GE(flagged, 90);   // the last second of two
  EXPECT_LE(flagged, 101);
}

TEST_F(FirstHour, AResetTakesTheRobotsYaw)
{
  ros::Publisher odom = nh.advertise<nav_msgs::Odometry>("/odom", 100);
  ASSERT_TRUE(watch.wait(20.0, [&] { return odom.getNumSubscribers() > 0; }));
  // rolling along x, then the clock jumps back (a looping bag) with the robot turned by 90 degrees and standing
  nav_msgs::Odometry o = sce::test::rollingOdometry(1.0);
  o.header.stamp = ros::Time(2000.0);
  odom.publish(o);
  o.twist.twist.angular.y = 0.0;
  o.twist.twist.linear.x = 0.0;
  o.pose.pose.orientation.z = std::sin(M_PI / 4);
  o.pose.pose.orientation.w = std::cos(M_PI / 4);
  o.header.stamp = ros::Time(1500.0);
  ros::WallDuration(0.05).sleep();
  odom.publish(o);
  EXPECT_TRUE(watch.wait(10.0, [&] {
    return !watch.estimates.empty() && watch.estimates.back().header.stamp == ros::Time(1500.0);
  }));
  std::lock_guard<std::mutex> lock(watch.mutex);
  ASSERT_FALSE(watch.estimates.empty());
  const sce::ContactEstimate& e = watch.estimates.back();
  EXPECT_TRUE(e.flags & sce::ContactEstimate::FLAG_TIME_JUMP_RESET);
  EXPECT_NEAR(e.heading, M_PI / 2, 1e-9);
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_first_hour");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
