#include "sphere_contact_estimator/ros/bag_analyzer.h"

// STL
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>

// ROS
#include <dynamic_reconfigure/Config.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2/buffer_core.h>
#include <tf2_msgs/TFMessage.h>

// Package
#include "sphere_contact_estimator/ros/bag_reading.h"
#include "sphere_contact_estimator/ros/bag_writer.h"
#include "sphere_contact_estimator/ros/config_report.h"
#include "sphere_contact_estimator/ros/estimate_csv.h"
#include "sphere_contact_estimator/ros/odometry_estimator.h"

namespace sphere_contact_estimator
{
namespace
{
const std::string kEstimateTopic = "/contact_estimate";
const std::string kBrushTopic = "/brush_wrench";
const std::string kRollingResistanceTopic = "/rolling_resistance_wrench";
const std::string kParameterTopic = "/contact_estimator/parameter_updates";

// A value of a recorded configuration, NaN if it has none of that name.
double recorded(const dynamic_reconfigure::Config& c, const std::string& name)
{
  for (const auto& d : c.doubles)
    if (d.name == name)
      return d.value;
  return NAN;
}

// What the bag says the robot was, against what this analysis assumes: the first live estimate's load and patch
// radius, the last recorded configuration's rolling radius.
std::vector<std::string> compareWithRecord(rosbag::Bag& in, const EstimatorSettings& s)
{
  std::vector<std::string> warnings;
  const auto differs = [](double a, double b) { return std::isfinite(a) && std::abs(a - b) > 1e-9 * std::max(std::abs(a), std::abs(b)); };
  char text[320];
  for (const rosbag::MessageInstance& m : rosbag::View(in, rosbag::TopicQuery(kEstimateTopic)))
  {
    const auto e = m.instantiate<ContactEstimate>();
    if (!e)
      continue;
    const double F_z = s.verticalLoad(), a = s.brushParameters().a;
    if (differs(e->load, F_z) || differs(e->patch_radius, a))
    {
      std::snprintf(text, sizeof text, "the bag's estimates (%s) were made with F_z = %.6g N and a = %.6g m; this "
                                       "analysis has F_z = %.6g N and a = %.6g m: give the robot's --params",
                    kEstimateTopic.c_str(), e->load, e->patch_radius, F_z, a);
      warnings.emplace_back(text);
    }
    break;
  }
  double R = NAN;
  for (const rosbag::MessageInstance& m : rosbag::View(in, rosbag::TopicQuery(kParameterTopic)))
    if (const auto c = m.instantiate<dynamic_reconfigure::Config>())
      R = recorded(*c, "rolling_radius");
  if (differs(R, s.rolling_radius))
  {
    std::snprintf(text, sizeof text, "the bag's recorded configuration (%s) has rolling_radius %.6g m; this analysis "
                                     "has %.6g m: give the robot's --params",
                  kParameterTopic.c_str(), R, s.rolling_radius);
    warnings.emplace_back(text);
  }
  return warnings;
}

}  // namespace

BagAnalysisResult analyzeBag(const BagAnalysisOptions& o, const std::function<void(double)>& progress)
{
  BagAnalysisResult result;
  OdometryEstimator estimator(o.config);  // throws std::invalid_argument for an invalid configuration

  const auto bag = openBag(o.input);
  rosbag::Bag& in = *bag;
  rosbag::View all(in);
  if (all.size() == 0)
    throw std::runtime_error("bag " + o.input + " is empty");
  result.odom_topic = topicOfType(all, "nav_msgs/Odometry", o.odom_topic, "--odom-topic");
  const ros::Time bag_begin = all.getBeginTime(), bag_end = all.getEndTime();
  const ros::Time begin = std::min(bag_end, bag_begin + ros::Duration(std::max(0.0, o.start)));
  const ros::Time end = std::isfinite(o.end) ? std::min(bag_end, bag_begin + ros::Duration(std::max(0.0, o.end))) : bag_end;
  if (end < begin)
    throw std::runtime_error("the time range is empty: --start must come before --end");
  result.bag_seconds = (end - begin).toSec();
  result.warnings = compareWithRecord(in, estimator.estimator().settings());

  // The static transforms hold for the whole bag, wherever the range starts.
  tf2::BufferCore tf(ros::Duration(60.0));
  for (const rosbag::MessageInstance& m : rosbag::View(in, rosbag::TopicQuery("/tf_static")))
    if (const auto msg = m.instantiate<tf2_msgs::TFMessage>())
      addTransforms(tf, *msg, true);

  std::unique_ptr<BagWriter> out;  // buffered: rosbag::Bag::write's system calls per message cost 13x the analysis
  if (!o.output.empty())
  {
    out = std::make_unique<BagWriter>(o.output);
    // the configuration the estimates were made with, as the live node's reconfigure server publishes it
    dynamic_reconfigure::Config config;
    o.config.__toMessage__(config);
    out->write(kParameterTopic, begin, config);
  }
  std::ofstream csv_file;
  std::unique_ptr<EstimateCsv> csv;
  if (!o.csv.empty())
  {
    csv_file.open(o.csv);
    if (!csv_file)
      throw std::runtime_error("cannot write " + o.csv);
    csv = std::make_unique<EstimateCsv>(
        csv_file, std::vector<std::string>{ "bag_analyze " + o.input + (o.config_source.empty() ? "" : ", " + o.config_source),
                                            "configuration: " + configurationText(o.config) });
  }

  const std::set<std::string> selected(o.topics.begin(), o.topics.end());
  const std::set<std::string> ours = { kEstimateTopic, kBrushTopic, kRollingResistanceTopic, kParameterTopic };
  std::set<std::string> replaced;
  const auto copied = [&](const std::string& topic) {
    return out && o.copy_input && (selected.empty() || selected.count(topic));
  };
  const auto copy = [&](const rosbag::MessageInstance& m) {
    if (!copied(m.getTopic()))
      return;
    if (ours.count(m.getTopic()))
    {
      replaced.insert(m.getTopic());
      return;
    }
    out->write(m);
    ++result.copied;
  };

  rosbag::View view(in, begin, end);
  const double span = std::max((end - begin).toSec(), 1e-9);
  std::uint64_t seen = 0;
  tf2_msgs::TFMessage contact_tf;
  contact_tf.transforms.resize(1);
  SkipReason reason;
  for (const rosbag::MessageInstance& m : view)
  {
    if (progress && ++seen % 2048 == 0)
      progress((m.getTime() - begin).toSec() / span);
    const std::string& topic = m.getTopic();
    if (topic == "/tf")
    {
      const auto msg = m.instantiate<tf2_msgs::TFMessage>();
      if (!msg)
        continue;
      addTransforms(tf, *msg, false);
      // a bag recorded beside the live node has its contact frame already: ours replaces it
      const bool has_contact = std::any_of(msg->transforms.begin(), msg->transforms.end(), [&](const auto& t) {
        return t.child_frame_id == estimator.contactFrame();
      });
      if (!has_contact)
        copy(m);
      else if (copied(topic))
      {
        tf2_msgs::TFMessage rest;
        for (const auto& t : msg->transforms)
          if (t.child_frame_id != estimator.contactFrame())
            rest.transforms.push_back(t);
        if (!rest.transforms.empty())
          out->write(topic, m.getTime(), rest);
        ++result.copied;
        replaced.insert("/tf (" + estimator.contactFrame() + ")");
      }
      continue;
    }
    if (topic != result.odom_topic)
    {
      copy(m);
      continue;
    }
    const auto odom = m.instantiate<nav_msgs::Odometry>();
    if (!odom)
      continue;
    copy(m);
    ++result.odometry;
    const EstimateOutputs* e = estimator.process(*odom, tf, reason, m.getCallerId());
    if (!e)
      continue;
    ++result.estimates;
    result.compute_seconds += e->data->compute_time;
    result.summary.add(*e->data);
    if (out)
    {
      out->write(kEstimateTopic, m.getTime(), e->estimate);
      out->write(kBrushTopic, m.getTime(), e->brush_wrench);
      out->write(kRollingResistanceTopic, m.getTime(), e->rolling_resistance_wrench);
      if (e->has_transform)
      {
        contact_tf.transforms[0] = e->contact_transform;
        out->write("/tf", m.getTime(), contact_tf);
      }
    }
    if (csv)
      csv->write(e->estimate);
  }
  if (progress)
    progress(1.0);
  result.no_orientation = estimator.counters().no_orientation;
  result.rejected = estimator.counters().rejected;
  result.dropped = estimator.counters().dropped;
  result.out_of_order = estimator.counters().out_of_order;
  result.tf_stale = estimator.counters().tf_stale;
  result.replaced_topics.assign(replaced.begin(), replaced.end());
  if (csv_file.is_open() && !csv_file.flush())
    throw std::runtime_error("writing " + o.csv + " failed");
  if (out)
    out->close();  // reports a failed write, which the destructor could not
  return result;
}

}  // namespace sphere_contact_estimator
