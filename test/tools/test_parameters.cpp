// One source of truth for the defaults: the core's EstimatorSettings defines them, cfg/ContactEstimator.cfg and
// config/contact_estimator.yaml repeat them, and these tests fail when either disagrees. Enum parameters take
// their names; bad names and numbers are errors that list the valid values, never clamped.

// STL
#include <stdexcept>
#include <string>

// GTest
#include <gtest/gtest.h>

// yaml-cpp
#include <yaml-cpp/yaml.h>

// Package
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/ros/config_file.h"
#include "sphere_contact_estimator/ros/config_settings.h"
#include "sphere_contact_estimator/ros/parameter_enum.h"

namespace sce = sphere_contact_estimator;

namespace
{
const std::string kParameterFile = std::string(PACKAGE_SOURCE_DIR) + "/config/contact_estimator.yaml";

TEST(Parameters, CfgDefaultsAreTheCoreDefaults)
{
  const sce::EstimatorSettings core;
  const sce::EstimatorSettings cfg = sce::settingsFromConfig(sce::ContactEstimatorConfig::__getDefault__());
#define SAME(field) EXPECT_EQ(cfg.field, core.field) << #field
  SAME(rolling_radius);
  SAME(robot_mass);
  SAME(load);
  SAME(gravity);
  SAME(brush_model);
  SAME(patch_radius);
  SAME(contact_modulus);
  SAME(bristle_stiffness);
  SAME(friction);
  SAME(pressure);
  SAME(sliding_law);
  SAME(tilt);
  SAME(tilt_ratio_source);
  SAME(tilt_ratio);
  SAME(resolution);
  SAME(accuracy_target);
  SAME(standstill_speed);
  SAME(turn_rate_time_constant);
  SAME(max_step);
  SAME(stamp_tolerance);
  SAME(work_budget);
  SAME(rolling_resistance_model);
  SAME(surface_stiffness);
  SAME(surface_damping);
  SAME(surface_density);
  SAME(mass_per_length);
  SAME(effective_length);
  SAME(propagate_covariance);
  SAME(auto_noise_fraction);
  SAME(covariance_period);
  SAME(hold_within_noise);
#undef SAME
}

TEST(Parameters, TheParameterFileHoldsEveryParameterAtItsDefault)
{
  const YAML::Node file = YAML::LoadFile(kParameterFile);
  for (const auto& d : sce::ContactEstimatorConfig::__getParamDescriptions__())
    EXPECT_TRUE(file[d->name]) << d->name << " is missing from " << kParameterFile;
  sce::ContactEstimatorConfig loaded = sce::ContactEstimatorConfig::__getDefault__();
  sce::applyParameterFile(loaded, kParameterFile);
  for (const auto& d : sce::ContactEstimatorConfig::__getParamDescriptions__())
  {
    dynamic_reconfigure::Config a, b;
    d->toMessage(a, sce::ContactEstimatorConfig::__getDefault__());
    d->toMessage(b, loaded);
    EXPECT_EQ(a, b) << d->name << " differs between cfg/ContactEstimator.cfg and " << kParameterFile;
  }
}

TEST(Parameters, EnumsTakeTheirNames)
{
  sce::ContactEstimatorConfig c = sce::ContactEstimatorConfig::__getDefault__();
  sce::setParameter(c, "brush_model", "steady");
  EXPECT_EQ(c.brush_model, 2);
  sce::setParameter(c, "brush_model", "3");
  EXPECT_EQ(c.brush_model, 3);
  sce::setParameter(c, "rolling_resistance_model", "off");
  EXPECT_EQ(c.rolling_resistance_model, 0);
  sce::setParameter(c, "rolling_resistance_model", "expansion");
  EXPECT_EQ(c.rolling_resistance_model, 2);
  sce::setParameter(c, "pressure", "hertzian");
  EXPECT_EQ(c.pressure, 1);
  sce::setParameter(c, "sliding_law", "rigid");
  EXPECT_EQ(c.sliding_law, 1);
  EXPECT_EQ(sce::settingsFromConfig(c).sliding_law, sce::SlidingLaw::Rigid);
  sce::setParameter(c, "tilt_ratio_source", "fixed");
  EXPECT_EQ(c.tilt_ratio_source, 1);
  EXPECT_EQ(sce::settingsFromConfig(c).brush_model, sce::BrushModelKind::Transient);
}

// The error message, or "" when nothing was thrown.
std::string errorOf(const std::string& name, const std::string& value)
{
  sce::ContactEstimatorConfig c = sce::ContactEstimatorConfig::__getDefault__();
  try
  {
    sce::setParameter(c, name, value);
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_EQ(c.brush_model, sce::ContactEstimatorConfig::__getDefault__().brush_model);  // unchanged
    return e.what();
  }
  return "";
}

TEST(Parameters, BadValuesAreErrorsThatListTheValidOnes)
{
  for (const char* bad : { "stedy", "5", "-1", "2.5", "", "1e300" })
  {
    const std::string e = errorOf("brush_model", bad);
    EXPECT_NE(e.find("off (0), linear (1), steady (2), transient (3), auto (4)"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_NE(errorOf("rolling_resistance_model", "on").find("Off (0), exact (1)"), std::string::npos);
  for (const char* bad : { "1e300", "3e9", "24.5", "nan" })
    EXPECT_NE(errorOf("resolution", bad), "") << bad;
  EXPECT_NE(errorOf("resolution", "100000").find("outside"), std::string::npos);
  EXPECT_NE(errorOf("friction", "-0.5").find("outside"), std::string::npos);
  EXPECT_EQ(errorOf("resolution", "64"), "");

  // a config whose enum holds an impossible number (the reconfigure server takes any int): rejected, not clamped
  sce::ContactEstimatorConfig c = sce::ContactEstimatorConfig::__getDefault__();
  c.brush_model = 9;
  try
  {
    sce::settingsFromConfig(c);
    ADD_FAILURE() << "brush_model 9 accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("auto (4)"), std::string::npos) << e.what();
  }
}

TEST(Parameters, EnumValuesFromTheCfg)
{
  for (const auto& d : sce::ContactEstimatorConfig::__getParamDescriptions__())
    if (d->name == "brush_model")
    {
      const std::vector<sce::EnumValue> v = sce::enumValues(d->edit_method);
      ASSERT_EQ(v.size(), 5u);
      EXPECT_EQ(v[4].name, "auto");
      EXPECT_EQ(v[4].value, 4);
      EXPECT_EQ(sce::enumValue(v, "auto"), 4);
      EXPECT_FALSE(sce::enumValue(v, "99999999999999999999"));
    }
}
}  // namespace
