#pragma once

// STL
#include <string>
#include <vector>

// ROS
#include <ros/node_handle.h>

namespace sphere_contact_estimator
{
/// How a line of repairTextParameters about a refused value (deleted: the default applies) ends.
inline constexpr const char* kParameterIgnored = ": ignored, the default applies";

/// The private parameters as the node reads them at start-up, checked before the reconfigure server sees them.
/// YAML 1.1, which rosparam and roslaunch read, takes 1.0e8 (an exponent without a sign) for a string; a text
/// where a number or a bool belongs is set to the value it means, and an enum parameter takes the names of
/// cfg/ContactEstimator.cfg (brush_model: steady). The server would also clamp a number outside the .cfg's
/// range, and take any int for an enum, without a word: such values, and text that means nothing, are deleted,
/// so the default applies, with a line that says why and lists the valid values (all_repaired is then false).
/// Call before the reconfigure server reads the parameters. Returns one line per repair, for the log.
std::vector<std::string> repairTextParameters(const ros::NodeHandle& pnh, bool& all_repaired);

}  // namespace sphere_contact_estimator
