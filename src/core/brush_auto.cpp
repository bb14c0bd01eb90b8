#include "sphere_contact_estimator/core/brush_auto.h"

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

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

// The largest of |dF_x|, |dF_y| and |dM_z| / a, as a fraction of mu F_z.
double distance(const BrushForces& a, const BrushForces& b, const BrushParameters& p)
{
  const double scale = p.mu * p.F_z;
  if (!(scale > 0.0))
    return 0.0;
  return std::max({ std::abs(a.F_x - b.F_x), std::abs(a.F_y - b.F_y), std::abs(a.M_z - b.M_z) / p.a }) / scale;
}

// The longest travel through the patch from the leading to the trailing edge: 2a on straight paths; an arc
// about a tilting centre at |R_gamma| >= a is at most pi/2 times its chord (the half circle), so pi a.
double longestPath(const BrushParameters& p)
{
  return p.tilt ? boost::math::double_constants::pi * p.a : 2.0 * p.a;
}
}  // namespace

BrushAuto::BrushAuto(const BrushParameters& parameters)
  : BrushModel(parameters), linear_(parameters), steady_(parameters), lag_(parameters.a)
{
  transient_resolution_ = std::min(p_.resolution, kMaxTransientResolution);
  transient_ = std::make_unique<BrushTransient>(withResolution(p_, transient_resolution_));
}

void BrushAuto::rotateFrame(double alpha)
{
  transient_->rotateFrame(alpha);
  // a force, physical, in the turned axes (x' = R(-alpha) x)
  const double c = std::cos(alpha), s = std::sin(alpha);
  lag_.rotate(alpha);
  const Eigen::Vector2d offset(c * offset_.F_x + s * offset_.F_y, -s * offset_.F_x + c * offset_.F_y);
  offset_.F_x = offset.x();
  offset_.F_y = offset.y();
}

void BrushAuto::reset()
{
  transient_->reset();
  in_transient_ = false;
  steady_distance_ = 0.0;
  lag_.reset();
  have_rolling_ = false;
  offset_ = BrushForces{};
  answered_ = false;
}

BrushForces BrushAuto::steadyFamily(const Slips& s, const Eigen::Vector2d& sigma, double budget, BrushModelKind& model)
{
  if (BrushLinear::errorBound(p_, sigma, s.phi, s.phi_gamma, s.phi_psi) <= budget)
  {
    model = BrushModelKind::Linear;
    cost_ += kLinearCost;
    return linear_.evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi);
  }
  model = BrushModelKind::Steady;
  BrushSteady::Stats stats;
  const BrushForces f = steady_.evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi, budget, &stats);
  cost_ += kSteadyPathCost * stats.paths;
  return f;
}

void BrushAuto::enterTransient()
{
  // Warm start: the bristles in the steady state of the last rolling inputs before this step (2.5 transits), so
  // the transient model takes over where the steady one was and then rolls this step under the new inputs; at
  // the finer resolution asked for last time.
  if (pending_resolution_ > transient_resolution_)
  {
    transient_resolution_ = pending_resolution_;
    transient_->setParameters(withResolution(p_, transient_resolution_));
  }
  transient_->reset();
  if (have_rolling_)
  {
    const double V = last_rolling_.V_r.norm();
    transient_->update(last_rolling_, 2.5 * longestPath(p_) / V);
    cost_ += transientStepCost(transient_resolution_) * std::ceil(5.0 * transient_resolution_);
  }
  in_transient_ = true;
  steady_distance_ = 0.0;
  // the warm start is the steady state of the last inputs, which the true state lagged by at most the lag then
  // (the steady family's answer accepted it); only renewed bristles forget that
  entry_error_ = last_lag_;
}

