#include "sphere_contact_estimator/ros/config_settings.h"

// STL
#include <stdexcept>
#include <string>

namespace sphere_contact_estimator
{
namespace
{
// an enum parameter's value, checked (the server takes any int for one), never forced into the range
template <class E>
E checked(const char* name, int value, int count, const char* valid)
{
  if (value < 0 || value >= count)
    throw std::invalid_argument(std::string("parameter ") + name + " = " + std::to_string(value) + " is none of " + valid);
  return static_cast<E>(value);
}
}  // namespace

EstimatorSettings settingsFromConfig(const ContactEstimatorConfig& c)
{
  EstimatorSettings s;
  s.rolling_radius = c.rolling_radius;
  s.robot_mass = c.robot_mass;
  s.load = c.load;
  s.gravity = c.gravity;
  s.brush_model = checked<BrushModelKind>("brush_model", c.brush_model, 5, "off (0), linear (1), steady (2), transient (3), auto (4)");
  s.accuracy_target = c.accuracy_target;
  s.patch_radius = c.patch_radius;
  s.contact_modulus = c.contact_modulus;
  s.bristle_stiffness = c.bristle_stiffness;
  s.friction = c.friction;
  s.pressure = checked<PressureDistribution>("pressure", c.pressure, 3, "parabolic (0), hertzian (1), uniform (2)");
  s.sliding_law = checked<SlidingLaw>("sliding_law", c.sliding_law, 2, "coulomb (0), rigid (1)");
  s.tilt = c.tilt;
  s.tilt_ratio_source = checked<TiltRatioSource>("tilt_ratio_source", c.tilt_ratio_source, 2, "estimate (0), fixed (1)");
  s.tilt_ratio = c.tilt_ratio;
  s.resolution = c.resolution;
  s.standstill_speed = c.standstill_speed;
  s.turn_rate_time_constant = c.turn_rate_time_constant;
  s.max_step = c.max_step;
  s.stamp_tolerance = c.stamp_tolerance;
  s.work_budget = c.work_budget;
  s.rolling_resistance_model = checked<CylinderModelKind>("rolling_resistance_model", c.rolling_resistance_model, 4,
                                                               "off (0), exact (1), expansion (2), table (3)");
  s.surface_stiffness = c.surface_stiffness;
  s.surface_damping = c.surface_damping;
  s.surface_density = c.surface_density;
  s.mass_per_length = c.mass_per_length;
  s.effective_length = c.effective_length;
  s.propagate_covariance = c.propagate_covariance;
  s.covariance_period = c.covariance_period;
  s.hold_within_noise = c.hold_within_noise;
  s.auto_noise_fraction = c.auto_noise_fraction;
  return s;
}

}  // namespace sphere_contact_estimator
