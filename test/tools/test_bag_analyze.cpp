// bag_analyze and its library on synthetic bags: transforms from the bag's /tf, the time range, topics
// copied and replaced, the run summary against closed forms, errors for people, and the plot script on
// the CSV it writes.

// STL
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

// GTest
#include <gtest/gtest.h>

// ROS
#include <dynamic_reconfigure/Config.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/ros/bag_analyzer.h"
#include "sphere_contact_estimator/ros/config_file.h"
#include "sphere_contact_estimator/ros/config_settings.h"
#include "../command_outcome.h"

namespace sce = sphere_contact_estimator;
using sce::test::Outcome;
using sce::test::runCommand;
using sce::test::slurp;

namespace
{
const std::string kDir = "/tmp/sphere_contact_estimator_test_bag_analyze";

/// Rolling along x at v for `seconds` at 100 Hz, the centre sliding back by `slide`; the sphere's frame is
/// yawed by `yaw` in the ground frame, given either by /tf (and no pose orientation) or by the pose.
std::string writeBag(const std::string& name, double v, double slide, double seconds, bool tf, double yaw = 0.6)
{
  const std::string path = kDir + "/" + name;
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  const double R = 0.1;
  for (int i = 0; i <= static_cast<int>(std::lround(seconds * 100.0)); ++i)
  {
    const ros::Time t(100.0 + 0.01 * i);
    if (tf)
    {
      tf2_msgs::TFMessage m;
      m.transforms.resize(1);
      m.transforms[0].header.stamp = t;
      m.transforms[0].header.frame_id = "odom";
      m.transforms[0].child_frame_id = "base_link";
      m.transforms[0].transform.rotation.z = std::sin(0.5 * yaw);
      m.transforms[0].transform.rotation.w = std::cos(0.5 * yaw);
      bag.write("/tf", t - ros::Duration(1e-6), m);  // received just before the odometry, as recorders see it
    }
    nav_msgs::Odometry o;
    o.header.stamp = t;
    o.header.frame_id = "odom";
    o.child_frame_id = "base_link";
    if (!tf)
    {
      o.pose.pose.orientation.z = std::sin(0.5 * yaw);
      o.pose.pose.orientation.w = std::cos(0.5 * yaw);
    }  // else all zero: no valid orientation, only tf gives one
    o.twist.twist.angular.y = v / R;  // body frame: rolling along its x
    o.twist.twist.linear.x = v - slide;
    bag.write("/wheel/odometry", t, o);
    if (i % 50 == 0)
    {
      std_msgs::String s;
      s.data = "unrelated";
      bag.write("/chatter", t, s);
    }
  }
  return path;
}

sce::BagAnalysisOptions options(const std::string& input)
{
  sce::BagAnalysisOptions o;
  o.input = input;
  o.config.brush_model = 2;                // steady: closed forms below
  o.config.rolling_resistance_model = 1;   // exact
  o.config.robot_mass = 5.0;
  return o;
}

// The values of a CSV's column, by its name in the header.
std::vector<std::string> column(const std::string& csv, const std::string& name)
{
  std::istringstream lines(csv);
  std::string line, cell;
  while (std::getline(lines, line) && line.rfind('#', 0) == 0)  // the record of what made the estimates
  {
  }
  std::istringstream header(line);
  int index = -1;
  for (int i = 0; std::getline(header, cell, ','); ++i)
    if (cell == name)
      index = i;
  std::vector<std::string> values;
  if (index < 0)
    return values;
  while (std::getline(lines, line))
  {
    std::istringstream row(line);
    for (int i = 0; std::getline(row, cell, ','); ++i)
      if (i == index)
        values.push_back(cell);
  }
  return values;
}

class BagAnalyze : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    ros::Time::init();
    std::system(("mkdir -p " + kDir).c_str());
  }
};

