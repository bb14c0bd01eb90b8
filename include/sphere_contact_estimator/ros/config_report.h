#pragma once

// STL
#include <functional>
#include <string>
#include <vector>

// Package
#include "sphere_contact_estimator/ContactEstimatorConfig.h"

namespace sphere_contact_estimator
{
/// "rolling_radius 0.1, robot_mass 5, ..., brush_model auto, ...": every parameter of cfg/ContactEstimator.cfg with
/// its value, enums by name, for the log at start-up.
std::string configurationText(const ContactEstimatorConfig& config);

/// Every parameter as a line of the node's parameter file (`name: value`, enums by name, numbers as YAML 1.1 reads
/// them: 1.0e-05, not 1e-05, which it takes for a string), in the .cfg's order; `comment(name)` may add one after it.
std::string parameterFileText(const ContactEstimatorConfig& config,
                              const std::function<std::string(const std::string&)>& comment = {});

/// One parameter that differs between two configurations.
struct ParameterChange
{
  std::string name, before, after;  // values as configurationText writes them
  bool at_bound = false;            // the new value is an end of the .cfg's range (where the server clamps to)
};

/// What differs from before to after, in the .cfg's order.
std::vector<ParameterChange> configurationChanges(const ContactEstimatorConfig& before, const ContactEstimatorConfig& after);

/// "friction 0.8 -> 0.6, brush_model auto -> steady".
std::string describeChanges(const std::vector<ParameterChange>& changes);

/// The known parameter nearest to name (edit distance, case-insensitive), among the .cfg's and `extra`; empty when
/// none is within a third of the name's length (at least 2 edits).
std::string nearestParameter(const std::string& name, const std::vector<std::string>& extra = {});

/// Whether name is a parameter of the .cfg or one of `extra`.
bool isKnownParameter(const std::string& name, const std::vector<std::string>& extra = {});

}  // namespace sphere_contact_estimator
