#pragma once

// STL
#include <vector>

// Package
#include "scenario.h"

namespace sphere_contact_estimator::test
{
/// The sensor noise config/manoeuvre_scenario.yaml records with (the demo's): standard deviations of the contact
/// centre's velocity [m/s] and of each angular velocity component [rad/s].
constexpr double kManoeuvreNoiseVelocity = 0.005, kManoeuvreNoiseOmega = 0.02;

/// The segments of config/manoeuvre_scenario.yaml (data/manoeuvre.bag, issue 21's robot stream): accelerate with the
/// centre lagging, weave at 1 m/s with the shell spinning at 8 rad/s, slow, pivot at 0.3 m/s (12 rad/s), skid to a
/// stop, spin in place, park (2 s here).
inline std::vector<ScenarioSegment> manoeuvreSegments()
{
  const auto segment = [](const char* name, double duration, double v0, double v1, double s0, double s1, double lateral,
                          double yaw_rate, double spin) {
    ScenarioSegment s;
    s.name = name;
    s.duration = duration;
    s.speed_start = v0;
    s.speed_end = v1;
    s.sliding_start = s0;
    s.sliding_end = s1;
    s.lateral_sliding = lateral;
    s.yaw_rate = yaw_rate;
    s.spin_rate = spin;
    return s;
  };
  return { segment("accelerate", 2.0, 0.0, 1.0, -0.03, -0.03, 0.0, 0.0, 0.0),
           segment("weave", 1.0, 1.0, 1.0, 0.0, 0.0, 0.05, 1.0, 8.0),
           segment("weave", 1.0, 1.0, 1.0, 0.0, 0.0, -0.05, -1.0, -8.0),
           segment("weave", 1.0, 1.0, 1.0, 0.0, 0.0, 0.05, 1.0, 8.0),
           segment("weave", 1.0, 1.0, 1.0, 0.0, 0.0, -0.05, -1.0, -8.0),
           segment("slow", 1.0, 1.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0),
           segment("pivot", 2.0, 0.3, 0.3, 0.0, 0.0, 0.08, 3.0, 12.0),
           segment("skid", 1.0, 0.3, 0.0, 0.3, 0.05, 0.0, 0.0, 0.0),
           segment("spin in place", 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 5.0),
           segment("park", 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0) };
}
}  // namespace sphere_contact_estimator::test