TEST_F(BagAnalyze, OrientationFromTheBagsTf)
{
  // the pose has no orientation: without the bag's /tf every message would be skipped
  sce::BagAnalysisOptions o = options(writeBag("tf.bag", 1.0, 0.0, 1.0, true));
  o.output = kDir + "/tf_out.bag";
  const sce::BagAnalysisResult r = sce::analyzeBag(o);
  EXPECT_EQ(r.odom_topic, "/wheel/odometry");
  EXPECT_EQ(r.odometry, 101u);
  EXPECT_EQ(r.estimates, 101u);
  EXPECT_EQ(r.no_orientation, 0u);
  rosbag::Bag out(o.output);
  std::size_t estimates = 0, tf = 0, chatter = 0, odometry = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(out))
  {
    if (m.getTopic() == "/contact_estimate")
    {
      const auto e = m.instantiate<sce::ContactEstimate>();
      ++estimates;
      EXPECT_FALSE(e->flags & sce::ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY);
      EXPECT_NEAR(e->heading, 0.6, 1e-9);  // the rolling direction, yawed by tf
      EXPECT_NEAR(e->rolling_speed, 1.0, 1e-12);
    }
    tf += m.getTopic() == "/tf";
    chatter += m.getTopic() == "/chatter";
    odometry += m.getTopic() == "/wheel/odometry";
  }
  EXPECT_EQ(estimates, 101u);
  EXPECT_EQ(tf, 101u + 101u);  // the input's and the contact frame's
  EXPECT_EQ(chatter, 3u);
  EXPECT_EQ(odometry, 101u);
}

TEST_F(BagAnalyze, TimeRangeAndTopics)
{
  sce::BagAnalysisOptions o = options(writeBag("range.bag", 1.0, 0.0, 2.0, false));
  o.start = 0.5;
  o.end = 1.5;
  o.output = kDir + "/range_out.bag";
  o.topics = { "/wheel/odometry" };
  const sce::BagAnalysisResult r = sce::analyzeBag(o);
  EXPECT_EQ(r.estimates, 101u);  // 0.50 s ... 1.50 s at 100 Hz
  EXPECT_NEAR(r.bag_seconds, 1.0, 1e-9);
  EXPECT_EQ(r.copied, 101u);     // the odometry only, no chatter
  rosbag::Bag out(o.output);
  EXPECT_EQ(rosbag::View(out, rosbag::TopicQuery("/chatter")).size(), 0u);
  EXPECT_EQ(rosbag::View(out, rosbag::TopicQuery("/contact_estimate")).size(), 101u);

  // estimates in the input (a bag recorded beside the live node) are replaced, not doubled
  sce::BagAnalysisOptions again = options(o.output);
  again.output = kDir + "/range_again.bag";
  const sce::BagAnalysisResult r2 = sce::analyzeBag(again);
  ASSERT_FALSE(r2.replaced_topics.empty());
  rosbag::Bag out2(again.output);
  EXPECT_EQ(rosbag::View(out2, rosbag::TopicQuery("/contact_estimate")).size(), 101u);
}

