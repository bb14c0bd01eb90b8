#include "sphere_contact_estimator/ros/config_report.h"

// STL
#include <algorithm>
#include <cctype>
#include <cstdio>

// Package
#include "sphere_contact_estimator/ros/parameter_enum.h"

namespace sphere_contact_estimator
{
namespace
{
using Description = ContactEstimatorConfig::AbstractParamDescriptionConstPtr;

// the parameter's value in config as text: an enum by its name, a double to 10 digits, a string quoted
std::string valueText(const Description& d, const ContactEstimatorConfig& config)
{
  dynamic_reconfigure::Config msg;
  d->toMessage(msg, config);
  if (!msg.ints.empty())
  {
    const int v = msg.ints[0].value;
    for (const EnumValue& e : enumValues(d->edit_method))
      if (e.value == v)
        return e.name;
    return std::to_string(v);
  }
  if (!msg.doubles.empty())
  {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", msg.doubles[0].value);
    return text;
  }
  if (!msg.bools.empty())
    return msg.bools[0].value ? "true" : "false";
  if (!msg.strs.empty())
    return "'" + msg.strs[0].value + "'";
  return "?";
}

std::string lower(std::string s)
{
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::size_t editDistance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t above = row[j];
      row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1) });
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::vector<std::string> knownNames(const std::vector<std::string>& extra)
{
  std::vector<std::string> names = extra;
  for (const Description& d : ContactEstimatorConfig::__getParamDescriptions__())
    names.push_back(d->name);
  return names;
}
}  // namespace

std::string configurationText(const ContactEstimatorConfig& config)
{
  std::string text;
  for (const Description& d : ContactEstimatorConfig::__getParamDescriptions__())
    text += (text.empty() ? "" : ", ") + d->name + " " + valueText(d, config);
  return text;
}

std::string parameterFileText(const ContactEstimatorConfig& config,
                              const std::function<std::string(const std::string&)>& comment)
{
  std::string text;
  for (const Description& d : ContactEstimatorConfig::__getParamDescriptions__())
  {
    std::string value = valueText(d, config);
    // YAML 1.1 (rosparam, roslaunch) reads a float only with a dot: 1e-05 would be a string
    dynamic_reconfigure::Config msg;
    d->toMessage(msg, config);
    const auto e = value.find('e');
    if (!msg.doubles.empty() && e != std::string::npos && value.find('.') == std::string::npos)
      value.insert(e, ".0");
    std::string line = d->name + ": " + value;
    const std::string extra = comment ? comment(d->name) : std::string();
    if (!extra.empty())
      line += std::string(std::max<std::size_t>(1, 30 - std::min<std::size_t>(line.size(), 30)), ' ') + "# " + extra;
    text += line + "\n";
  }
  return text;
}

std::vector<ParameterChange> configurationChanges(const ContactEstimatorConfig& before, const ContactEstimatorConfig& after)
{
  std::vector<ParameterChange> changes;
  for (const Description& d : ContactEstimatorConfig::__getParamDescriptions__())
  {
    dynamic_reconfigure::Config a, b, lo, hi;
    d->toMessage(a, before);
    d->toMessage(b, after);
    if (a == b)
      continue;
    d->toMessage(lo, ContactEstimatorConfig::__getMin__());
    d->toMessage(hi, ContactEstimatorConfig::__getMax__());
    ParameterChange c{ d->name, valueText(d, before), valueText(d, after) };
    // strings and bools have no range; an enum's ends are values like any other
    if (!b.doubles.empty())
      c.at_bound = b.doubles[0].value == lo.doubles[0].value || b.doubles[0].value == hi.doubles[0].value;
    else if (!b.ints.empty() && enumValues(d->edit_method).empty())
      c.at_bound = b.ints[0].value == lo.ints[0].value || b.ints[0].value == hi.ints[0].value;
    changes.push_back(c);
  }
  return changes;
}

std::string describeChanges(const std::vector<ParameterChange>& changes)
{
  std::string text;
  for (const ParameterChange& c : changes)
    text += (text.empty() ? "" : ", ") + c.name + " " + c.before + " -> " + c.after;
  return text;
}

std::string nearestParameter(const std::string& name, const std::vector<std::string>& extra)
{
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const std::string& known : knownNames(extra))
  {
    const std::size_t d = editDistance(lower(name), lower(known));
    if (d < best_distance)
    {
      best_distance = d;
      best = known;
    }
  }
  return best;
}

bool isKnownParameter(const std::string& name, const std::vector<std::string>& extra)
{
  const std::vector<std::string> names = knownNames(extra);
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace sphere_contact_estimator