BrushForces BrushAuto::update(const ContactKinematics& kin, double dt)
{
  checkInput(kin, dt);
  const Slips s = computeSlips(kin, p_.standstill_speed);
  const double target = p_.accuracy_target;
  const BrushModelKind before = last_model_;
  const int before_resolution = last_resolution_;

  // Conditions under which a steady state describes the contact, and the lag of that state.
  bool steady_ok = s.defined;
  bool renewed = false;  // every bristle entered under these inputs: the state is exactly the steady one
  double lag = 0.0;
  Eigen::Vector2d sigma = Eigen::Vector2d::Zero();
  RollingFrame frame(s.defined ? s.epsilon : Eigen::Vector2d(0.0, 1.0));
  if (s.defined)
  {
    sigma = frame.toRolling(s.sigma);
    if (p_.tilt && std::abs(s.phi_gamma) * p_.a > 1.0)
      steady_ok = false;  // |R_gamma| < a: no steady state on an inner disc
    renewed = s.V_r * dt >= longestPath(p_);
    // the lag of the steady state behind the true one, from the changes of the (saturated) linear forces
    const double limit = p_.mu * p_.F_z;
    BrushForces lin = linear_.evaluate(sigma, s.phi);
    frame.forcesToPatch(lin);
    lag_.step(Eigen::Vector3d(lin.F_x, lin.F_y, lin.M_z / p_.a), s.V_r * dt);
    lag = limit > 0.0 ? lag_.lag() / limit : 0.0;
    if (!(lag <= 0.5 * target))
      steady_ok = false;
  }
  else
    lag_.reset();

  if (in_transient_ && steady_ok)
  {
    steady_distance_ += s.V_r * dt;
    if (renewed || steady_distance_ >= longestPath(p_))
      in_transient_ = false;  // its state is the steady one now
  }
  else if (in_transient_)
    steady_distance_ = 0.0;
  else if (!steady_ok)
    enterTransient();  // from the state before this step
  if (s.defined)
  {
    last_rolling_ = kin;
    have_rolling_ = true;
    last_lag_ = lag;
  }

  BrushForces out;
  BrushModelKind model;
  int resolution = 0;
  if (in_transient_)
  {
    out = transient_->update(kin, dt);
    entry_error_ *= lag_.memory(s.V_r * dt);
    out.error_estimate += entry_error_;
    model = BrushModelKind::Transient;
    resolution = transient_resolution_;
    cost_ += transientStepCost(resolution) * std::max(1.0, std::ceil(s.V_r * dt / (p_.a / resolution)));
    // A missed target asks for twice the resolution. Rolling, the bristle state is interpolated onto the finer
    // lattice at once (a rare event: it allocates), and the interpolation's error leaves the patch with the
    // bristles within a transit. At standstill nothing renews the state, so the interpolation's error would stay
    // (measured on the demo bag): the finer lattice waits for the next entry into the transient model, whose
    // warm start builds the state afresh, and the estimate meanwhile says that the target is missed.
    if (out.error_estimate > target && transient_resolution_ < kMaxTransientResolution)
    {
      const int finer = std::min(2 * transient_resolution_, kMaxTransientResolution);
      if (s.defined)
      {
        auto next = std::make_unique<BrushTransient>(withResolution(p_, finer));
        next->resampleFrom(*transient_);
        transient_ = std::move(next);
        transient_resolution_ = finer;
      }
      else
        pending_resolution_ = finer;
    }
  }
  else
  {
    out = steadyFamily(s, sigma, target - lag, model);
    out.error_estimate += lag;
    frame.forcesToPatch(out);
  }

  // Continuity: at a switch, carry the difference from the previous model's answer and let it decay (the first
  // answer after a reset has nothing to be continuous with).
  if (answered_ && (model != before || resolution != before_resolution))
  {
    BrushForces previous = out;
    if (before == BrushModelKind::Transient)
      previous = transient_->forces();
    else if (s.defined && before == BrushModelKind::Linear)
    {
      previous = linear_.evaluate(sigma, s.phi);
      frame.forcesToPatch(previous);
    }
    else if (s.defined && before == BrushModelKind::Steady)
    {
      previous = steady_.evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi, std::max(0.5 * target, 1e-6));
      frame.forcesToPatch(previous);
    }
    offset_.F_x += previous.F_x - out.F_x;
    offset_.F_y += previous.F_y - out.F_y;
    offset_.M_z += previous.M_z - out.M_z;
  }
  const double decay = s.V_r > 0.0 ? std::exp(-s.V_r * dt / (0.5 * p_.a)) : std::exp(-dt / 0.05);
  offset_.F_x *= decay;
  offset_.F_y *= decay;
  offset_.M_z *= decay;
  out.F_x += offset_.F_x;
  out.F_y += offset_.F_y;
  out.M_z += offset_.M_z;
  out.error_estimate += distance(offset_, BrushForces{}, p_);
  // the offset never takes the force off the friction circle
  const double norm = std::hypot(out.F_x, out.F_y), limit = p_.mu * p_.F_z;
  if (norm > limit && norm > 0.0)
  {
    out.F_x *= limit / norm;
    out.F_y *= limit / norm;
  }
  out.flags &= ~brush_flags::kLinearSaturated;  // auto never publishes a saturated linear answer as such
  if (out.error_estimate > target)
    out.flags |= brush_flags::kAccuracyNotMet;
  else
    out.flags &= ~brush_flags::kAccuracyNotMet;
  last_model_ = model;
  last_resolution_ = resolution;
  answered_ = true;
  return out;
}

}  // namespace sphere_contact_estimator
