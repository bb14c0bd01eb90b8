#include "sphere_contact_estimator/ros/parameter_enum.h"

// STL
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <regex>

namespace sphere_contact_estimator
{
std::vector<EnumValue> enumValues(const std::string& edit_method)
{
  // dynamic_reconfigure writes each constant as {'name': 'off', 'type': 'int', 'value': 0, ...}
  static const std::regex constant(R"('name': '([^']*)', 'type': '[^']*', 'value': (-?[0-9]+))");
  std::vector<EnumValue> values;
  for (auto it = std::sregex_iterator(edit_method.begin(), edit_method.end(), constant); it != std::sregex_iterator(); ++it)
    values.push_back({ (*it)[1].str(), std::stoi((*it)[2].str()) });
  return values;
}

std::optional<int> enumValue(const std::vector<EnumValue>& values, const std::string& text)
{
  // without regard to case, as dynparam matches them
  const auto same = [](const std::string& a, const std::string& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
             return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
  };
  for (const EnumValue& v : values)
    if (same(text, v.name))
      return v.value;
  char* end = nullptr;
  errno = 0;
  const long number = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno == ERANGE || number < INT_MIN || number > INT_MAX)
    return std::nullopt;
  for (const EnumValue& v : values)
    if (v.value == number)
      return v.value;
  return std::nullopt;
}

bool isInt(double x)
{
  return std::isfinite(x) && x >= static_cast<double>(INT_MIN) && x <= static_cast<double>(INT_MAX) && std::trunc(x) == x;
}

std::string describeEnum(const std::vector<EnumValue>& values)
{
  std::string text;
  for (const EnumValue& v : values)
    text += (text.empty() ? "" : ", ") + v.name + " (" + std::to_string(v.value) + ")";
  return text;
}

}  // namespace sphere_contact_estimator
