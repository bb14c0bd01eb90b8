#pragma once

// Internal to the core library: the one way parameter validation reports a rejected value.

namespace sphere_contact_estimator::detail
{
/// Throws std::invalid_argument "invalid <kind>parameter <name> = <value>: must be <rule>" unless ok.
/// kind is "" or ends in a space ("brush ").
void requireParameter(bool ok, const char* kind, const char* name, double value, const char* rule);
}  // namespace sphere_contact_estimator::detail