TEST_F(BagAnalyze, SummaryAgainstClosedForms)
{
  // 2 s at 1 m/s with the centre sliding back at 2 m/s (full sliding): distance 2 m; the patch takes
  // mu F_z |V_s| (|F_t| = mu F_z against V_s), the surface F_R L V_r
  sce::BagAnalysisOptions o = options(writeBag("sliding.bag", 1.0, 2.0, 2.0, false));
  const sce::BagAnalysisResult r = sce::analyzeBag(o);
  const sce::RunSummary& s = r.summary;
  const double mu_Fz = o.config.friction * o.config.robot_mass * o.config.gravity;
  EXPECT_NEAR(s.duration(), 2.0, 1e-9);
  EXPECT_NEAR(s.distance(), 2.0, 1e-9);
  EXPECT_NEAR(s.brushEnergy(), mu_Fz * 2.0 * 2.0, 1e-6 * mu_Fz * 4.0);
  EXPECT_NEAR(s.peakUtilisation(), 1.0, 1e-9);
  EXPECT_NEAR(s.slidingShareMostly(), 1.0, 1e-12);
  EXPECT_GT(s.rollingResistanceEnergy(), 0.0);
  EXPECT_NEAR(s.rollingResistanceEnergy(), s.peakRollingResistance() * 1.0 * 2.0, 1e-9 * s.rollingResistanceEnergy());
  EXPECT_EQ(s.brushModelsUsed()[2], r.estimates);

  EXPECT_EQ(s.accuracyMissed(), 0u);
  EXPECT_NE(s.report().find("target met at every estimate"), std::string::npos) << s.report();

  // pure rolling: no sliding, so (almost) nothing for the patch to take
  const sce::BagAnalysisResult rolling = sce::analyzeBag(options(writeBag("rolling.bag", 1.0, 0.0, 1.0, false)));
  EXPECT_NEAR(rolling.summary.brushEnergy(), 0.0, 1e-9);
  EXPECT_NEAR(rolling.summary.slidingShareAny(), 0.0, 1e-12);

  // a target the least work budget cannot reach: every such answer counted, with how far its estimate is off
  sce::BagAnalysisOptions hard = options(writeBag("hard.bag", 1.0, 0.05, 1.0, false));
  hard.config.brush_model = 4;  // auto
  hard.config.accuracy_target = 1e-6;
  hard.config.work_budget = 10000;
  const sce::BagAnalysisResult missed = sce::analyzeBag(hard);
  EXPECT_GT(missed.summary.accuracyMissed(), 0u);
  EXPECT_LE(missed.summary.accuracyMissed(), missed.estimates);
  EXPECT_GT(missed.summary.worstAccuracyRatio(), 1.0);
  EXPECT_NE(missed.summary.report().find("target missed at " +
                                         std::to_string(missed.summary.accuracyMissed()) + " estimates"),
            std::string::npos)
      << missed.summary.report();
  // and how many of them the budget held (auto below the lattice or tolerance the target asks), with what a larger
  // budget does
  EXPECT_GT(missed.summary.accuracyMissedBudgetLimited(), 0u);
  EXPECT_LE(missed.summary.accuracyMissedBudgetLimited(), missed.summary.accuracyMissed());
  EXPECT_NE(missed.summary.report().find("of them held back by the work budget at " +
                                         std::to_string(missed.summary.accuracyMissedBudgetLimited()) +
                                         " (BRUSH_FLAG_BUDGET_LIMITED: a larger work_budget lets auto refine)"),
            std::string::npos)
      << missed.summary.report();

  // the transient model at a fixed resolution: its lattice cannot show such a target, and the summary says so (before,
  // "target met at every estimate": the transient answers were never flagged)
  hard.config.brush_model = 3;  // transient
  hard.config.work_budget = 1000000000;  // (10000 cannot pay for its lattice: the settings are rejected)
  const sce::BagAnalysisResult fixed = sce::analyzeBag(hard);
  // (every answer but the first, whose lattice is still empty: no force, and none to miss)
  EXPECT_EQ(fixed.summary.accuracyMissed() + 1, fixed.estimates);
  EXPECT_NE(fixed.summary.report().find("target missed at "), std::string::npos) << fixed.summary.report();
  EXPECT_EQ(fixed.summary.accuracyMissedCutShort(), 0u);  // (a budget of 1e9: nothing cut short)

  // with tilt (substeps) at the least budget its lattice takes: the updates the budget cut short are said, with what
  // buys them
  hard.config.tilt = true;
  hard.config.accuracy_target = 1e-2;
  hard.config.work_budget = static_cast<int>(sce::settingsFromConfig(hard.config).leastWorkBudget());
  const sce::BagAnalysisResult cut = sce::analyzeBag(hard);
  EXPECT_GT(cut.summary.accuracyMissedCutShort(), 0u);
  EXPECT_LE(cut.summary.accuracyMissedCutShort(), cut.summary.accuracyMissed());
  EXPECT_NE(cut.summary.report().find("cut short by the work budget at " +
                                      std::to_string(cut.summary.accuracyMissedCutShort()) + " (BRUSH_FLAG_SUBSTEPS"),
            std::string::npos)
      << cut.summary.report();
}

