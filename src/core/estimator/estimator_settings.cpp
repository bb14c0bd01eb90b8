#include "sphere_contact_estimator/core/estimator/estimator_settings.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "sphere_contact_estimator/core/numerics/parameter_check.h"

// STL
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphere_contact_estimator
{
namespace
{
void require(bool ok, const char* name, double value, const char* rule)
{
  detail::requireParameter(ok, "", name, value, rule);
}
}  // namespace

BrushParameters EstimatorSettings::brushParameters() const
{
  BrushParameters p;
  p.F_z = verticalLoad();
  p.a = contact_modulus > 0.0 ? contactRadiusHertz(p.F_z, rolling_radius, contact_modulus) : patch_radius;
  p.k = bristle_stiffness;
  p.mu = friction;
  p.pressure = pressure;
  p.sliding_law = sliding_law;
  p.tilt = tilt;
  p.resolution = resolution;
  p.standstill_speed = standstill_speed;
  p.accuracy_target = accuracy_target;
  p.auto_noise_fraction = auto_noise_fraction;
  return p;
}

CylinderParameters EstimatorSettings::cylinderParameters() const
{
  CylinderParameters c;
  c.R = rolling_radius;
  c.k = surface_stiffness;
  c.gamma = surface_damping;
  c.m = surface_density;
  c.g = gravity;
  c.L = effective_length;
  c.M = mass_per_length > 0.0 ? mass_per_length : verticalLoad() / (gravity * effective_length);
  return c;
}

long EstimatorSettings::leastWorkBudget() const
{
  if (brush_model != BrushModelKind::Transient)
    return kMinWorkBudget;
  // the brush model has what the covariance left less a granularity (ContactEstimator), and the covariance's sigma
  // points may pass their share by one path under way: two granularities of room
  const double share = propagate_covariance ? 1.0 - kCovarianceShare : 1.0;
  const long lattice = BrushTransient::leastUpdateWork(resolution, tilt) + 2 * BrushModel::kWorkGranularity;
  return std::max(kMinWorkBudget, static_cast<long>(std::ceil(static_cast<double>(lattice) / share)));
}

void EstimatorSettings::validate() const
{
  const auto finite = [](double x) { return std::isfinite(x); };
  require(finite(rolling_radius) && rolling_radius > 0.0, "rolling_radius", rolling_radius, "finite and > 0 [m]");
  require(finite(robot_mass) && robot_mass >= 0.0, "robot_mass", robot_mass, "finite and >= 0 [kg]");
  require(finite(load) && load >= 0.0, "load", load, "finite and >= 0 [N] (0: robot_mass * gravity)");
  require(finite(gravity) && gravity > 0.0, "gravity", gravity, "finite and > 0 [m/s^2]");
  require(verticalLoad() > 0.0, "load", verticalLoad(), "> 0: set load or robot_mass");
  require(finite(contact_modulus) && contact_modulus >= 0.0, "contact_modulus", contact_modulus,
          "finite and >= 0 [Pa] (0: use patch_radius)");
  require(finite(tilt_ratio), "tilt_ratio", tilt_ratio, "finite");
  require(finite(turn_rate_time_constant) && turn_rate_time_constant >= 0.0, "turn_rate_time_constant",
          turn_rate_time_constant, "finite and >= 0 [s]");
  require(finite(max_step) && max_step > 0.0, "max_step", max_step, "finite and > 0 [s]");
  require(finite(stamp_tolerance) && stamp_tolerance >= 0.0 && stamp_tolerance <= max_step, "stamp_tolerance",
          stamp_tolerance, "finite, >= 0 and <= max_step [s]");
  require(work_budget >= kMinWorkBudget && work_budget <= kMaxWorkBudget, "work_budget", static_cast<double>(work_budget),
          "between 1e4 and 1e9 (work units of about 10 ns)");
  require(finite(mass_per_length) && mass_per_length >= 0.0, "mass_per_length", mass_per_length,
          "finite and >= 0 [kg/m] (0: load / (gravity effective_length))");
  require(finite(auto_noise_fraction) && auto_noise_fraction >= 0.0 && auto_noise_fraction <= 1.0,
          "auto_noise_fraction", auto_noise_fraction, "in [0, 1]");
  require(finite(covariance_period) && covariance_period >= 0.0 && covariance_period <= max_step, "covariance_period",
          covariance_period, "finite, >= 0 and <= max_step [s]");
  // the models' own checks, with the node's parameter names in front
  try
  {
    if (brush_model != BrushModelKind::Off)
      brushParameters().validate();
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(std::string("brush (patch_radius/contact_modulus, bristle_stiffness, friction, "
                                            "resolution, standstill_speed): ") + e.what());
  }
  // (after the brush's own checks: the resolution is within its range)
  const long least = leastWorkBudget();
  if (work_budget < least)
    throw std::invalid_argument(
        "work_budget = " + std::to_string(work_budget) +
        " cannot pay for one update of the transient model's lattice at resolution " + std::to_string(resolution) +
        (tilt ? " with tilt" : "") + (propagate_covariance ? " beside the covariance's share" : "") +
        ": it needs at least " + std::to_string(least) +
        " (raise work_budget, lower resolution, or use brush_model auto, whose lattice adapts to the budget)");
  try
  {
    if (rolling_resistance_model != CylinderModelKind::Off)
      cylinderParameters().validate();
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(std::string("rolling resistance (surface_stiffness, surface_damping, surface_density, "
                                            "mass_per_length, effective_length): ") + e.what());
  }
}

}  // namespace sphere_contact_estimator
