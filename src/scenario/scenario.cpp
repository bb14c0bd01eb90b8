#include "scenario.h"

// STL
#include <cmath>
#include <stdexcept>

namespace sphere_contact_estimator
{
Scenario::Scenario(std::vector<ScenarioSegment> segments, double rolling_radius)
  : segments_(std::move(segments)), rolling_radius_(rolling_radius)
{
  if (segments_.empty())
    throw std::invalid_argument("scenario: no segments");
  if (!(std::isfinite(rolling_radius) && rolling_radius > 0.0))
    throw std::invalid_argument("scenario: rolling radius must be finite and > 0");
  for (const ScenarioSegment& s : segments_)
  {
    for (double x : { s.duration, s.speed_start, s.speed_end, s.sliding_start, s.sliding_end, s.lateral_sliding,
                      s.yaw_rate, s.spin_rate })
      if (!std::isfinite(x))
        throw std::invalid_argument("scenario: segment '" + s.name + "' has a non-finite value");
    if (!(s.duration > 0.0))
      throw std::invalid_argument("scenario: segment '" + s.name + "' needs a duration > 0");
    duration_ += s.duration;
  }
}

std::vector<ScenarioSegment> Scenario::defaultSegments()
{
  std::vector<ScenarioSegment> s(6);
  s[0] = { "accelerate", 2.0, 0.0, 1.5, -0.03, -0.03, 0.0, 0.0, 0.0 };  // traction: the sphere turns faster
  s[1] = { "cruise", 2.0, 1.5, 1.5, 0.0, 0.0, 0.0, 0.0, 0.0 };
  s[2] = { "turn", 3.0, 1.5, 1.5, 0.0, 0.0, 0.04, 0.5, 0.5 };
  s[3] = { "brake with slip", 1.5, 1.5, 0.0, 0.2, 0.02, 0.0, 0.0, 0.0 };
  s[4] = { "spin in place", 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 3.0 };
  s[5] = { "rest", 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  return s;
}

std::vector<ScenarioSample> Scenario::sample(double dt) const
{
  if (!(std::isfinite(dt) && dt > 0.0))
    throw std::invalid_argument("scenario: sample period must be finite and > 0");
  std::vector<ScenarioSample> out;
  const auto n = static_cast<std::size_t>(std::floor(duration_ / dt + 1e-9)) + 1;
  out.reserve(n);
  ScenarioSample state;
  std::size_t segment = 0;
  double segment_start = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double t = static_cast<double>(i) * dt;
    while (segment + 1 < segments_.size() && t >= segment_start + segments_[segment].duration - 1e-12)
      segment_start += segments_[segment++].duration;
    const ScenarioSegment& s = segments_[segment];
    const double f = std::min(1.0, (t - segment_start) / s.duration);
    const double speed = s.speed_start + f * (s.speed_end - s.speed_start);
    const double sliding = s.sliding_start + f * (s.sliding_end - s.sliding_start);
    if (i > 0)
    {
      // integrate the pose with the previous sample's velocities
      const double c = std::cos(state.yaw), sn = std::sin(state.yaw);
      const Eigen::Vector3d& v = state.velocity_body;
      state.position += dt * Eigen::Vector3d(c * v.x() - sn * v.y(), sn * v.x() + c * v.y(), 0.0);
      state.yaw += dt * s.yaw_rate;
    }
    state.time = t;
    state.segment = static_cast<int>(segment);
    state.omega_body = Eigen::Vector3d(0.0, speed / rolling_radius_, s.spin_rate);  // rolls about +y (REP 103)
    state.velocity_body = Eigen::Vector3d(speed + sliding, s.lateral_sliding, 0.0);  // V_C = V_r + V_s
    out.push_back(state);
  }
  return out;
}

}  // namespace sphere_contact_estimator