TEST_F(BagAnalyze, ParameterFiles)
{
  sce::ContactEstimatorConfig c = sce::ContactEstimatorConfig::__getDefault__();
  std::ofstream(kDir + "/good.yaml") << "friction: 0.5\nbristle_stiffness: 2.0e8\ntilt: true\nresolution: 24\n"
                                        "ground_frame: map\nqueue_size: 100\n";
  sce::applyParameterFile(c, kDir + "/good.yaml");
  EXPECT_EQ(c.friction, 0.5);
  EXPECT_EQ(c.bristle_stiffness, 2e8);  // YAML 1.1 text, read as the number it is
  EXPECT_TRUE(c.tilt);
  EXPECT_EQ(c.resolution, 24);
  EXPECT_EQ(c.ground_frame, "map");
  const auto rejects = [&](const std::string& text, const std::string& says) {
    std::ofstream(kDir + "/bad.yaml") << text;
    sce::ContactEstimatorConfig before = c;
    try
    {
      sce::applyParameterFile(c, kDir + "/bad.yaml");
      ADD_FAILURE() << text << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
    EXPECT_EQ(c.friction, before.friction) << "a rejected file changed the configuration";
  };
  rejects("friction: 0.3\nfrictoin: 0.4\n", "unknown parameter 'frictoin'");
  rejects("friction: lots\n", "not a number");
  rejects("resolution: 2.5\n", "not an integer");
  rejects("friction: 1000\n", "outside");
  rejects("tilt: maybe\n", "not true or false");
  rejects("friction: [1, 2]\n", "not a single value");
  rejects("- friction\n", "expected a map");
}

TEST_F(BagAnalyze, CommandLine)
{
  const std::string tool = BAG_ANALYZE_PATH, plot = PLOT_ANALYSIS_PATH;
  const std::string bag = writeBag("cli.bag", 1.0, 0.05, 3.0, false);
  const std::string params = std::string(PACKAGE_SOURCE_DIR) + "/config/contact_estimator.yaml";
  Outcome r = runCommand(tool + " -i " + bag + " -o " + kDir + "/cli_out.bag --csv " + kDir + "/cli.csv -p " + params +
                         " --brush-model auto --set friction=0.6");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  for (const char* line : { "301 odometry, 301 estimates", "distance rolled", "energy dissipated", "time sliding",
                            "peak brush force", "brush models run" })
    EXPECT_NE(r.out.find(line), std::string::npos) << line << " missing in\n" << r.out;
  const std::string csv = slurp(kDir + "/cli.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 304);  // the record, the header and one row per estimate
  // what made the estimates, before the header: the parameter file, the overrides, every parameter by name
  EXPECT_EQ(csv.rfind("# bag_analyze " + bag + ", parameters " + params + ", --set friction=0.6, --brush-model auto\n", 0), 0u)
      << csv.substr(0, 300);
  EXPECT_NE(csv.find("\n# configuration: rolling_radius 0.1, robot_mass 5,"), std::string::npos);
  EXPECT_NE(csv.find(" friction 0.6,"), std::string::npos);
  EXPECT_NE(csv.find(",0.6,4,"), std::string::npos) << "friction 0.6 and brush model auto in the rows";
  EXPECT_EQ(column(csv, "sliding_law"), std::vector<std::string>(301, "0")) << "eq. (4b), the default (SLIDING_LAW_COULOMB)";
  // the approximation of Sect. 6 on request, said in every row
  r = runCommand(tool + " -i " + bag + " --csv " + kDir + "/cli_rigid.csv -p " + params + " --sliding-law rigid");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(column(slurp(kDir + "/cli_rigid.csv"), "sliding_law"), std::vector<std::string>(301, "1"));
  EXPECT_NE(runCommand(tool + " -i " + bag + " -p " + params + " --sliding-law viscous").status, 0);
  // the models' names are the cfg's enums, as the node and dynparam take them (without regard to case), and a name
  // that is none of them is an error that lists them
  r = runCommand(tool + " -i " + bag + " --csv " + kDir + "/cli_models.csv -p " + params +
                 " --brush-model Steady --rolling-resistance-model OFF");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(column(slurp(kDir + "/cli_models.csv"), "brush_model"), std::vector<std::string>(301, "2"));
  r = runCommand(tool + " -i " + bag + " -p " + params + " --brush-model stedy");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("'stedy' is none of off (0), linear (1), steady (2), transient (3), auto (4)"), std::string::npos)
      << r.err;

  // errors for people: status 2 (CLI11's own for usage) and the reason on stderr
  r = runCommand(tool + " -i " + kDir + "/tf_out.bag --odom-topic /nope");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no nav_msgs/Odometry topic /nope"), std::string::npos) << r.err;
  r = runCommand(tool + " -i " + bag + " -p " + params + " --set frction=1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown parameter 'frction'"), std::string::npos) << r.err;
  r = runCommand(tool + " -i " + bag + " -p " + params + " --start 2 --end 1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("time range is empty"), std::string::npos) << r.err;
  std::ofstream(kDir + "/not_a.bag") << "hello";
  r = runCommand(tool + " -i " + kDir + "/not_a.bag -p " + params);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot read bag"), std::string::npos) << r.err;
  EXPECT_NE(runCommand(tool + " -i /nonexistent.bag").status, 0);

  // the output bag records the configuration as the live node's server publishes it; analysed again as another
  // robot, the bag's own record disagrees, and bag_analyze says so
  {
    rosbag::Bag out_bag(kDir + "/cli_out.bag");
    int configs = 0;
    for (const rosbag::MessageInstance& m : rosbag::View(out_bag, rosbag::TopicQuery("/contact_estimator/parameter_updates")))
      if (const auto c = m.instantiate<dynamic_reconfigure::Config>())
      {
        ++configs;
        sce::ContactEstimatorConfig read = sce::ContactEstimatorConfig::__getDefault__();
        read.__fromMessage__(*c);
        EXPECT_EQ(read.friction, 0.6);
        EXPECT_EQ(read.brush_model, 4);
      }
    EXPECT_EQ(configs, 1);
  }
  r = runCommand(tool + " -i " + kDir + "/cli_out.bag --csv " + kDir + "/cli_again.csv -p " + params + " --set friction=0.6");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << "the same robot: " << r.err;
  r = runCommand(tool + " -i " + kDir + "/cli_out.bag --csv " + kDir + "/cli_other.csv -p " + params +
                 " --set robot_mass=3 --set rolling_radius=0.15");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the bag's estimates (/contact_estimate) were made with F_z = 49.05 N"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("warning: the bag's recorded configuration (/contact_estimator/parameter_updates) has rolling_radius 0.1 m"),
            std::string::npos) << r.err;

  // the figures of the analysis
  r = runCommand("/usr/bin/python3 " + plot + " " + kDir + "/cli.csv --output " + kDir + "/figures");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  for (const char* figure : { "forces", "slips", "rolling_resistance", "friction_circle" })
  {
    std::ifstream png(kDir + "/figures/cli_" + figure + ".png", std::ios::binary | std::ios::ate);
    EXPECT_GT(png.tellg(), 10000) << figure;
  }
}
// The estimates of a bag analysed with the package's parameter file (its defaults: auto, eq. 4b), from `start` s;
// hold_within_noise as given.
std::vector<sce::ContactEstimate> estimatesOf(const std::string& bag, double robot_mass, const char* law, double start,
                                              sce::BagAnalysisResult* result = nullptr, bool hold = false)
{
  sce::BagAnalysisOptions o;
  o.input = bag;
  o.output = kDir + "/parked_out.bag";
  o.copy_input = false;
  o.start = start;
  sce::applyParameterFile(o.config, std::string(PACKAGE_SOURCE_DIR) + "/config/contact_estimator.yaml");
  o.config.robot_mass = robot_mass;
  sce::setParameter(o.config, "sliding_law", law);
  sce::setParameter(o.config, "hold_within_noise", hold ? "true" : "false");
  const sce::BagAnalysisResult analysed = sce::analyzeBag(o);
  if (result)
    *result = analysed;
  std::vector<sce::ContactEstimate> out;
  rosbag::Bag written(o.output);
  for (const rosbag::MessageInstance& m : rosbag::View(written, rosbag::TopicQuery("/contact_estimate")))
    out.push_back(*m.instantiate<sce::ContactEstimate>());
  return out;
}

