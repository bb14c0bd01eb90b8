#pragma once

// ROS
#include <geometry_msgs/WrenchStamped.h>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

namespace sphere_contact_estimator
{
/// Fills a ContactEstimate message from the core's estimate (both in the ROS contact frame); the header is
/// the caller's. No allocation: the message has no variable-length fields.
void toMessage(const ContactEstimateData& estimate, ContactEstimate& message);

/// The brush force and moment on the sphere, at the contact-patch centre.
void brushWrench(const ContactEstimateData& estimate, geometry_msgs::WrenchStamped& wrench);

/// The rolling resistance as its equivalent force at the contact point, against the rolling direction
/// (x). Its moment about the sphere centre, R F_R L, is ContactEstimate.rolling_resistance.torque; it is not
/// repeated here, so that adding up wrenches does not count it twice.
void rollingResistanceWrench(const ContactEstimateData& estimate, geometry_msgs::WrenchStamped& wrench);

}  // namespace sphere_contact_estimator
