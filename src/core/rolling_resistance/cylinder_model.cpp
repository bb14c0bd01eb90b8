#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"

// STL
#include <cmath>
#include <sstream>
#include <stdexcept>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

namespace sphere_contact_estimator
{
const char* toString(CylinderModelKind kind)
{
  switch (kind)
  {
    case CylinderModelKind::Off:
      return "off";
    case CylinderModelKind::Exact:
      return "exact";
    case CylinderModelKind::Expansion:
      return "expansion";
    case CylinderModelKind::Table:
      return "table";
  }
  return "unknown";
}

std::optional<CylinderModelKind> parseCylinderModelKind(std::string_view name)
{
  for (auto kind : { CylinderModelKind::Exact, CylinderModelKind::Expansion, CylinderModelKind::Table })
    if (name == toString(kind))
      return kind;
  return std::nullopt;
}

CylinderModel::CylinderModel(const CylinderParameters& parameters) : p_(parameters)
{
  p_.validate();
  scales_ = CylinderScales::of(p_);
}

void CylinderModel::checkSpeed(double v)
{
  if (v >= 0.0 && v <= kMaxSpeed)
    return;
  std::ostringstream msg;
  msg.precision(17);
  msg << "invalid rolling speed v = " << v << " m/s: must be finite, >= 0 and below the speed of light";
  throw std::invalid_argument(msg.str());
}

CylinderState CylinderModel::staticState() const
{
  CylinderState s;
  s.v = 0.0;
  s.h = scales_.h0;           // eq. 25
  s.xi_plus = scales_.xi0;    // eq. 22
  s.xi_minus = -scales_.xi0;  // eq. 23 at v = 0
  s.F_N = p_.weight();
  s.F_R = 0.0;
  s.regime = CylinderRegime::Static;
  finish(s);
  return s;
}

void CylinderModel::finish(CylinderState& s) const
{
  const double v2 = s.v * s.v;
  s.F_N_impact = p_.m * v2 * s.xi_plus / p_.R;       // eq. 8
  s.F_R_impact = p_.m * v2 * 2.0 * s.h / p_.R;       // impact term of eq. 17
  s.torque = p_.R * s.F_R;                           // M = R F_R
  s.mu_roll = s.torque / p_.weight();                // eq. 26
  if (!scales_.overdamped)
    s.flags |= cylinder_flags::kUnderdamped;
  if (s.regime == CylinderRegime::PointContact)
    s.flags |= cylinder_flags::kSelfInconsistent;
  if (s.regime == CylinderRegime::NoSteadyState)
    s.flags |= cylinder_flags::kNoSteadyState | cylinder_flags::kSelfInconsistent;
  if (s.xi_plus > CylinderExact::kLargeDeformation * p_.R)
    s.flags |= cylinder_flags::kLargeDeformation;
}

std::unique_ptr<CylinderModel> makeCylinderModel(CylinderModelKind kind, const CylinderParameters& parameters)
{
  switch (kind)
  {
    case CylinderModelKind::Off:
      return nullptr;
    case CylinderModelKind::Exact:
      return std::make_unique<CylinderExact>(parameters);
    case CylinderModelKind::Expansion:
      return std::make_unique<CylinderExpansion>(parameters);
    case CylinderModelKind::Table:
      return std::make_unique<CylinderTable>(parameters);
  }
  throw std::invalid_argument("unknown cylinder model kind");
}

}  // namespace sphere_contact_estimator