TEST_F(BagAnalyze, ParkedRobotsForcesFollowTheNoise)
{
  // Two recordings of a parked robot: data/parked.bag (config/parked_scenario.yaml through demo.launch record:=, 3 s
  // at 100 Hz, 5 mm/s on V_C and 0.02 rad/s on omega, replayed as a 3 kg robot) and data/demo.bag's rest phase (its
  // last 0.5 s, the 5 kg robot), the noise let through to the bristles (hold_within_noise false: the laws' own
  // response to it). Under eq. (4b), the default: the force moves by more than half of mu F_z between consecutive
  // estimates at <= 1 % of them, and the estimates say the motion is within the noise. Under Sect. 6's approximation
  // (issue 20) the resultant jumped across the friction circle at most of them. With the defaults (the noise held) the
  // forces do not move at all under either law, and every estimate after the first says so (FLAG_MOTION_HELD).
  struct Recording
  {
    std::string bag;
    double robot_mass, start;
  };
  for (const Recording& r : { Recording{ std::string(PACKAGE_SOURCE_DIR) + "/data/parked.bag", 3.0, 0.0 },
                              Recording{ std::string(PACKAGE_SOURCE_DIR) + "/data/demo.bag", 5.0, 10.51 } })
    for (const char* law : { "coulomb", "rigid" })
    {
      sce::BagAnalysisResult analysed;
      const std::vector<sce::ContactEstimate> e = estimatesOf(r.bag, r.robot_mass, law, r.start, &analysed);
      // why an answer misses its target: at standstill, where auto's lattice cannot refine (not the budget); the
      // forces' covariance walks with the noise while parked, and auto's target follows it (most are met)
      const sce::RunSummary& s = analysed.summary;
      std::printf("%s, %s: target missed at %llu, at standstill %llu\n", r.bag.c_str(), law,
                  static_cast<unsigned long long>(s.accuracyMissed()),
                  static_cast<unsigned long long>(s.accuracyMissedStandstill()));
      EXPECT_EQ(s.accuracyMissedStandstill(), s.accuracyMissed()) << r.bag;
      EXPECT_EQ(s.accuracyMissedBudgetLimited(), 0u) << r.bag;
      if (s.accuracyMissed() > 0)
      {
        EXPECT_NE(s.report().find("of them at standstill at " + std::to_string(s.accuracyMissedStandstill()) +
                                  " (auto refines its lattice only while the patch rolls)"),
                  std::string::npos)
            << s.report();
      }
      ASSERT_GT(e.size(), 40u) << r.bag;
      // the forces' covariance walked from the estimator's own start (approximate: test_uncertainty); where the noise
      // has pushed more than half the bristles onto their bounds (a 3 kg robot at 100 Hz, within a few tenths of a
      // second) not followed: undefined
      int walked = 0;
      for (std::size_t i = 0; i < e.size(); ++i)
      {
        const bool walk = e[i].brush_covariance_method == sce::ContactEstimate::COVARIANCE_METHOD_RANDOM_WALK;
        walked += walk;
        if (i < 10)
        {
          EXPECT_TRUE(walk && e[i].covariance_status == sce::ContactEstimate::COVARIANCE_APPROXIMATE) << r.bag << " " << i;
        }
        if (!walk)
        {
          EXPECT_EQ(e[i].covariance_status, sce::ContactEstimate::COVARIANCE_UNDEFINED) << r.bag << " " << i;
          EXPECT_GT(e[i].sliding_fraction, 0.5) << r.bag << " " << i;
        }
      }
      std::printf("%s, %s: the covariance walked at %d\n", r.bag.c_str(), law, walked);
      EXPECT_GE(walked, 10) << r.bag;
      int jumps = 0, within = 0;
      for (std::size_t i = 0; i < e.size(); ++i)
      {
        const double muFz = e[i].friction * e[i].load;
        if (i > 0)
          jumps += std::hypot(e[i].brush_force.x - e[i - 1].brush_force.x, e[i].brush_force.y - e[i - 1].brush_force.y) >
                   0.5 * muFz;
        within += (e[i].flags & sce::ContactEstimate::FLAG_MOTION_WITHIN_NOISE) != 0;
        EXPECT_TRUE(e[i].flags & sce::ContactEstimate::FLAG_STANDSTILL);
      }
      const double share = static_cast<double>(jumps) / (e.size() - 1);
      std::printf("%s, %s: %zu estimates, |dF| > mu F_z / 2 at %.1f %%, motion within the noise at %d\n", r.bag.c_str(),
                  law, e.size(), 100.0 * share, within);
      if (std::string(law) == "coulomb")
        EXPECT_LE(share, 0.01) << r.bag;
      else
        EXPECT_GT(share, 0.3) << r.bag;  // the failure the default law removes, still there on request
      EXPECT_GE(within, 0.98 * e.size()) << r.bag;
      // the defaults: from the first estimate held on, every one held and its forces those the motion left
      const std::vector<sce::ContactEstimate> held = estimatesOf(r.bag, r.robot_mass, law, r.start, nullptr, true);
      ASSERT_EQ(held.size(), e.size()) << r.bag;
      std::size_t first = 0;
      while (first < held.size() && !(held[first].flags & sce::ContactEstimate::FLAG_MOTION_HELD))
        ++first;
      std::printf("%s, %s, held: from estimate %zu of %zu\n", r.bag.c_str(), law, first, held.size());
      EXPECT_LE(first, 5u) << r.bag;
      for (std::size_t i = first; i < held.size(); ++i)
      {
        EXPECT_TRUE(held[i].flags & sce::ContactEstimate::FLAG_MOTION_HELD) << r.bag << " " << i;
        EXPECT_EQ(held[i].brush_force.x, held[first].brush_force.x) << r.bag << " " << i;
        EXPECT_EQ(held[i].brush_force.y, held[first].brush_force.y) << r.bag << " " << i;
        EXPECT_EQ(held[i].brush_moment, held[first].brush_moment) << r.bag << " " << i;
        EXPECT_EQ(held[i].sliding_fraction, 0.0) << r.bag << " " << i;
      }
    }
}

