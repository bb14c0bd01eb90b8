#include "sphere_contact_estimator/core/rolling_resistance/cylinder_state.h"

namespace sphere_contact_estimator
{
const char* toString(CylinderRegime regime)
{
  switch (regime)
  {
    case CylinderRegime::Static:
      return "static";
    case CylinderRegime::ContactPatch:
      return "contact_patch";
    case CylinderRegime::PointContact:
      return "point_contact";
    case CylinderRegime::NoSteadyState:
      return "no_steady_state";
  }
  return "unknown";
}

namespace cylinder_flags
{
std::vector<std::string> describe(std::uint32_t flags)
{
  std::vector<std::string> out;
  if (flags & kUnderdamped)
    out.emplace_back("surface not overdamped (eq. 2: 4 m k >= gamma^2): surface waves and multiple contact "
                     "regions are possible, the single-patch model may not hold");
  if (flags & kSelfInconsistent)
    out.emplace_back("self-consistency h > m^2 v^2 / (2 gamma^2 R) fails: past the critical speed the weight "
                     "is carried by the impact force F'_N alone (note 13), where lateral coupling of the surface, "
                     "ignored by the model, matters");
  if (flags & kNoSteadyState)
    out.emplace_back("eq. 18 has no root with f(xi_+) <= 0 (m k > gamma^2): reported at xi_+ = m v / gamma, "
                     "where the forces do not balance the weight");
  if (flags & kExpansionOutOfRange)
    out.emplace_back("speed outside the range of the small-velocity expansion (eqs. 21-27): its next term "
                     "exceeds the tolerance or the truncated series turned unphysical; use the exact model");
  if (flags & kLargeDeformation)
    out.emplace_back("contact half-width xi_+ is not small against R: the parabolic profile of eq. 4 is a "
                     "poor approximation of the circle");
  if (flags & kTableFallback)
    out.emplace_back("speed outside the tabulated range: evaluated by the exact solver");
  if (flags & kRootNotConverged)
    out.emplace_back("the root of eq. 18 was not found to tolerance within the iteration limit: the state is "
                     "the midpoint of the last bracket");
  if (flags & kModelFault)
    out.emplace_back("the rolling-resistance model failed (a defect: please report it with the input): no state");
  return out;
}
}  // namespace cylinder_flags

}  // namespace sphere_contact_estimator
