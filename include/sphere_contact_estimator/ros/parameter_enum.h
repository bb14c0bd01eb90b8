#pragma once

// STL
#include <optional>
#include <string>
#include <vector>

namespace sphere_contact_estimator
{
/// One named value of an enum parameter of cfg/ContactEstimator.cfg.
struct EnumValue
{
  std::string name;
  int value = 0;
};

/// The named values of an enum parameter, read from the edit_method that dynamic_reconfigure generates
/// from the .cfg; empty for a parameter that is no enum.
std::vector<EnumValue> enumValues(const std::string& edit_method);

/// The value that text means: a name of the .cfg without regard to case, as dynparam reads them ("steady", "off" for
/// the rolling-resistance model's "Off") or the number of one of the values ("2"). Nothing for anything else.
std::optional<int> enumValue(const std::vector<EnumValue>& values, const std::string& text);

/// A whole number within int's range, which an int parameter can take (a cast of one beyond it is undefined).
bool isInt(double x);

/// "off (0), linear (1), ...": the valid values, for error messages.
std::string describeEnum(const std::vector<EnumValue>& values);

}  // namespace sphere_contact_estimator
