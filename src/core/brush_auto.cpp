#include "sphere_contact_estimator/core/brush_auto.h"

// STL
#include <cmath>

// Package
#include "sphere_contact_estimator/core/rolling_frame.h"

namespace sphere_contact_estimator
{
namespace
{
BrushParameters withResolution(BrushParameters p, int n)
{
  p.resolution = n;
  return p;
}

BrushForces difference(const BrushForces& a, const BrushForces& b)
{
  BrushForces d;
  d.F_x = a.F_x - b.F_x;
  d.F_y = a.F_y - b.F_y;
  d.M_z = a.M_z - b.M_z;
  return d;
}
}  // namespace

const std::vector<int>& BrushAuto::ladder()
{
  static const std::vector<int> resolutions{ 4, 8, 12, 16, 24, 32, 48, 64 };
  return resolutions;
}

double BrushAuto::transientError(int resolution)
{
  return 0.055 * std::pow(8.0 / resolution, 1.5);
}

double BrushAuto::linearError(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi)
{
  const double C_sigma = BrushLinear::slipStiffness(p), C_phi = BrushLinear::spinStiffness(p);
  const double limit = p.mu * p.F_z;
  if (!(limit > 0.0))
    return INFINITY;
  const double u = (C_sigma * sigma.norm() + 2.0 * C_phi * std::abs(phi)) / limit;
  return 0.5 * u * u;
}

BrushAuto::BrushAuto(const BrushParameters& parameters) : BrushModel(parameters), linear_(parameters)
{
  for (int n : ladder())
    steady_.push_back(std::make_unique<BrushSteady>(withResolution(p_, n)));
  transient_resolution_ = ladder().back();
  for (int n : ladder())
    if (n >= 8 && transientError(n) <= p_.accuracy_target)
    {
      transient_resolution_ = n;
      break;
    }
  transient_ = std::make_unique<BrushTransient>(withResolution(p_, transient_resolution_));
}

void BrushAuto::rotateFrame(double alpha)
{
  transient_->rotateFrame(alpha);
  // a force, physical, in the turned axes (x' = R(-alpha) x)
  const double c = std::cos(alpha), s = std::sin(alpha);
  previous_force_ = Eigen::Vector2d(c * previous_force_.x() + s * previous_force_.y(),
                                    -s * previous_force_.x() + c * previous_force_.y());
  const Eigen::Vector2d offset(c * offset_.F_x + s * offset_.F_y, -s * offset_.F_x + c * offset_.F_y);
  offset_.F_x = offset.x();
  offset_.F_y = offset.y();
}

void BrushAuto::reset()
{
  transient_->reset();
  in_transient_ = false;
  steady_distance_ = 0.0;
  have_previous_ = false;
  have_rolling_ = false;
  offset_ = BrushForces{};
}

BrushForces BrushAuto::runSteadyFamily(const Slips& s, const Eigen::Vector2d& sigma, double budget, BrushModelKind& model,
                                       int& resolution)  // budget: the error allowed, relative to mu F_z
{
  if (linearError(p_, sigma, s.phi) <= budget)
  {
    model = BrushModelKind::Linear;
    resolution = 0;
    cost_ += kLinearCost;
    return linear_.evaluate(sigma, s.phi);
  }
  std::size_t i = 0;
  while (i + 1 < ladder().size() && steadyError(ladder()[i]) > budget)
    ++i;
  model = BrushModelKind::Steady;
  resolution = ladder()[i];
  cost_ += steadyCost(resolution);
  return steady_[i]->evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi);
}

void BrushAuto::enterTransient()
{
  // Warm start: the bristles in the steady state of the last rolling inputs (2.5 transits), so the
  // transient model takes over where the steady one was.
  transient_->reset();
  if (have_rolling_)
  {
    const double V = last_rolling_.V_r.norm();
    const double t = 5.0 * p_.a / V;
    transient_->update(last_rolling_, t);
    cost_ += transientStepCost(transient_resolution_) * std::ceil(5.0 * transient_resolution_);
  }
  in_transient_ = true;
  steady_distance_ = 0.0;
}

