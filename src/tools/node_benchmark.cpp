// node_benchmark: the contact estimator node over real roscpp on loopback. For each brush model it raises
// the odometry rate until the node falls behind (a failing rate is tried once more: the machine is shared),
// and reports the highest rate sustained with no backlog and
// the p50/p99 latency from odometry stamp to the estimate's arrival. Then the offline replay throughput of a
// bag by bag_analyze's own path, analyzeBag (messages per second).
//
// Then, with streams (a list of bags: recorded manoeuvres), each bag's odometry published at its recorded pace into the
// node at its configured settings, stream_runs times (default 3): every message's latency from publication to the
// estimate's arrival (p50, p99, max) of the run with the lowest p99, each run's p99, and the fewest answered in a run.
//
// Run by scripts/benchmark.sh beside `contact_estimator_node` (pinned to one core); prints JSON.
// Private parameters: node (default /contact_estimator), duration per rate [s], rates (list), models (list), streams
// (bag paths, comma-separated; default none), stream_runs (default 3).

// STL
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

// ROS
#include <dynamic_reconfigure/client.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/ros/bag_analyzer.h"
#include "scenario.h"

namespace sce = sphere_contact_estimator;

namespace
{
struct RateResult
{
  double rate = 0.0;
  std::size_t sent = 0, received = 0;
  double p50 = 0.0, p99 = 0.0;  // [s]
  bool sustained = false;
};

double percentile(std::vector<double> v, double q)
{
  if (v.empty())
    return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
}

nav_msgs::Odometry odometry(const ros::Time& stamp, double t)
{
  nav_msgs::Odometry o;
  o.header.stamp = stamp;
  o.header.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.pose.pose.orientation.w = 1.0;
  const double v = 1.0 + 0.2 * std::sin(t);  // rolling with a varying slip: every model works
  o.twist.twist.angular.y = v / 0.1;
  o.twist.twist.angular.z = 0.3;
  o.twist.twist.linear.x = v * (1.0 + 0.02 * std::sin(3.0 * t));
  o.twist.twist.linear.y = 0.01;
  return o;
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "node_benchmark");
  ros::NodeHandle nh, pnh("~");
  const std::string node = pnh.param<std::string>("node", "/contact_estimator");
  const double duration = pnh.param("duration", 2.0);
  std::vector<double> rates{ 1000, 2000, 5000, 10000, 20000 };
  pnh.getParam("rates", rates);
  std::vector<int> models{ 1, 2, 3, 4 };
  pnh.getParam("models", models);
  const int stream_runs = std::max(1, pnh.param("stream_runs", 3));
  // bags, comma-separated (a private parameter given on the command line is a string)
  std::vector<std::string> streams;
  {
    const std::string list = pnh.param<std::string>("streams", "");
    for (std::size_t start = 0; start < list.size();)
    {
      const std::size_t end = std::min(list.find(',', start), list.size());
      if (end > start)
        streams.push_back(list.substr(start, end - start));
      start = end + 1;
    }
  }

