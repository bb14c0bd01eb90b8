// replay_benchmark: bag_analyze's throughput on a bag of the size a fleet logs. Writes a bag of the demo manoeuvre at
// 1 kHz, repeated to at least --messages odometry messages (with the odometry's orientation, its noise covariance and,
// with --tf, the sphere's transform on /tf beside each message), then replays it through bag_analyze's own path
// (analyzeBag: the node's estimator class, writing the output bag and the CSV) once per brush model, and prints JSON:
// messages per second for each, and the estimator's own rate (messages over the time spent in its update(): the
// models and their uncertainty), the bound a replay can reach. The bag is generated, never committed, and removed afterwards unless --keep.
// With --streams, recorded bags instead (data/manoeuvre.bag and its 1 kHz recording: a robot's stream, not a demo
// lap): each replayed with the parameter file's settings (--params, default the package's
// config/contact_estimator.yaml: what a user runs) or with each of --models, the fastest of --repeat replays, and its
// times real time.
//
//   replay_benchmark [--messages 110000] [--models off linear steady transient auto] [--tf] [--bag PATH] [--keep]
//   replay_benchmark --streams A.bag [B.bag ...] [--params FILE] [--models ...] [--repeat 3]
//   replay_benchmark --writers [--messages N]   rosbag::Bag::write against BagWriter: the same odometry messages
//                                              written by each, microseconds per message
//
// Run by scripts/benchmark.sh (docs/benchmarks.md, "Offline replay"); on one core of the machine.

// STL
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

// CLI11
#include <CLI/CLI.hpp>

// ROS
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <tf2_msgs/TFMessage.h>

// Package
#include "scenario.h"
#include "sphere_contact_estimator/core/brush/brush_model.h"
#include "sphere_contact_estimator/ros/bag_analyzer.h"
#include "sphere_contact_estimator/ros/bag_writer.h"
#include "sphere_contact_estimator/ros/config_file.h"

namespace sce = sphere_contact_estimator;

namespace
{
// The demo manoeuvre at 1 kHz, again and again, as a robot's odometry (and tf) would record it.
std::size_t writeBag(const std::string& path, std::size_t messages, bool with_tf)
{
  const std::vector<sce::ScenarioSample> samples = sce::Scenario(sce::Scenario::defaultSegments(), 0.1).sample(1e-3);
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  nav_msgs::Odometry o;
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.twist.covariance[0] = o.twist.covariance[7] = 0.005 * 0.005;  // the demo's sensor noise
  o.twist.covariance[21] = o.twist.covariance[28] = o.twist.covariance[35] = 0.02 * 0.02;
  tf2_msgs::TFMessage tf;
  tf.transforms.resize(1);
  tf.transforms[0].header.frame_id = "odom";
  tf.transforms[0].child_frame_id = "base_link";
  std::size_t written = 0;
  const double period = samples.back().time + 1e-3;
  for (int lap = 0; written < messages; ++lap)
    for (const sce::ScenarioSample& s : samples)
    {
      o.header.stamp = ros::Time(1000.0 + lap * period + s.time);
      o.pose.pose.position.x = s.position.x();
      o.pose.pose.position.y = s.position.y();
      o.pose.pose.position.z = 0.1;
      o.pose.pose.orientation.z = std::sin(0.5 * s.yaw);
      o.pose.pose.orientation.w = std::cos(0.5 * s.yaw);
      o.twist.twist.angular.x = s.omega_body.x();
      o.twist.twist.angular.y = s.omega_body.y();
      o.twist.twist.angular.z = s.omega_body.z();
      o.twist.twist.linear.x = s.velocity_body.x();
      o.twist.twist.linear.y = s.velocity_body.y();
      bag.write("/odom", o.header.stamp, o);
      if (with_tf)
      {
        geometry_msgs::TransformStamped& t = tf.transforms[0];
        t.header.stamp = o.header.stamp;
        t.transform.translation.x = o.pose.pose.position.x;
        t.transform.translation.y = o.pose.pose.position.y;
        t.transform.translation.z = o.pose.pose.position.z;
        t.transform.rotation = o.pose.pose.orientation;
        bag.write("/tf", o.header.stamp, tf);
      }
      if (++written == messages)
        break;
    }
  return written;
}
// Seconds to write n odometry messages with W (rosbag::Bag or BagWriter) to path.
template <class W>
double writeTime(W& bag, std::size_t n)
{
  nav_msgs::Odometry o;
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < n; ++i)
  {
    o.header.stamp = ros::Time(1000.0 + 1e-3 * static_cast<double>(i));
    bag.write("/odom", o.header.stamp, o);
  }
  bag.close();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int compareWriters(const std::string& path, std::size_t n)
{
  double rosbag_seconds = 0.0, ours_seconds = 0.0;
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    rosbag_seconds = writeTime(bag, n);
  }
  {
    sce::BagWriter bag(path);
    ours_seconds = writeTime(bag, n);
  }
  std::remove(path.c_str());
  std::printf("{\"messages\": %zu, \"writers\": [\n  {\"name\": \"rosbag::Bag::write\", \"us_per_message\": %.3f},\n"
              "  {\"name\": \"BagWriter::write\", \"us_per_message\": %.3f}\n]}\n",
              n, 1e6 * rosbag_seconds / static_cast<double>(n), 1e6 * ours_seconds / static_cast<double>(n));
  return 0;
}
// The node's brush_model number of a model's name, as the node, dynparam and bag_analyze read it (setParameter: the
// cfg's enum, any case), or -1, said on stderr.
int brushModel(const std::string& name)
{
  sce::ContactEstimatorConfig config;
  try
  {
    sce::setParameter(config, "brush_model", name);
  }
  catch (const std::invalid_argument& e)
  {
    std::fprintf(stderr, "replay_benchmark: %s\n", e.what());
    return -1;
  }
  return config.brush_model;
}

