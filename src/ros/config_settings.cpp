#include "sphere_contact_estimator/ros/config_settings.h"

// STL
#include <algorithm>

namespace sphere_contact_estimator
{
EstimatorSettings settingsFromConfig(const ContactEstimatorConfig& c)
{
  EstimatorSettings s;
  s.rolling_radius = c.rolling_radius;
  s.robot_mass = c.robot_mass;
  s.load = c.load;
  s.gravity = c.gravity;
  s.brush_model = static_cast<BrushChoice>(std::clamp(c.brush_model, 0, 4));
  s.accuracy_target = c.accuracy_target;
  s.patch_radius = c.patch_radius;
  s.contact_modulus = c.contact_modulus;
  s.bristle_stiffness = c.bristle_stiffness;
  s.friction = c.friction;
  s.pressure = static_cast<PressureDistribution>(std::clamp(c.pressure, 0, 2));
  s.tilt = c.tilt;
  s.tilt_ratio_source = static_cast<TiltRatioSource>(std::clamp(c.tilt_ratio_source, 0, 1));
  s.tilt_ratio = c.tilt_ratio;
  s.resolution = c.resolution;
  s.standstill_speed = c.standstill_speed;
  s.turn_rate_time_constant = c.turn_rate_time_constant;
  s.max_step = c.max_step;
  s.rolling_resistance_model = static_cast<RollingResistanceChoice>(std::clamp(c.rolling_resistance_model, 0, 3));
  s.surface_stiffness = c.surface_stiffness;
  s.surface_damping = c.surface_damping;
  s.surface_density = c.surface_density;
  s.mass_per_length = c.mass_per_length;
  s.effective_length = c.effective_length;
  return s;
}

}  // namespace sphere_contact_estimator
