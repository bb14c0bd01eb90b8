#pragma once

// STL
#include <optional>
#include <string>

namespace sphere_contact_estimator::bench
{
/// A command-line argument as a whole number within [lo, hi]; nothing for anything else (a sign, a fraction, trailing
/// characters, out of range): the bench programs' seeds and counts.
inline std::optional<long> wholeNumber(const std::string& text, long lo, long hi)
{
  if (text.empty() || text.size() > 12 || text.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  const long v = std::stol(text);
  return v >= lo && v <= hi ? std::optional<long>(v) : std::nullopt;
}
}  // namespace sphere_contact_estimator::bench
