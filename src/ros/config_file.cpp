#include "sphere_contact_estimator/ros/config_file.h"

// STL
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <vector>

// yaml-cpp
#include <yaml-cpp/yaml.h>

// ROS
#include <ros/package.h>

// Package
#include "sphere_contact_estimator/ros/parameter_enum.h"

namespace sphere_contact_estimator
{
namespace
{
using Description = ContactEstimatorConfig::AbstractParamDescriptionConstPtr;

Description find(const std::string& name)
{
  for (const Description& d : ContactEstimatorConfig::__getParamDescriptions__())
    if (d->name == name)
      return d;
  return nullptr;
}

double toDouble(const std::string& name, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE)
    throw std::invalid_argument("parameter " + name + ": '" + text + "' is not a number");
  return x;
}

bool toBool(const std::string& name, const std::string& text)
{
  if (text == "true" || text == "True" || text == "1")
    return true;
  if (text == "false" || text == "False" || text == "0")
    return false;
  throw std::invalid_argument("parameter " + name + ": '" + text + "' is not true or false");
}
}  // namespace

void setParameter(ContactEstimatorConfig& config, const std::string& name, const std::string& value)
{
  const Description d = find(name);
  if (!d)
    throw std::invalid_argument("unknown parameter '" + name + "' (see cfg/ContactEstimator.cfg)");
  dynamic_reconfigure::Config msg;
  if (d->type == "int")
  {
    dynamic_reconfigure::IntParameter p;
    p.name = name;
    const std::vector<EnumValue> values = enumValues(d->edit_method);
    if (!values.empty())
    {
      const std::optional<int> v = enumValue(values, value);
      if (!v)
        throw std::invalid_argument("parameter " + name + ": '" + value + "' is none of " + describeEnum(values));
      p.value = *v;
    }
    else
    {
      const double x = toDouble(name, value);
      if (!isInt(x))
        throw std::invalid_argument("parameter " + name + ": '" + value + "' is not an integer");
      p.value = static_cast<int>(x);
    }
    msg.ints.push_back(p);
  }
  else if (d->type == "double")
  {
    dynamic_reconfigure::DoubleParameter p;
    p.name = name;
    p.value = toDouble(name, value);
    msg.doubles.push_back(p);
  }
  else if (d->type == "bool")
  {
    dynamic_reconfigure::BoolParameter p;
    p.name = name;
    p.value = toBool(name, value);
    msg.bools.push_back(p);
  }
  else
  {
    dynamic_reconfigure::StrParameter p;
    p.name = name;
    p.value = value;
    msg.strs.push_back(p);
  }
  ContactEstimatorConfig next = config;
  d->fromMessage(msg, next);
  // outside the range: the clamped value differs
  ContactEstimatorConfig clamped = next;
  d->clamp(clamped, ContactEstimatorConfig::__getMax__(), ContactEstimatorConfig::__getMin__());
  dynamic_reconfigure::Config a, b;
  d->toMessage(a, next);
  d->toMessage(b, clamped);
  if (a != b)
  {
    dynamic_reconfigure::Config lo, hi;
    d->toMessage(lo, ContactEstimatorConfig::__getMin__());
    d->toMessage(hi, ContactEstimatorConfig::__getMax__());
    const auto text = [](const dynamic_reconfigure::Config& c) {
      return !c.ints.empty() ? std::to_string(c.ints[0].value) : std::to_string(c.doubles.at(0).value);
    };
    throw std::invalid_argument("parameter " + name + " = " + value + " is outside [" + text(lo) + ", " + text(hi) + "]");
  }
  config = next;
}

void applyParameterFile(ContactEstimatorConfig& config, const std::string& path)
{
  YAML::Node root;
  try
  {
    root = YAML::LoadFile(path);
  }
  catch (const YAML::Exception& e)
  {
    throw std::invalid_argument("parameter file " + path + ": " + e.what());
  }
  if (root.IsNull())
    return;  // empty file: nothing to change
  if (!root.IsMap())
    throw std::invalid_argument("parameter file " + path + ": expected a map of parameter names to values");
  ContactEstimatorConfig next = config;
  for (const auto& entry : root)
  {
    const std::string name = entry.first.as<std::string>();
    if (name == "queue_size")  // the node's start-up only
      continue;
    if (!entry.second.IsScalar())
      throw std::invalid_argument("parameter file " + path + ": " + name + " is not a single value");
    try
    {
      setParameter(next, name, entry.second.as<std::string>());
    }
    catch (const std::invalid_argument& e)
    {
      throw std::invalid_argument("parameter file " + path + ": " + e.what());
    }
  }
  config = next;
}

std::string defaultParameterFile()
{
  const std::string share = ros::package::getPath("sphere_contact_estimator");
  if (share.empty())
    throw std::runtime_error("the package is not on ROS_PACKAGE_PATH: give --params");
  return share + "/config/contact_estimator.yaml";
}

void applyParameterSets(ContactEstimatorConfig& config, const std::vector<std::string>& sets)
{
  for (const std::string& s : sets)
  {
    const auto eq = s.find('=');
    if (eq == std::string::npos)
      throw std::invalid_argument("--set " + s + ": expected NAME=VALUE");
    setParameter(config, s.substr(0, eq), s.substr(eq + 1));
  }
}

}  // namespace sphere_contact_estimator
