#include "sphere_contact_estimator/ros/parameter_text.h"

// STL
#include <climits>
#include <cmath>
#include <cstdlib>

// Package
#include "sphere_contact_estimator/ContactEstimatorConfig.h"

namespace sphere_contact_estimator
{
namespace
{
// a whole number within int's range (a cast of one beyond it is undefined)
bool isInt(double x)
{
  return std::isfinite(x) && x >= static_cast<double>(INT_MIN) && x <= static_cast<double>(INT_MAX) && std::trunc(x) == x;
}
}  // namespace

std::vector<std::string> repairTextParameters(const ros::NodeHandle& pnh, bool& all_repaired)
{
  std::vector<std::string> lines;
  all_repaired = true;
  for (const auto& d : ContactEstimatorConfig::__getParamDescriptions__())
  {
    if (d->type == "str")
      continue;
    XmlRpc::XmlRpcValue value;
    if (!pnh.getParam(d->name, value) || value.getType() != XmlRpc::XmlRpcValue::TypeString)
      continue;
    const std::string text = static_cast<std::string>(value);
    const std::string name = pnh.resolveName(d->name);
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
    else if (number && d->type == "int" && isInt(x))
    {
      pnh.setParam(d->name, static_cast<int>(x));
      lines.push_back(name + " was the text '" + text + "': read as " + std::to_string(static_cast<int>(x)));
    }
    else
    {
      pnh.deleteParam(d->name);
      all_repaired = false;
      lines.push_back(name + " = '" + text + "' is no " + d->type + ": ignored, the default applies");
    }
  }
  return lines;
}

}  // namespace sphere_contact_estimator
