#include "sphere_contact_estimator/core/numerics/parameter_check.h"

// STL
#include <sstream>
#include <stdexcept>

namespace sphere_contact_estimator::detail
{
void requireParameter(bool ok, const char* kind, const char* name, double value, const char* rule)
{
  if (ok)
    return;
  std::ostringstream msg;
  msg.precision(17);  // the rejected value exactly as it was given
  msg << "invalid " << kind << "parameter " << name << " = " << value << ": must be " << rule;
  throw std::invalid_argument(msg.str());
}
}  // namespace sphere_contact_estimator::detail
