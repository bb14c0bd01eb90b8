#include "sphere_contact_estimator/ros/bag_reading.h"

// STL
#include <mutex>
#include <set>
#include <stdexcept>

namespace sphere_contact_estimator
{
namespace
{
// Recursive: a bag that fails to open is deleted while the lock is held.
std::recursive_mutex g_bag_lifetime;

std::string list(const std::set<std::string>& s)
{
  std::string text;
  for (const auto& t : s)
    text += (text.empty() ? "" : ", ") + t;
  return text.empty() ? std::string("none") : text;
}
}  // namespace

void BagDeleter::operator()(rosbag::Bag* bag) const
{
  std::lock_guard<std::recursive_mutex> lock(g_bag_lifetime);
  delete bag;
}

BagPtr openBag(const std::string& path)
{
  std::lock_guard<std::recursive_mutex> lock(g_bag_lifetime);
  BagPtr bag(new rosbag::Bag);
  try
  {
    bag->open(path, rosbag::bagmode::Read);
  }
  catch (const rosbag::BagException& e)
  {
    throw std::runtime_error("cannot read bag " + path + ": " + e.what());
  }
  return bag;
}

std::string topicOfType(rosbag::View& all, const std::string& type, const std::string& requested,
                        const std::string& option)
{
  std::set<std::string> of_type, topics;
  for (const rosbag::ConnectionInfo* c : all.getConnections())
  {
    topics.insert(c->topic);
    if (c->datatype == type)
      of_type.insert(c->topic);
  }
  if (!requested.empty())
  {
    if (!of_type.count(requested))
      throw std::runtime_error("no " + type + " topic " + requested + " in the bag; " + type + " topics: " + list(of_type));
    return requested;
  }
  if (of_type.size() != 1)
    throw std::runtime_error(of_type.empty() ? "no " + type + " topic in the bag; topics: " + list(topics) :
                                               "several " + type + " topics (" + list(of_type) + "): choose one with " +
                                                   option);
  return *of_type.begin();
}

void addTransforms(tf2::BufferCore& buffer, const tf2_msgs::TFMessage& msg, bool is_static)
{
  for (const auto& t : msg.transforms)
  {
    try
    {
      buffer.setTransform(t, "bag", is_static);
    }
    catch (const std::exception&)  // a malformed transform in a bag is not ours to stop on
    {
    }
  }
}

}  // namespace sphere_contact_estimator
