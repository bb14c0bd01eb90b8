#include "sphere_contact_estimator/core/contact_estimator.h"

// STL
#include <chrono>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/brush_auto.h"
#include "sphere_contact_estimator/core/brush_steady.h"
#include "sphere_contact_estimator/core/brush_transient.h"
#include "sphere_contact_estimator/core/rolling_frame.h"

namespace sphere_contact_estimator
{
namespace
{
using boost::math::double_constants::pi;

double wrap(double angle)
{
  return std::remainder(angle, 2.0 * pi);
}

BrushModelKind kindOf(BrushChoice c)
{
  switch (c)
  {
    case BrushChoice::Linear:
      return BrushModelKind::Linear;
    case BrushChoice::Steady:
      return BrushModelKind::Steady;
    case BrushChoice::Auto:
      return BrushModelKind::Auto;
    default:
      return BrushModelKind::Transient;
  }
}

BrushChoice choiceOf(BrushModelKind k)
{
  switch (k)
  {
    case BrushModelKind::Linear:
      return BrushChoice::Linear;
    case BrushModelKind::Steady:
      return BrushChoice::Steady;
    case BrushModelKind::Auto:
      return BrushChoice::Auto;
    default:
      return BrushChoice::Transient;
  }
}
}  // namespace

bool ContactEstimateData::valid() const
{
  return (brush_model == BrushChoice::Off || brush.valid()) &&
         (rolling_resistance_model == RollingResistanceChoice::Off || rolling_resistance.valid());
}

ContactEstimator::ContactEstimator(const EstimatorSettings& settings)
{
  settings.validate();
  rebuildBrush(settings);
  rebuildCylinder(settings);
  settings_ = settings;
  adopt();
}

void ContactEstimator::adopt()
{
  // the scene's patch and load, whether or not a brush model runs (the markers draw them)
  const BrushParameters p = settings_.brushParameters();
  patch_radius_ = p.a;
  load_ = p.F_z;
}

void ContactEstimator::configure(const EstimatorSettings& next)
{
  next.validate();
  // build first, so that a failure (e.g. a table that cannot be built) leaves everything as it was
  const bool brush_changes = next.brush_model != settings_.brush_model ||
                             (next.brush_model != BrushChoice::Off && next.brushParameters() != settings_.brushParameters());
  const bool cylinder_changes =
      next.rolling_resistance_model != settings_.rolling_resistance_model ||
      (next.rolling_resistance_model != RollingResistanceChoice::Off &&
       next.cylinderParameters() != settings_.cylinderParameters());
  if (cylinder_changes)
    rebuildCylinder(next);
  if (brush_changes)
    rebuildBrush(next);
  settings_ = next;
  adopt();
}

void ContactEstimator::rebuildBrush(const EstimatorSettings& next)
{
  if (next.brush_model == BrushChoice::Off)
  {
    brush_.reset();
    return;
  }
  // the transient state survives a retune of the same model (BrushTransient::setParameters)
  if (brush_ && next.brush_model == settings_.brush_model && next.brush_model == BrushChoice::Transient)
  {
    static_cast<BrushTransient&>(*brush_).setParameters(next.brushParameters());
    return;
  }
  brush_ = makeBrushModel(kindOf(next.brush_model), next.brushParameters());
}

void ContactEstimator::rebuildCylinder(const EstimatorSettings& next)
{
  switch (next.rolling_resistance_model)
  {
    case RollingResistanceChoice::Off:
      cylinder_.reset();
      return;
    case RollingResistanceChoice::Exact:
      cylinder_ = makeCylinderModel(CylinderModelKind::Exact, next.cylinderParameters());
      return;
    case RollingResistanceChoice::Expansion:
      cylinder_ = makeCylinderModel(CylinderModelKind::Expansion, next.cylinderParameters());
      return;
    case RollingResistanceChoice::Table:
      cylinder_ = makeCylinderModel(CylinderModelKind::Table, next.cylinderParameters());
      return;
  }
}

void ContactEstimator::reset()
{
  have_last_ = false;
  was_rolling_ = false;
  heading_ = 0.0;
  turn_rate_ = 0.0;
  if (brush_)
    brush_->reset();
}

bool ContactEstimator::slipsRepresentable(const EstimatorInput& in, const Eigen::Vector2d& V_r, double speed) const
{
  // The slips divide by V_r: past the standstill speed (which may be tiny) the ratios must stay finite, the
  // turn rate's included (at most pi per kMinStep); fuzz_estimator found omega_z = -2e307 rad/s at V_r = 2 mm/s.
  if (speed < settings_.standstill_speed)
    return true;
  const double V_s = (in.v_contact.head<2>() - V_r).norm();
  const double turn = std::abs(in.omega.z()) * (1.0 + std::abs(1.0 - settings_.tilt_ratio)) + pi / kMinStep;
  return std::isfinite(V_s / speed) && std::isfinite(turn / speed);
}

const ContactEstimateData* ContactEstimator::update(const EstimatorInput& in)
{
  const double R = settings_.rolling_radius;
  const Eigen::Vector2d V_r(in.omega.y() * R, -in.omega.x() * R);  // pure rolling, ROS axes (docs/conventions.md)
  const double speed = V_r.norm();
  if (!(std::isfinite(in.stamp) && in.omega.allFinite() && in.v_contact.allFinite() && speed <= CylinderModel::kMaxSpeed &&
        in.v_contact.norm() <= CylinderModel::kMaxSpeed && in.omega.norm() * R <= CylinderModel::kMaxSpeed &&
        slipsRepresentable(in, V_r, speed)))
    return nullptr;
  const auto start = std::chrono::steady_clock::now();
  ContactEstimateData& o = out_;
  o.flags = 0;
  o.stamp = in.stamp;

  // Time: message stamps only (sim time and bags alike), never the wall clock.
  double dt = 0.0;
  if (have_last_)
  {
    const double gap = in.stamp - last_stamp_;
    if (gap < 0.0)
    {
      reset();
      o.flags |= estimate_flags::kTimeJumpReset;
    }
    else if (gap < kMinStep)
      o.flags |= estimate_flags::kDuplicateStamp;  // nothing advances (a rate over 1e-315 s overflowed)
    else if (gap > settings_.max_step)
    {
      if (brush_)
        brush_->reset();
      turn_rate_ = 0.0;
      was_rolling_ = false;
      o.flags |= estimate_flags::kGapReset;
    }
    else
      dt = gap;
  }
  const bool first = !have_last_;
  if (!(o.flags & estimate_flags::kDuplicateStamp))  // sub-nanosecond steps add up to one that counts
    last_stamp_ = in.stamp;
  have_last_ = true;
  o.dt = dt;

  // Contact frame: x along V_r, held at standstill; psi_dot from its heading.
  const bool rolling = speed >= settings_.standstill_speed;
  if (rolling)
  {
    const double theta = std::atan2(V_r.y(), V_r.x());
    const double delta = wrap(theta - heading_);
    if (!was_rolling_ || std::abs(delta) > kHeadingJump)
    {
      // re-initialise: turn the bristle state with the frame (a turn of delta about z up is -delta about
      // the paper's z down), no rate from the jump
      if (brush_)
        brush_->rotateFrame(-delta);
      if (!first)
        o.flags |= estimate_flags::kHeadingReset;
      turn_rate_ = 0.0;
    }
    else if (dt > 0.0)
    {
      const double tau = settings_.turn_rate_time_constant;
      const double gain = tau > 0.0 ? -std::expm1(-dt / tau) : 1.0;
      turn_rate_ += gain * (delta / dt - turn_rate_);
    }
    heading_ = theta;
  }
  else
  {
    turn_rate_ = 0.0;  // the frame does not turn at standstill
    o.flags |= estimate_flags::kStandstill;
  }
  was_rolling_ = rolling;
  const double psi_dot =
      settings_.tilt_ratio_source == TiltRatioSource::Fixed ? (1.0 - settings_.tilt_ratio) * in.omega.z() : turn_rate_;
  o.heading = heading_;
  o.turn_rate = psi_dot;

  // Ground -> contact frame (yaw heading) -> paper frame (x, -y, -z).
  const double c = std::cos(heading_), s = std::sin(heading_);
  const auto toContact = [c, s](double x, double y) { return Eigen::Vector2d(c * x + s * y, -s * x + c * y); };
  const Eigen::Vector2d w = toContact(in.omega.x(), in.omega.y());
  const Eigen::Vector2d v = toContact(in.v_contact.x(), in.v_contact.y());
  const ContactKinematics kin = ContactKinematics::fromWheel(Eigen::Vector3d(w.x(), -w.y(), -in.omega.z()),
                                                             Eigen::Vector2d(v.x(), -v.y()), R, -psi_dot);
  const Slips sl = computeSlips(kin, settings_.standstill_speed);
  last_slips_ = sl;
  o.rolling_speed = speed;
  o.sliding_velocity = Eigen::Vector2d(kin.V_s.x(), -kin.V_s.y());
  o.slips_defined = sl.defined;
  o.slip = Eigen::Vector2d(sl.sigma.x(), -sl.sigma.y());
  o.spin = -sl.phi;
  o.spin_tilt = -sl.phi_gamma;
  o.spin_turn = -sl.phi_psi;
  o.tilt_ratio = sl.chi_gamma.value_or(1.0);
  o.epsilon = sl.epsilon;

  o.brush_model = settings_.brush_model;
  o.brush_model_used = BrushChoice::Off;
  o.brush_resolution = 0;
  o.brush = BrushForces{};
  o.friction = 0.0;
  o.patch_radius = patch_radius_;
  o.load = load_;
  if (brush_)
  {
    o.brush = brush_->update(kin, dt);
    o.brush_model_used = settings_.brush_model;
    o.brush_resolution = brush_->kind() == BrushModelKind::Transient ? brush_->parameters().resolution : 0;
    if (const auto* automatic = dynamic_cast<const BrushAuto*>(brush_.get()))
    {
      o.brush_model_used = choiceOf(automatic->lastModel());
      o.brush_resolution = automatic->lastResolution();
    }
    o.brush.F_y = -o.brush.F_y;  // paper -> ROS
    o.brush.M_z = -o.brush.M_z;
    o.friction = brush_->parameters().mu;
  }
  // a scalar: the same in both frames (ROS omega_z is about z up, like M_z)
  o.brush_power = -(o.brush.F_x * o.sliding_velocity.x() + o.brush.F_y * o.sliding_velocity.y() + o.brush.M_z * in.omega.z());
  o.rolling_resistance_model = settings_.rolling_resistance_model;
  o.rolling_resistance = CylinderState{};
  o.rolling_resistance_force = o.rolling_resistance_torque = 0.0;
  if (cylinder_)
  {
    o.rolling_resistance = cylinder_->solve(speed);
    o.rolling_resistance_force = o.rolling_resistance.F_R * cylinder_->parameters().L;
    o.rolling_resistance_torque = o.rolling_resistance.torque * cylinder_->parameters().L;
  }
  o.rolling_resistance_power = o.rolling_resistance_force * speed;
  o.compute_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return &o;
}

void ContactEstimator::visitBristles(const std::function<void(const Eigen::Vector2d& x, bool sliding)>& visit) const
{
  const auto ros = [&visit](const Eigen::Vector2d& x, bool sliding) { visit(Eigen::Vector2d(x.x(), -x.y()), sliding); };
  if (const auto* transient = dynamic_cast<const BrushTransient*>(brush_.get()))
    transient->forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d&, bool sliding) { ros(x, sliding); });
  else if (const auto* steady = dynamic_cast<const BrushSteady*>(brush_.get()))
  {
    if (!last_slips_.defined)
      return;
    const RollingFrame frame(last_slips_.epsilon);  // (0, 1) here: the contact frame follows V_r
    steady->evaluate(frame.toRolling(last_slips_.sigma), last_slips_.phi, last_slips_.phi_gamma, last_slips_.phi_psi,
                     [&](const Eigen::Vector2d& x, const Eigen::Vector2d&, bool sliding) { ros(frame.toPatch(x), sliding); });
  }
}

}  // namespace sphere_contact_estimator
