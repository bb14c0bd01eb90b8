#include "sphere_contact_estimator/ros/parameter_text.h"

// STL
#include <climits>
#include <cmath>
#include <cstdlib>
#include <sstream>

// Package
#include "sphere_contact_estimator/ContactEstimatorConfig.h"
#include "sphere_contact_estimator/ros/parameter_enum.h"

namespace sphere_contact_estimator
{
namespace
{
// the parameter's value in the .cfg's minimum or maximum configuration
dynamic_reconfigure::Config bound(const ContactEstimatorConfig::AbstractParamDescription& d, const ContactEstimatorConfig& limit)
{
  dynamic_reconfigure::Config c;
  d.toMessage(c, limit);
  return c;
}
}  // namespace

std::vector<std::string> repairTextParameters(const ros::NodeHandle& pnh, bool& all_repaired)
{
  std::vector<std::string> lines;
  all_repaired = true;
  const ContactEstimatorConfig& lo = ContactEstimatorConfig::__getMin__();
  const ContactEstimatorConfig& hi = ContactEstimatorConfig::__getMax__();
  for (const auto& d : ContactEstimatorConfig::__getParamDescriptions__())
  {
    if (d->type == "str")
      continue;
    XmlRpc::XmlRpcValue value;
    if (!pnh.getParam(d->name, value))
      continue;
    const std::string name = pnh.resolveName(d->name);
    const std::vector<EnumValue> values = enumValues(d->edit_method);
    const auto drop = [&](const std::string& why) {
      pnh.deleteParam(d->name);
      all_repaired = false;
      lines.push_back(name + " = " + why + kParameterIgnored);
    };
    if (value.getType() == XmlRpc::XmlRpcValue::TypeString)
    {
      const std::string text = static_cast<std::string>(value);
      char* end = nullptr;
      const double x = std::strtod(text.c_str(), &end);
      const bool number = !text.empty() && *end == '\0';
      if (d->type == "bool" && (text == "true" || text == "True" || text == "false" || text == "False"))
      {
        pnh.setParam(d->name, text[0] == 't' || text[0] == 'T');
        lines.push_back(name + " was the text '" + text + "': read as a bool");
      }
      else if (number && d->type == "double")
      {
        pnh.setParam(d->name, x);
        lines.push_back(name + " was the text '" + text + "' (YAML 1.1 reads an exponent without a sign as text; " +
                        "write 1.0e+8): read as " + std::to_string(x));
      }
      else if (d->type == "int" && !values.empty() && enumValue(values, text))
        pnh.setParam(d->name, *enumValue(values, text));  // a name of the .cfg: as it should be written
      else if (number && d->type == "int" && values.empty() && isInt(x))
      {
        pnh.setParam(d->name, static_cast<int>(x));
        lines.push_back(name + " was the text '" + text + "': read as " + std::to_string(static_cast<int>(x)));
      }
      else
      {
        drop("'" + text + "' is no " + (values.empty() ? d->type : "one of " + describeEnum(values)));
        continue;
      }
      pnh.getParam(d->name, value);
    }
    // the reconfigure server would clamp a value outside the .cfg's range without a word
    if (d->type == "int" && value.getType() == XmlRpc::XmlRpcValue::TypeInt)
    {
      const int v = static_cast<int>(value);
      const int min = bound(*d, lo).ints.at(0).value, max = bound(*d, hi).ints.at(0).value;
      if (!values.empty() && !enumValue(values, std::to_string(v)))
        drop(std::to_string(v) + " is none of " + describeEnum(values));
      else if (v < min || v > max)
        drop(std::to_string(v) + " is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    else if (d->type == "double" &&
             (value.getType() == XmlRpc::XmlRpcValue::TypeDouble || value.getType() == XmlRpc::XmlRpcValue::TypeInt))
    {
      const double v = value.getType() == XmlRpc::XmlRpcValue::TypeDouble ? static_cast<double>(value)
                                                                          : static_cast<int>(value);
      const double min = bound(*d, lo).doubles.at(0).value, max = bound(*d, hi).doubles.at(0).value;
      if (!(v >= min && v <= max))
      {
        std::ostringstream why;
        why.precision(17);
        why << v << " is outside [" << min << ", " << max << "]";
        drop(why.str());
      }
    }
  }
  return lines;
}

}  // namespace sphere_contact_estimator