BrushForces BrushAuto::update(const ContactKinematics& kin, double dt)
{
  checkInput(kin, dt);
  const Slips s = computeSlips(kin, p_.standstill_speed);
  const double target = p_.accuracy_target;
  const BrushModelKind before = last_model_;
  const int before_resolution = last_resolution_;

  // Conditions under which a steady state describes the contact.
  bool steady_ok = s.defined;
  Eigen::Vector2d sigma = Eigen::Vector2d::Zero();
  RollingFrame frame(s.defined ? s.epsilon : Eigen::Vector2d(0.0, 1.0));
  if (s.defined)
  {
    sigma = frame.toRolling(s.sigma);
    if (p_.tilt && std::abs(s.phi_gamma) * p_.a > 1.0)
      steady_ok = false;  // |R_gamma| < a: no steady state on an inner disc
    // lag of the steady state: change of the (saturated) linear force over about a/V_r
    const BrushForces lin = linear_.evaluate(sigma, s.phi);
    const Eigen::Vector2d F(lin.F_x, lin.F_y);
    if (have_previous_ && dt > 0.0)
    {
      const double lag = (F - previous_force_).norm() / dt * (p_.a / s.V_r) / (p_.mu * p_.F_z);
      if (lag > 0.5 * target)
        steady_ok = false;
    }
    previous_force_ = F;
    have_previous_ = true;
    last_rolling_ = kin;
    have_rolling_ = true;
  }
  else
    have_previous_ = false;

  BrushForces out;
  BrushModelKind model;
  int resolution;
  if (in_transient_ && steady_ok)
  {
    steady_distance_ += s.V_r * dt;
    if (steady_distance_ >= 2.0 * p_.a)
      in_transient_ = false;  // its state is the steady one now
  }
  else if (in_transient_)
    steady_distance_ = 0.0;
  else if (!steady_ok)
    enterTransient();

  if (in_transient_)
  {
    out = transient_->update(kin, dt);
    model = BrushModelKind::Transient;
    resolution = transient_resolution_;
    cost_ += transientStepCost(resolution) * std::max(1.0, std::ceil(s.V_r * dt / (p_.a / resolution)));
  }
  else
  {
    out = runSteadyFamily(s, sigma, target, model, resolution);
    // keep the transient model's clock: forget its state, it is re-seeded when needed
    frame.forcesToPatch(out);
  }

  // Continuity: at a switch, carry the difference from the previous model's answer and let it decay.
  if (model != before || resolution != before_resolution)
  {
    BrushForces previous;
    if (before == BrushModelKind::Transient)
      previous = transient_->forces();
    else if (s.defined && before == BrushModelKind::Linear)
    {
      previous = linear_.evaluate(sigma, s.phi);
      frame.forcesToPatch(previous);
    }
    else if (s.defined && before == BrushModelKind::Steady)
    {
      for (std::size_t i = 0; i < ladder().size(); ++i)
        if (ladder()[i] == before_resolution)
          previous = steady_[i]->evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi);
      frame.forcesToPatch(previous);
    }
    else
      previous = out;
    const BrushForces jump = difference(previous, out);
    offset_.F_x += jump.F_x;
    offset_.F_y += jump.F_y;
    offset_.M_z += jump.M_z;
  }
  const double decay = s.V_r > 0.0 ? std::exp(-s.V_r * dt / (0.5 * p_.a)) : std::exp(-dt / 0.05);
  offset_.F_x *= decay;
  offset_.F_y *= decay;
  offset_.M_z *= decay;
  out.F_x += offset_.F_x;
  out.F_y += offset_.F_y;
  out.M_z += offset_.M_z;
  // the offset never takes the force off the friction circle
  const double norm = std::hypot(out.F_x, out.F_y), limit = p_.mu * p_.F_z;
  if (norm > limit && norm > 0.0)
  {
    out.F_x *= limit / norm;
    out.F_y *= limit / norm;
  }
  out.flags &= ~brush_flags::kLinearSaturated;  // auto never publishes a saturated linear answer as such
  last_model_ = model;
  last_resolution_ = resolution;
  return out;
}

}  // namespace sphere_contact_estimator
