#pragma once

// Package
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/core/estimator/estimator_settings.h"

namespace sphere_contact_estimator
{
/// The core settings of a dynamic_reconfigure configuration (same names; the frames stay in the ROS layer).
EstimatorSettings settingsFromConfig(const ContactEstimatorConfig& config);

}  // namespace sphere_contact_estimator