  ros::AsyncSpinner spinner(1);
  spinner.start();
  ros::Publisher pub = nh.advertise<nav_msgs::Odometry>("odom", 100000);
  std::mutex mutex;
  std::vector<double> latencies;
  std::atomic<std::size_t> received{ 0 };
  ros::Subscriber sub = nh.subscribe<sce::ContactEstimate>(
      "contact_estimate", 100000,
      [&](const sce::ContactEstimate::ConstPtr& m) {
        const double latency = (ros::Time::now() - m->header.stamp).toSec();
        std::lock_guard<std::mutex> lock(mutex);
        latencies.push_back(latency);
        ++received;
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  dynamic_reconfigure::Client<sce::ContactEstimatorConfig> client(node);
  sce::ContactEstimatorConfig config;
  if (!client.getCurrentConfiguration(config, ros::Duration(20.0)))
  {
    ROS_FATAL("node_benchmark: no %s", node.c_str());
    return 1;
  }
  const ros::WallTime wait = ros::WallTime::now() + ros::WallDuration(10.0);
  while ((pub.getNumSubscribers() == 0 || sub.getNumPublishers() == 0) && ros::WallTime::now() < wait)
    ros::WallDuration(0.01).sleep();

  std::printf("{\n  \"node\": [\n");
  for (std::size_t mi = 0; mi < models.size(); ++mi)
  {
    config.brush_model = models[mi];
    client.setConfiguration(config);
    ros::WallDuration(0.3).sleep();
    std::vector<RateResult> results;
    bool retried = false;  // a shared machine hiccups: a rate that fails is tried once more before it counts
    for (std::size_t ri = 0; ri < rates.size(); ++ri)
    {
      const double rate = rates[ri];
      {
        std::lock_guard<std::mutex> lock(mutex);
        latencies.clear();
        received = 0;
      }
      RateResult r;
      r.rate = rate;
      const auto start = std::chrono::steady_clock::now();
      const auto period = std::chrono::duration<double>(1.0 / rate);
      const std::size_t n = static_cast<std::size_t>(rate * duration);
      for (std::size_t i = 0; i < n; ++i)
      {
        std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(i * period));
        pub.publish(odometry(ros::Time::now(), i / rate));
      }
      r.sent = n;
      const ros::WallTime drain = ros::WallTime::now() + ros::WallDuration(1.0);
      while (received < n && ros::WallTime::now() < drain)
        ros::WallDuration(0.005).sleep();
      {
        std::lock_guard<std::mutex> lock(mutex);
        r.received = received;
        r.p50 = percentile(latencies, 0.5);
        r.p99 = percentile(latencies, 0.99);
      }
      // sustained: every message answered, and the latency did not build up (no queue growing)
      r.sustained = r.received == r.sent && r.p99 < 0.02;
      results.push_back(r);
      if (!r.sustained && !retried)
      {
        retried = true;
        --ri;
        continue;
      }
      if (!r.sustained)
        break;
    }
    double best = 0.0;
    const RateResult* at = nullptr;
    for (const RateResult& r : results)
      if (r.sustained && r.rate > best)
      {
        best = r.rate;
        at = &r;
      }
    std::printf("%s    {\"brush_model\": %d, \"max_rate\": %.0f, \"p50\": %.6g, \"p99\": %.6g, \"tried\": [", mi ? ",\n" : "",
                models[mi], best, at ? at->p50 : 0.0, at ? at->p99 : 0.0);
    for (std::size_t i = 0; i < results.size(); ++i)
      std::printf("%s{\"rate\": %.0f, \"received\": %zu, \"sent\": %zu, \"p50\": %.6g, \"p99\": %.6g}", i ? ", " : "",
                  results[i].rate, results[i].received, results[i].sent, results[i].p50, results[i].p99);
    std::printf("]}");
    std::fflush(stdout);
  }
  std::printf("\n  ],\n");

  // The recorded manoeuvres at their own pace, the node at its configured settings (restored after the models' runs)
  {
    sce::ContactEstimatorConfig configured = config;
    client.getDefaultConfiguration(configured, ros::Duration(5.0));
    std::printf("  \"streams\": [\n");
    for (std::size_t bi = 0; bi < streams.size(); ++bi)
    {
      std::vector<nav_msgs::Odometry> messages;
      {
        rosbag::Bag bag(streams[bi]);
        for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/odom")))
          if (const nav_msgs::Odometry::ConstPtr o = m.instantiate<nav_msgs::Odometry>())
            messages.push_back(*o);
      }
      if (messages.empty())
        continue;
      config.brush_model = 4;  // the default: auto
      client.setConfiguration(config);
      ros::WallDuration(0.3).sleep();
      // Each bag `stream_runs` times: a shared host's scheduler adds latency spikes of 10 ms and more to single runs
      // (the same bag's p99 at 1 kHz was 1.0 and 3.9 ms in two runs minutes apart), so the run with the lowest p99 is
      // reported, every run's p99 beside it; messages lost in any run count.
      const ros::Time t0 = messages.front().header.stamp;
      const double duration = (messages.back().header.stamp - t0).toSec();
      double best_p50 = 0.0, best_p99 = 0.0, best_max = 0.0;  // (0 where no run got anything back, as percentile's)
      bool any = false;
      std::size_t least_received = messages.size();
      std::string run_p99s;
      for (int run = 0; run < stream_runs; ++run)
      {
        {
          std::lock_guard<std::mutex> lock(mutex);
          latencies.clear();
          received = 0;
        }
        // a gap beyond max_step first (the node forgets the last run), then the bag's offsets from now
        ros::WallDuration(0.6).sleep();
        const auto start = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < messages.size(); ++i)
        {
          const double offset = (messages[i].header.stamp - t0).toSec();
          std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                    std::chrono::duration<double>(offset)));
          nav_msgs::Odometry o = messages[i];
          o.header.stamp = ros::Time::now();  // the latency is measured from here
          pub.publish(o);
        }
        const ros::WallTime drain = ros::WallTime::now() + ros::WallDuration(2.0);
        while (received < messages.size() && ros::WallTime::now() < drain)
          ros::WallDuration(0.005).sleep();
        std::lock_guard<std::mutex> lock(mutex);
        const double p99 = percentile(latencies, 0.99);
        run_p99s += (run ? ", " : "") + std::to_string(p99);
        least_received = std::min<std::size_t>(least_received, received);
        if (!latencies.empty() && (!any || p99 < best_p99))  // (a run that got nothing back has no latency to be best at)
        {
          any = true;
          best_p99 = p99;
          best_p50 = percentile(latencies, 0.5);
          best_max = percentile(latencies, 1.0);
        }
      }
      std::printf("%s    {\"bag\": \"%s\", \"rate\": %.0f, \"sent\": %zu, \"received\": %zu, \"p50\": %.6g, \"p99\": %.6g, "
                  "\"max\": %.6g, \"run_p99\": [%s]}",
                  bi ? ",\n" : "", streams[bi].substr(streams[bi].find_last_of('/') + 1).c_str(),
                  duration > 0.0 ? (messages.size() - 1) / duration : 0.0, messages.size(), least_received, best_p50,
                  best_p99, best_max, run_p99s.c_str());
      std::fflush(stdout);
    }
    std::printf("\n  ],\n");
    config = configured;
  }

  // Offline replay: a bag of the demo manoeuvre at 1 kHz through the estimator class, as fast as it goes.
  const std::string bag_path = "/tmp/sphere_contact_estimator_replay_benchmark.bag";
  {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Write);
    const ros::Time t0(1000.0);
    for (const sce::ScenarioSample& s : sce::Scenario(sce::Scenario::defaultSegments(), 0.1).sample(1e-3))
    {
      nav_msgs::Odometry o = odometry(t0 + ros::Duration(s.time), s.time);
      o.twist.twist.angular.y = s.omega_body.y();
      o.twist.twist.angular.z = s.omega_body.z();
      o.twist.twist.linear.x = s.velocity_body.x();
      o.twist.twist.linear.y = s.velocity_body.y();
      o.pose.pose.orientation.z = std::sin(0.5 * s.yaw);
      o.pose.pose.orientation.w = std::cos(0.5 * s.yaw);
      bag.write("/odom", o.header.stamp, o);
    }
  }
  std::printf("  \"replay\": [\n");
  for (std::size_t mi = 0; mi < models.size(); ++mi)
  {
    // bag_analyze's own path: the node's estimator class, the output bag and the CSV
    sce::BagAnalysisOptions replay;
    replay.input = bag_path;
    replay.output = bag_path + ".out.bag";
    replay.csv = bag_path + ".csv";
    replay.config = config;
    replay.config.brush_model = models[mi];
    const auto start = std::chrono::steady_clock::now();
    const sce::BagAnalysisResult r = sce::analyzeBag(replay);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s    {\"brush_model\": %d, \"messages\": %llu, \"messages_per_second\": %.0f}", mi ? ",\n" : "",
                models[mi], static_cast<unsigned long long>(r.estimates), r.estimates / seconds);
    std::remove(replay.output.c_str());
    std::remove(replay.csv.c_str());
  }
  std::printf("\n  ]\n}\n");
  std::remove(bag_path.c_str());
  ros::shutdown();
  return 0;
}
