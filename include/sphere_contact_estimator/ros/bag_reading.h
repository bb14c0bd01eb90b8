#pragma once

// STL
#include <memory>
#include <string>

// ROS
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2/buffer_core.h>
#include <tf2_msgs/TFMessage.h>

namespace sphere_contact_estimator
{
/// Closes a bag under the lock that openBag takes.
struct BagDeleter
{
  void operator()(rosbag::Bag* bag) const;
};
using BagPtr = std::unique_ptr<rosbag::Bag, BagDeleter>;

/// Opens a bag for reading. rosbag::Bag's constructor and destructor load and unload its encryption plugin through
/// class_loader, whose state is global and unguarded (two bags made at once on two threads crashed), so both happen
/// under one lock; reading an open bag touches none of it. Throws std::runtime_error naming the bag.
BagPtr openBag(const std::string& path);

/// The topic of message type `type` (e.g. "nav_msgs/Odometry") in the view: `requested` if given (it must be of that
/// type), else the bag's only one. Throws std::runtime_error naming the type, the topics there are, and `option` (the
/// command-line option that chooses one) when there are several.
std::string topicOfType(rosbag::View& all, const std::string& type, const std::string& requested,
                        const std::string& option);

/// Adds a bag's tf message to the buffer (authority "bag"); a malformed transform is skipped.
void addTransforms(tf2::BufferCore& buffer, const tf2_msgs::TFMessage& msg, bool is_static);

}  // namespace sphere_contact_estimator
