// Live and offline give the same estimates: the bundled demo bag played with rosbag play --clock into the
// node on simulated time (replay.launch, started paused), against analyzeBag() (bag_analyze) on the same bag
// and parameter file. Every field of every estimate must be equal, bit for bit, but the compute time and the
// header's sequence number.

// STL
#include <cstdio>
#include <mutex>
#include <vector>

// GTest
#include <gtest/gtest.h>

// ROS
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_srvs/SetBool.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/ros/bag_analyzer.h"
#include "sphere_contact_estimator/ros/config_file.h"

namespace sce = sphere_contact_estimator;

namespace
{
std::vector<uint8_t> bytes(sce::ContactEstimate m)
{
  m.compute_time = 0.0;  // wall time
  m.header.seq = 0;      // set by the transport
  std::vector<uint8_t> buffer(ros::serialization::serializationLength(m));
  ros::serialization::OStream stream(buffer.data(), static_cast<uint32_t>(buffer.size()));
  ros::serialization::serialize(stream, m);
  return buffer;
}

std::size_t countOdometry(const std::string& bag_path)
{
  rosbag::Bag bag(bag_path);
  rosbag::View view(bag, rosbag::TypeQuery("nav_msgs/Odometry"));
  return view.size();
}

TEST(Replay, LiveAndOfflineGiveTheSameEstimates)
{
  ros::NodeHandle nh, pnh("~");
  std::string bag_path, config_path;
  ASSERT_TRUE(pnh.getParam("bag", bag_path));
  ASSERT_TRUE(pnh.getParam("config", config_path));
  const std::size_t n = countOdometry(bag_path);
  ASSERT_GT(n, 100u);

  std::mutex mutex;
  std::vector<sce::ContactEstimate> live;
  ros::Subscriber sub = nh.subscribe<sce::ContactEstimate>("/contact_estimate", 10000, [&](const sce::ContactEstimate::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    live.push_back(*m);
  });
  const auto wait = [](const std::function<bool()>& done, double seconds) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::ok() && !done() && ros::WallTime::now() < end)
      ros::WallDuration(0.01).sleep();
    return done();
  };
  // the player waits, paused, for the estimator; this test resumes it once it listens itself
  ASSERT_TRUE(wait([&] { return sub.getNumPublishers() > 0; }, 30.0)) << "no estimator";
  ASSERT_TRUE(ros::service::waitForService("/play/pause_playback", ros::Duration(30.0))) << "no player";
  std_srvs::SetBool resume;
  resume.request.data = false;
  ASSERT_TRUE(ros::service::call("/play/pause_playback", resume));
  // the bag lasts 11 s at rate 1
  EXPECT_TRUE(wait([&] {
    std::lock_guard<std::mutex> lock(mutex);
    return live.size() >= n;
  }, 60.0));
  ros::WallDuration(0.5).sleep();  // nothing more arrives

  sce::BagAnalysisOptions options;
  options.input = bag_path;
  options.output = "/tmp/sphere_contact_estimator_test_replay.bag";
  sce::applyParameterFile(options.config, config_path);
  const sce::BagAnalysisResult result = sce::analyzeBag(options);
  EXPECT_EQ(result.estimates, n);
  std::vector<sce::ContactEstimate> offline;
  {
    rosbag::Bag out(options.output);
    for (const rosbag::MessageInstance& m : rosbag::View(out, rosbag::TopicQuery("/contact_estimate")))
      offline.push_back(*m.instantiate<sce::ContactEstimate>());
  }
  std::remove(options.output.c_str());

  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_EQ(live.size(), n) << "the live node answered " << live.size() << " of " << n << " messages";
  ASSERT_EQ(offline.size(), n);
  std::size_t different = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    ASSERT_EQ(live[i].header.stamp, offline[i].header.stamp) << i;
    if (bytes(live[i]) != bytes(offline[i]))
    {
      if (++different <= 3)
        ADD_FAILURE() << "estimate " << i << " differs: F_x live " << live[i].brush_force.x << " offline "
                      << offline[i].brush_force.x << ", mu_roll " << live[i].rolling_resistance.mu_roll << " / "
                      << offline[i].rolling_resistance.mu_roll << ", flags " << live[i].flags << " / "
                      << offline[i].flags;
    }
  }
  EXPECT_EQ(different, 0u);
  // and the run did something: it rolled, slid and spun
  EXPECT_GT(result.summary.distance(), 5.0);
  EXPECT_GT(result.summary.brushEnergy(), 0.0);
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_replay");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