// The recorded bags through analyzeBag with the parameter file's settings, or with each of `models` (empty: the file's
// own brush model), each the fastest of `repeat` replays (they answer alike; the machine's other tenants only slow
// one down). JSON on stdout.
int replayStreams(const std::vector<std::string>& bags, const std::string& params,
                  const std::vector<std::string>& models, int repeat, const std::string& scratch)
{
  sce::BagAnalysisOptions base;
  base.output = scratch + ".out.bag";
  base.csv = scratch + ".csv";
  std::string file = params;
  try
  {
    if (file.empty())
      file = sce::defaultParameterFile();
    sce::applyParameterFile(base.config, file);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "replay_benchmark: %s\n", e.what());
    return 2;
  }
  std::vector<int> kinds;
  for (const std::string& name : models)
  {
    kinds.push_back(brushModel(name));
    if (kinds.back() < 0)
      return 2;
  }
  if (kinds.empty())
    kinds.push_back(base.config.brush_model);
  std::printf("{\"params\": \"%s\", \"repeat\": %d, \"streams\": [", file.c_str(), repeat);
  for (std::size_t b = 0; b < bags.size(); ++b)
  {
    const std::string name = bags[b].substr(bags[b].find_last_of('/') + 1);
    std::printf("%s\n  {\"bag\": \"%s\", \"runs\": [", b == 0 ? "" : ",", name.c_str());
    for (std::size_t k = 0; k < kinds.size(); ++k)
    {
      sce::BagAnalysisOptions o = base;
      o.input = bags[b];
      o.config.brush_model = kinds[k];
      double best = INFINITY, best_estimator = INFINITY;
      sce::BagAnalysisResult r;
      for (int i = 0; i < repeat; ++i)
      {
        const auto start = std::chrono::steady_clock::now();
        try
        {
          r = sce::analyzeBag(o);
        }
        catch (const std::exception& e)
        {
          std::fprintf(stderr, "replay_benchmark: %s: %s\n", bags[b].c_str(), e.what());
          return 1;
        }
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        best_estimator = std::min(best_estimator, r.compute_seconds);
      }
      std::printf("%s\n    {\"brush_model\": %d, \"name\": \"%s\", \"messages\": %llu, \"bag_seconds\": %.3f, "
                  "\"seconds\": %.4f, \"messages_per_second\": %.0f, \"times_real_time\": %.2f, "
                  "\"estimator_seconds\": %.4f, \"estimator_times_real_time\": %.2f}",
                  k == 0 ? "" : ",", kinds[k], sce::toString(static_cast<sce::BrushModelKind>(kinds[k])),
                  static_cast<unsigned long long>(r.odometry), r.bag_seconds, best, r.odometry / best,
                  r.bag_seconds / best, best_estimator, best_estimator > 0.0 ? r.bag_seconds / best_estimator : 0.0);
      std::fflush(stdout);
    }
    std::printf("]}");
  }
  std::printf("\n]}\n");
  std::remove(base.output.c_str());
  std::remove(base.csv.c_str());
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{ "replay_benchmark: bag_analyze's throughput on a generated bag of --messages odometry messages, or on "
                "recorded bags (--streams)" };
  std::size_t messages = 110000;
  std::vector<std::string> models = { "off", "linear", "steady", "transient", "auto" };
  bool with_tf = false, keep = false, writers = false;
  std::string path = "/tmp/sphere_contact_estimator_replay_benchmark.bag";
  std::vector<std::string> streams;
  std::string params;
  int repeat = 3;
  app.add_option("--messages", messages, "odometry messages in the bag")->capture_default_str();
  app.add_option("--models", models, "brush models to replay with")->capture_default_str();
  app.add_flag("--tf", with_tf, "record the sphere's pose on /tf beside each message (the estimator then looks it up)");
  app.add_option("--bag", path, "where to write the bag")->capture_default_str();
  app.add_flag("--keep", keep, "keep the bag, the output bag and the CSV");
  app.add_flag("--writers", writers, "only time rosbag::Bag::write against BagWriter on --messages odometry messages");
  app.add_option("--streams", streams, "recorded bags to replay instead of the generated one (e.g. data/manoeuvre.bag)")
      ->check(CLI::ExistingFile);
  app.add_option("--params", params,
                 "with --streams: parameter file (default: the package's config/contact_estimator.yaml)");
  app.add_option("--repeat", repeat, "with --streams: replays of each, the fastest reported")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  if (!streams.empty())
  {
    ros::Time::init();
    return replayStreams(streams, params, app.count("--models") > 0 ? models : std::vector<std::string>{}, repeat,
                         path);
  }
  if (writers)
  {
    ros::Time::init();
    return compareWriters(path, messages);
  }
  ros::Time::init();
  const std::size_t written = writeBag(path, messages, with_tf);
  std::printf("{\"messages\": %zu, \"tf\": %s, \"replay\": [", written, with_tf ? "true" : "false");
  bool first = true;
  for (const std::string& name : models)
  {
    const int kind = brushModel(name);
    if (kind < 0)
      return 2;
    sce::BagAnalysisOptions o;
    o.input = path;
    o.output = path + ".out.bag";
    o.csv = path + ".csv";
    o.config.brush_model = kind;
    const auto start = std::chrono::steady_clock::now();
    const sce::BagAnalysisResult r = sce::analyzeBag(o);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s\n  {\"brush_model\": %d, \"name\": \"%s\", \"messages\": %llu, \"seconds\": %.3f, "
                "\"messages_per_second\": %.0f, \"estimator_seconds\": %.3f, \"estimator_messages_per_second\": %.0f}",
                first ? "" : ",", kind, name.c_str(), static_cast<unsigned long long>(r.odometry), seconds,
                r.odometry / seconds, r.compute_seconds,
                r.compute_seconds > 0.0 ? r.odometry / r.compute_seconds : 0.0);
    std::fflush(stdout);
    first = false;
    if (!keep)
    {
      std::remove(o.output.c_str());
      std::remove(o.csv.c_str());
    }
  }
  std::printf("\n]}\n");
  if (!keep)
    std::remove(path.c_str());
  return 0;
}
