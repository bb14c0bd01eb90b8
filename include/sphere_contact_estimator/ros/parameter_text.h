#pragma once

// STL
#include <string>
#include <vector>

// ROS
#include <ros/node_handle.h>

namespace sphere_contact_estimator
{
/// Numbers that reached the parameter server as text. YAML 1.1, which rosparam and roslaunch read, takes
/// 1.0e8 (an exponent without a sign) for a string; dynamic_reconfigure would then keep the .cfg default
/// without a word. Each private parameter of cfg/ContactEstimator.cfg that holds text where a number or a
/// bool belongs is set to the value the text means; text that means none is deleted, so the default applies.
/// Call before the reconfigure server reads the parameters. Returns one line per repair, for the log.
std::vector<std::string> repairTextParameters(const ros::NodeHandle& pnh, bool& all_repaired);

}  // namespace sphere_contact_estimator
