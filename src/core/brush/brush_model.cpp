#include "sphere_contact_estimator/core/brush/brush_model.h"

// STL
#include <cmath>
#include <sstream>
#include <stdexcept>

// Package
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "rolling_frame.h"

namespace sphere_contact_estimator
{
const char* toString(BrushModelKind kind)
{
  switch (kind)
  {
    case BrushModelKind::Off:
      return "off";
    case BrushModelKind::Linear:
      return "linear";
    case BrushModelKind::Steady:
      return "steady";
    case BrushModelKind::Transient:
      return "transient";
    case BrushModelKind::Auto:
      return "auto";
  }
  return "unknown";
}

std::optional<BrushModelKind> parseBrushModelKind(std::string_view name)
{
  for (auto kind : { BrushModelKind::Linear, BrushModelKind::Steady, BrushModelKind::Transient, BrushModelKind::Auto })
    if (name == toString(kind))
      return kind;
  return std::nullopt;
}

BrushModel::BrushModel(const BrushParameters& parameters) : p_(parameters)
{
  p_.validate();
}

void BrushModel::checkInput(const ContactKinematics& k, double dt)
{
  if (!(k.V_r.allFinite() && k.V_s.allFinite() && std::isfinite(k.omega_z) && std::isfinite(k.psi_dot)))
    throw std::invalid_argument("brush model: contact kinematics must be finite");
  if (!(std::isfinite(dt) && dt >= 0.0))
  {
    std::ostringstream msg;
    msg << "brush model: time step dt = " << dt << " s must be finite and >= 0";
    throw std::invalid_argument(msg.str());
  }
}

BrushForces BrushSlipModel::update(const ContactKinematics& kin, double dt)
{
  checkInput(kin, dt);
  const Slips s = computeSlips(kin, p_.standstill_speed);
  last_ = s;
  if (!s.defined)
  {
    BrushForces f;
    f.flags |= brush_flags::kStandstill;
    return f;
  }
  const RollingFrame frame(s.epsilon);
  BrushForces f = evaluate(frame.toRolling(s.sigma), s.phi, s.phi_gamma, s.phi_psi);
  frame.forcesToPatch(f);
  f.flagAbove(p_.accuracy_target);  // (the linear model's bound too)
  return f;
}

std::unique_ptr<BrushModel> makeBrushModel(BrushModelKind kind, const BrushParameters& parameters)
{
  switch (kind)
  {
    case BrushModelKind::Off:
      return nullptr;
    case BrushModelKind::Linear:
      return std::make_unique<BrushLinear>(parameters);
    case BrushModelKind::Steady:
      return std::make_unique<BrushSteady>(parameters);
    case BrushModelKind::Transient:
      return std::make_unique<BrushTransient>(parameters);
    case BrushModelKind::Auto:
      return std::make_unique<BrushAuto>(parameters);
  }
  throw std::invalid_argument("unknown brush model kind");
}

}  // namespace sphere_contact_estimator