TEST_F(BagAnalyze, ManyBagsInParallel)
{
  // two bags in a folder with a broken one, and a third bag by name, two at a time: one output bag and CSV each, the
  // same as alone; the broken one named and skipped; summary.csv with a row each and the totals
  const std::string tool = BAG_ANALYZE_PATH;
  const std::string params = std::string(PACKAGE_SOURCE_DIR) + "/config/contact_estimator.yaml";
  const std::string in = kDir + "/set", out = kDir + "/set_out";
  std::system(("rm -rf " + in + " " + out + " && mkdir -p " + in).c_str());
  const std::string a = writeBag("set/a.bag", 1.0, 0.05, 2.0, false), b = writeBag("set/b.bag", 0.5, 0.2, 3.0, true);
  const std::string c = writeBag("c.bag", 2.0, 0.01, 1.0, false);
  std::ofstream(in + "/broken.bag") << "not a bag";
  Outcome r = runCommand(tool + " -i " + in + " " + c + " -o " + out + " --csv " + out + " -p " + params +
                         " --jobs 2 --brush-model steady");
  EXPECT_EQ(r.status, 1) << r.out << r.err;  // one bag failed
  EXPECT_NE(r.err.find("broken.bag"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("3 of 4 ok"), std::string::npos) << r.out;
  for (const char* name : { "a", "b", "c" })
  {
    EXPECT_TRUE(std::ifstream(out + "/" + name + "_analysis.bag").good()) << name;
    EXPECT_TRUE(std::ifstream(out + "/" + name + ".csv").good()) << name;
  }
  // each the same as its analysis alone (but the compute time, the last number of the first part of each row)
  const auto strip = [](const std::string& csv) {
    std::string kept;
    std::istringstream lines(csv);
    for (std::string line; std::getline(lines, line);)
    {
      if (line.rfind('#', 0) == 0)
        continue;  // the record names the input as given
      std::vector<std::string> cells;
      std::istringstream row(line);
      for (std::string cell; std::getline(row, cell, ',');)
        cells.push_back(cell);
      if (cells.size() > 43)
        cells[43].clear();  // compute_time
      for (const std::string& cell : cells)
        kept += cell + ",";
      kept += "\n";
    }
    return kept;
  };
  r = runCommand(tool + " -i " + b + " --csv " + kDir + "/b_alone.csv -p " + params + " --brush-model steady");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(strip(slurp(out + "/b.csv")) == strip(slurp(kDir + "/b_alone.csv"))) << "b.csv differs from b alone";
  // the summary: a row per bag, totals that add up
  const std::string summary = slurp(out + "/summary.csv");
  std::map<std::string, std::vector<std::string>> rows;
  std::istringstream lines(summary);
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header.rfind("bag,status,odometry,estimates", 0), 0u) << header;
  for (std::string line; std::getline(lines, line);)
  {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');)
      cells.push_back(cell);
    rows[cells[0]] = cells;
  }
  ASSERT_EQ(rows.size(), 5u) << summary;
  EXPECT_EQ(rows["broken"][1], "failed");
  EXPECT_EQ(rows["a"][2], "201");  // 2 s at 100 Hz
  EXPECT_EQ(std::stoi(rows["total"][2]), 201 + 301 + 101);
  const double distance = std::stod(rows["a"][8]) + std::stod(rows["b"][8]) + std::stod(rows["c"][8]);
  EXPECT_NEAR(std::stod(rows["total"][8]), distance, 1e-4 * distance);
  EXPECT_NEAR(std::stod(rows["a"][8]), 2.0, 0.02);  // rolled 1 m/s for 2 s
  // two bags of one name would overwrite each other's outputs: refused before anything runs
  r = runCommand(tool + " -i " + a + " " + kDir + "/set/../set/a.bag -o " + out + " -p " + params);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("two bags are named a"), std::string::npos) << r.err;
  r = runCommand(tool + " -i " + a + " /nonexistent_dir/ -p " + params);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no such bag or directory"), std::string::npos) << r.err;
  // a share of one bag, as a script that splits a list hands it out: folders and summary.csv all the same
  const std::string one = kDir + "/set_one";
  std::system(("rm -rf " + one).c_str());
  r = runCommand(tool + " --set-of-bags -i " + c + " -o " + one + " --csv " + one + " -p " + params);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::ifstream(one + "/c_analysis.bag").good());
  EXPECT_TRUE(std::ifstream(one + "/c.csv").good());
  EXPECT_NE(slurp(one + "/summary.csv").find("\ntotal,1 of 1 ok,101,"), std::string::npos) << slurp(one + "/summary.csv");
}

