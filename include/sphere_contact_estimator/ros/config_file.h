#pragma once

// STL
#include <string>

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

}  // namespace sphere_contact_estimator
