#include "sphere_contact_estimator/core/brush/brush_model.h"

// STL
#include <cmath>
#include <sstream>
#include <stdexcept>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "rolling_frame.h"

namespace sphere_contact_estimator
{
const std::array<Eigen::Vector2d, AdhesionResponse::kDirections>& AdhesionResponse::directions()
{
  static const std::array<Eigen::Vector2d, kDirections> table = [] {
    std::array<Eigen::Vector2d, kDirections> t;
    for (int j = 0; j < kDirections; ++j)
    {
      const double angle = boost::math::double_constants::two_pi * j / kDirections;
      t[j] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    }
    return t;
  }();
  return table;
}

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

void BrushModel::checkInput(const ContactKinematics& k, const Slips& s, double dt) const
{
  if (!(k.V_r.allFinite() && k.V_s.allFinite() && std::isfinite(k.omega_z) && std::isfinite(k.psi_dot)))
    throw std::invalid_argument("brush model: contact kinematics must be finite");
  if (!(std::isfinite(dt) && dt >= 0.0))
  {
    std::ostringstream msg;
    msg << "brush model: time step dt = " << dt << " s must be finite and >= 0";
    throw std::invalid_argument(msg.str());
  }
  // (the slips' other components follow from the kinematics as these two do; a caller's own computeSlips gives them all)
  if (!(s.V_r == k.V_r.norm() && s.defined == (s.V_r >= p_.standstill_speed && s.V_r > 0.0)))
  {
    std::ostringstream msg;
    msg << "brush model: slips (V_r = " << s.V_r << " m/s, " << (s.defined ? "defined" : "undefined")
        << ") are not those of the kinematics (|V_r| = " << k.V_r.norm() << " m/s) at standstill_speed "
        << p_.standstill_speed << " m/s";
    throw std::invalid_argument(msg.str());
  }
}

BrushForces BrushSlipModel::update(const ContactKinematics& kin, const Slips& s, double dt)
{
  checkInput(kin, s, dt);
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