TEST_F(BagAnalyze, TheOutputBagReadsBackInEveryTool)
{
  // BagWriter's bag (format 2.0, its own chunks and index) read by rosbag's C++ API, by rosbag info and by Python
  const std::string bag = writeBag("readback.bag", 1.0, 0.05, 30.0, true);  // 3001 odometry, several chunks
  sce::BagAnalysisOptions o;
  o.input = bag;
  o.output = kDir + "/readback_out.bag";
  o.config.brush_model = 1;
  const sce::BagAnalysisResult r = sce::analyzeBag(o);
  rosbag::Bag in(o.output, rosbag::bagmode::Read);
  std::map<std::string, int> counts;
  ros::Time last;
  for (const rosbag::MessageInstance& m : rosbag::View(in))
  {
    ++counts[m.getTopic()];
    EXPECT_GE(m.getTime(), last);  // in time order across chunks
    last = m.getTime();
    if (m.getTopic() == "/contact_estimate")
    {
      ASSERT_NE(m.instantiate<sce::ContactEstimate>(), nullptr);
    }
  }
  EXPECT_EQ(counts["/contact_estimate"], static_cast<int>(r.estimates));
  EXPECT_EQ(counts["/wheel/odometry"], 3001);
  EXPECT_EQ(counts["/chatter"], 61);
  const Outcome info = runCommand("rosbag info " + o.output);
  EXPECT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("/contact_estimate"), std::string::npos) << info.out;
  const Outcome py = runCommand("/usr/bin/python3 -c \"import rosbag; print(sum(1 for _ in rosbag.Bag('" + o.output +
                                "').read_messages(topics=['/brush_wrench'])))\"");
  EXPECT_EQ(py.status, 0) << py.err;
  EXPECT_EQ(std::stoi(py.out), static_cast<int>(r.estimates));
}
}  // namespace
