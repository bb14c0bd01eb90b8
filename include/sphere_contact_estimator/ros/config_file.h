#pragma once

// STL
#include <string>
#include <vector>

// Package
#include "sphere_contact_estimator/ContactEstimatorConfig.h"

namespace sphere_contact_estimator
{
/// Sets one parameter of the node by its name (cfg/ContactEstimator.cfg) from text. Throws
/// std::invalid_argument for an unknown name, a value that is not of the parameter's type, or one outside
/// its range: offline tools say so instead of clamping as the reconfigure server does.
void setParameter(ContactEstimatorConfig& config, const std::string& name, const std::string& value);

/// Applies a parameter file in the node's format (config/contact_estimator.yaml: a map of parameter names
/// to values). Keys the node reads at start-up only (queue_size) are ignored; anything else unknown, or a
/// file that cannot be read, throws std::invalid_argument naming the file and the key.
void applyParameterFile(ContactEstimatorConfig& config, const std::string& path);

/// The package's own parameter file (config/contact_estimator.yaml, as contact_estimator.launch loads it). Throws
/// std::runtime_error when the package is not on ROS_PACKAGE_PATH (the offline tools then ask for --params).
std::string defaultParameterFile();

/// Applies command-line overrides NAME=VALUE in order (setParameter); throws std::invalid_argument naming a malformed
/// one.
void applyParameterSets(ContactEstimatorConfig& config, const std::vector<std::string>& sets);

}  // namespace sphere_contact_estimator
