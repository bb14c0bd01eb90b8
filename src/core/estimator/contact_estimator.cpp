#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

// Package
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/estimator/motion_noise.h"
#include "sphere_contact_estimator/core/estimator/paper_frame.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_spread.h"

// STL
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

// Boost
#include <boost/math/constants/constants.hpp>

namespace sphere_contact_estimator
{
namespace
{
using boost::math::double_constants::pi;

double wrap(double angle)
{
  return std::remainder(angle, 2.0 * pi);
}

// the five twist components the models use (motion_noise.h), ROS ground frame
UsedTwist usedTwist(const EstimatorInput& in)
{
  UsedTwist x;
  x << in.v_contact.x(), in.v_contact.y(), in.omega.x(), in.omega.y(), in.omega.z();
  return x;
}
}  // namespace

bool ContactEstimateData::valid() const
{
  return (brush_model == BrushModelKind::Off || brush.valid()) &&
         (rolling_resistance_model == CylinderModelKind::Off || rolling_resistance.valid());
}

bool ContactEstimateData::modelFault() const
{
  return (brush.flags & brush_flags::kModelFault) || (rolling_resistance.flags & cylinder_flags::kModelFault);
}

ContactEstimator::ContactEstimator(const EstimatorSettings& settings)
{
  settings.validate();
  // the steady solver's quadrature rules, built on first use: here, not in the first message that needs them (the
  // first covariance or steady answer took about 0.5 ms more, 1 ms in all on a slow host)
  BrushSteady::prepareRules();
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
                             (next.brush_model != BrushModelKind::Off && next.brushParameters() != settings_.brushParameters());
  const bool cylinder_changes =
      next.rolling_resistance_model != settings_.rolling_resistance_model ||
      (next.rolling_resistance_model != CylinderModelKind::Off &&
       next.cylinderParameters() != settings_.cylinderParameters());
  if (cylinder_changes)
    rebuildCylinder(next);
  if (brush_changes)
  {
    rebuildBrush(next);
    walk_.lose();  // a retuned state's forces answer to new parameters: unknown until the slips are defined again
  }
  settings_ = next;
  held_covariance_.valid = false;
  hold_.clear();  // (motion within the noise: what it held is not worth a step under new settings)
  adopt();
}

void ContactEstimator::rebuildBrush(const EstimatorSettings& next)
{
  if (next.brush_model == BrushModelKind::Off)
  {
    brush_.reset();
    return;
  }
  // a model that can keeps its state through a retune (the transient bristles)
  if (brush_ && next.brush_model == settings_.brush_model && brush_->retune(next.brushParameters()))
    return;
  brush_ = makeBrushModel(next.brush_model, next.brushParameters());
}

void ContactEstimator::rebuildCylinder(const EstimatorSettings& next)
{
  cylinder_ = makeCylinderModel(next.rolling_resistance_model, next.cylinderParameters());  // none for Off
}

void ContactEstimator::reset()
{
  have_last_ = false;
  was_rolling_ = false;
  have_heading_ = false;  // the next message's body yaw, or its rolling direction, sets it
  heading_ = 0.0;
  turn_rate_ = 0.0;
  not_rolling_time_ = 0.0;
  held_covariance_.valid = false;
  walk_.restart(Eigen::Matrix3d::Zero());  // the model's own start
  hold_.clear();
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

bool ContactEstimator::acceptable(const EstimatorInput& in, const Eigen::Vector2d& V_r, double speed) const
{
  const double R = settings_.rolling_radius;
  return std::isfinite(in.stamp) && in.omega.allFinite() && in.v_contact.allFinite() && speed <= CylinderModel::kMaxSpeed &&
         in.v_contact.norm() <= CylinderModel::kMaxSpeed && in.omega.norm() * R <= CylinderModel::kMaxSpeed &&
         slipsRepresentable(in, V_r, speed);
}

const ContactEstimateData* ContactEstimator::update(const EstimatorInput& in)
{
  const Eigen::Vector2d V_r = rollingVelocity(in.omega);
  const double speed = V_r.norm();
  if (!acceptable(in, V_r, speed))
    return nullptr;
  const auto start = std::chrono::steady_clock::now();
  ContactEstimateData& o = out_;
  o.flags = 0;
  o.stamp = in.stamp;
  const bool first = !have_last_;
  o.dt = advanceClock(in.stamp, o.flags);
  followHeading(V_r, speed, in.body_heading, o.dt, first, o.flags);
  judgeRolling(in, speed, o);
  const double psi_dot = turnRate(in.omega.z());
  o.heading = heading_;
  o.turn_rate = psi_dot;
  o.rolling_speed = speed;
  Slips slips;  // of kin: computed once, the brush model's too
  const ContactKinematics kin = contactKinematics(in, psi_dot, o, slips);
  o.work = 0;
  // A model that throws has a defect, which no input should reach; one message answered without its forces, flagged,
  // and the model's state reset, serves a robot better than a node that dies (or a replay that stops) at it.
  judgeMotion(in, o);
  const MotionHold::Decision hold = holdMotion(in, V_r, o);
  try
  {
    propagateBrushCovariance(in, speed, o);
    advanceBrush(in, kin, slips, hold, o);
    if (o.covariance.brush_method == CovarianceMethod::RandomWalk)  // this message's share, through the state as it is now
      walkBrushCovariance(in, o);
  }
  catch (const std::exception& error)
  {
    fault("brush model", error, o);
    o.covariance = EstimateCovariance{};
    o.covariance.status = CovarianceStatus::Undefined;
    clearBrush(o);
    o.brush.flags = brush_flags::kModelFault;
    if (brush_)
      brush_->reset();
    walk_.restart(Eigen::Matrix3d::Zero());
    hold_.clear();
  }
  try
  {
    runRollingResistance(speed, o);
    propagateRollingResistanceCovariance(speed, o);
  }
  catch (const std::exception& error)
  {
    fault("rolling-resistance model", error, o);
    o.rolling_resistance = CylinderState{};
    o.rolling_resistance.flags = cylinder_flags::kModelFault;
    o.rolling_resistance_force = o.rolling_resistance_torque = o.rolling_resistance_power = 0.0;
  }
  o.compute_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return &o;
}

void ContactEstimator::fault(const char* model, const std::exception& error, const ContactEstimateData& o)
{
  ++faults_;
  char head[96];
  std::snprintf(head, sizeof head, "%s threw at t = %.9f s: ", model, o.stamp);
  last_fault_ = std::string(head) + error.what();
}

double ContactEstimator::advanceClock(double stamp, std::uint32_t& flags)
{
  // message stamps only (sim time and bags alike), never the wall clock
  double dt = 0.0;
  if (have_last_)
  {
    const double gap = stamp - last_stamp_;
    if (gap < 0.0 && -gap <= settings_.stamp_tolerance)
      flags |= estimate_flags::kStampOutOfOrder;  // jitter (a USB source): a reset would lose the whole state
    else if (gap < 0.0)
    {
      reset();
      flags |= estimate_flags::kTimeJumpReset;
    }
    else if (gap < kMinStep)
      flags |= estimate_flags::kDuplicateStamp;  // nothing advances (a rate over 1e-315 s overflowed)
    else if (gap > settings_.max_step)
    {
      if (brush_)
        brush_->reset();
      walk_.restart(Eigen::Matrix3d::Zero());
      hold_.clear();
      turn_rate_ = 0.0;
      was_rolling_ = false;
      flags |= estimate_flags::kGapReset;
    }
    else
      dt = gap;
  }
  if (!(flags & (estimate_flags::kDuplicateStamp | estimate_flags::kStampOutOfOrder)))  // sub-nanosecond steps add up to one that counts; the clock never goes back
    last_stamp_ = stamp;
  have_last_ = true;
  return dt;
}

void ContactEstimator::followHeading(const Eigen::Vector2d& V_r, double speed, double body_heading, double dt, bool first,
                                     std::uint32_t& flags)
{
  // the contact frame: x along V_r, held at standstill; psi_dot from its heading
  const bool rolling = speed >= settings_.standstill_speed;
  if (rolling)
  {
    const double theta = std::atan2(V_r.y(), V_r.x());
    const double delta = wrap(theta - heading_);
    if (!was_rolling_ || std::abs(delta) > kHeadingJump)
    {
      // re-initialise: turn the bristle state with the frame (a turn about z up, the paper's z down), no rate
      // from the jump
      if (brush_)
        brush_->rotateFrame(paper_frame::zFromRos(delta));
      if (!first)
        flags |= estimate_flags::kHeadingReset;
      turn_rate_ = 0.0;
    }
    else if (dt > 0.0)
    {
      const double tau = settings_.turn_rate_time_constant;
      const double gain = tau > 0.0 ? -std::expm1(-dt / tau) : 1.0;
      turn_rate_ += gain * (delta / dt - turn_rate_);
    }
    heading_ = theta;
    have_heading_ = true;
  }
  else
  {
    if (!have_heading_ && std::isfinite(body_heading))
    {
      heading_ = body_heading;  // standing: the robot's own yaw until it rolls (a reset forgets the old heading)
      have_heading_ = true;
    }
    turn_rate_ = 0.0;  // the frame does not turn at standstill
    flags |= estimate_flags::kStandstill;
  }
  was_rolling_ = rolling;
}

ContactKinematics ContactEstimator::contactKinematics(const EstimatorInput& in, double psi_dot, ContactEstimateData& o,
                                                     Slips& sl) const
{
  const ContactKinematics kin = paperKinematics(in.omega, in.v_contact, psi_dot);
  using namespace paper_frame;
  sl = computeSlips(kin, settings_.standstill_speed);
  o.sliding_velocity = toRos(kin.V_s);
  o.slips_defined = sl.defined;
  o.slip = toRos(sl.sigma);
  o.spin = zToRos(sl.phi);
  o.spin_tilt = zToRos(sl.phi_gamma);
  o.spin_turn = zToRos(sl.phi_psi);
  o.tilt_ratio = sl.chi_gamma.value_or(1.0);
  o.epsilon = sl.epsilon;
  return kin;
}

ContactKinematics ContactEstimator::paperKinematics(const Eigen::Vector3d& omega, const Eigen::Vector3d& v_contact,
                                                   double psi_dot) const
{
  // ground -> contact frame (yaw by the heading) -> paper frame
  const double c = std::cos(heading_), s = std::sin(heading_);
  const auto toContact = [c, s](const Eigen::Vector3d& x) {
    return Eigen::Vector3d(c * x.x() + s * x.y(), -s * x.x() + c * x.y(), x.z());
  };
  using namespace paper_frame;
  return ContactKinematics::fromWheel(fromRos(toContact(omega)), fromRos(Eigen::Vector2d(toContact(v_contact).head<2>())),
                                      settings_.rolling_radius, zFromRos(psi_dot));
}

Eigen::Vector2d ContactEstimator::rollingVelocity(const Eigen::Vector3d& omega) const
{
  const double R = settings_.rolling_radius;
  return { omega.y() * R, -omega.x() * R };  // pure rolling, ROS axes (docs/conventions.md)
}

double ContactEstimator::turnRate(double omega_z) const
{
  return settings_.tilt_ratio_source == TiltRatioSource::Fixed ? (1.0 - settings_.tilt_ratio) * omega_z : turn_rate_;
}

MotionHold::Decision ContactEstimator::holdMotion(const EstimatorInput& in, const Eigen::Vector2d& V_r,
                                                  ContactEstimateData& o)
{
  // Only a model with a state has anything to hold (the linear and steady ones answer each message's inputs), and only
  // a patch that moves nowhere faster than standstill_speed (V_r, and the drive |V_s| + |omega_z| a) is parked: a twist
  // covariance declared far too large (1e3 where a source does not measure a component, say) then holds no rolling,
  // skidding or spinning robot, it only widens their bands.
  const bool state = brush_ && (brush_->kind() == BrushModelKind::Transient || brush_->kind() == BrushModelKind::Auto);
  const double still = settings_.standstill_speed;
  const bool parked = V_r.norm() < still &&
                      (in.v_contact.head<2>() - V_r).norm() + std::abs(in.omega.z()) * patch_radius_ < still;
  if (!settings_.hold_within_noise || !state || !parked)
  {
    hold_.clear();  // (moving: what was held, within its noise, is let go, as MotionHold::offer does)
    return MotionHold::Decision::Advance;
  }
  // motion_to_noise is negative (unknown) without a usable covariance: nothing is held then, and what was is let go
  const Eigen::Matrix<double, 5, 5> S = o.motion_to_noise >= 0.0 ? usedTwistCovariance(in.twist_covariance)
                                                                 : Eigen::Matrix<double, 5, 5>::Zero();
  const MotionHold::Decision d = hold_.offer(usedTwist(in), S, o.dt, o.motion_to_noise);
  if (d == MotionHold::Decision::Hold)
    o.flags |= estimate_flags::kMotionHeld;
  return d;
}

void ContactEstimator::advanceBrush(const EstimatorInput& in, const ContactKinematics& kin, const Slips& slips,
                                    MotionHold::Decision hold, ContactEstimateData& o)
{
  if (hold == MotionHold::Decision::Hold)
  {
    runBrush(kin, slips, 0.0, in.omega.z(), o);  // the state as the motion before the hold left it
    // nothing moves, so nothing slides (eq. 4b without a drive: v_s = 0), whatever the last motion left on the bounds
    o.brush.sliding_fraction = 0.0;
    return;
  }
  if (hold == MotionHold::Decision::Release)
  {
    // the held motion, this message's included, in one step: its mean twist over its time, in the frame as it stands
    // (the bristles respond to the path, not its pace: eq. 1 is linear in the velocities)
    const UsedTwist m = hold_.meanTwist();
    EstimatorInput mean = in;
    mean.omega = Eigen::Vector3d(m(2), m(3), m(4));
    mean.v_contact = Eigen::Vector3d(m(0), m(1), 0.0);
    const Eigen::Vector2d V_r = rollingVelocity(mean.omega);
    const double duration = hold_.duration();
    hold_.clear();
    // (a mean of acceptable twists is finite and below the speed of light, but its slips may pass a double's range
    // where standstill_speed is tinier than the noise: then this message's own step, as without the hold)
    if (slipsRepresentable(mean, V_r, V_r.norm()))
    {
      const ContactKinematics held = paperKinematics(mean.omega, mean.v_contact, turnRate(mean.omega.z()));
      runBrush(held, computeSlips(held, settings_.standstill_speed), duration, in.omega.z(), o);
      return;
    }
  }
  runBrush(kin, slips, o.dt, in.omega.z(), o);
}

void ContactEstimator::clearBrush(ContactEstimateData& o) const
{
  o.brush_model = settings_.brush_model;
  o.sliding_law = settings_.sliding_law;
  o.brush_model_used = BrushModelKind::Off;
  o.brush_resolution = 0;
  o.brush_target = 0.0;
  o.brush = BrushForces{};
  o.friction = 0.0;
  o.patch_radius = patch_radius_;
  o.load = load_;
  o.brush_power = 0.0;
}

void ContactEstimator::runBrush(const ContactKinematics& kin, const Slips& slips, double dt, double omega_z,
                                ContactEstimateData& o)
{
  clearBrush(o);
  if (brush_)
  {
    brush_->setInputSpread(o.covariance.brush_method == CovarianceMethod::None ? 0.0 : o.covariance.brush_spread);
    // what the covariance left, less the granularity of the work (a path or a substep under way when it ran out): the
    // message's total stays within the budget, whatever the model (EstimatorSettings::validate: at a fixed resolution
    // the transient model's least update fits)
    brush_->setWorkBudget(settings_.work_budget - o.work - BrushModel::kWorkGranularity);
    o.brush = brush_->update(kin, slips, dt);
    o.work += o.brush.work;
    o.brush_model_used = brush_->lastModel();
    o.brush_resolution = brush_->lastResolution();
    o.brush_target = brush_->lastTarget();
    const Eigen::Vector2d F = paper_frame::toRos(Eigen::Vector2d(o.brush.F_x, o.brush.F_y));
    o.brush.F_x = F.x();
    o.brush.F_y = F.y();
    o.brush.M_z = paper_frame::zToRos(o.brush.M_z);
    o.friction = brush_->parameters().mu;
  }
  // a scalar: the same in both frames (ROS omega_z is about z up, like M_z)
  o.brush_power = -(o.brush.F_x * o.sliding_velocity.x() + o.brush.F_y * o.sliding_velocity.y() + o.brush.M_z * omega_z);
}

void ContactEstimator::runRollingResistance(double speed, ContactEstimateData& o) const
{
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
}

void ContactEstimator::judgeRolling(const EstimatorInput& in, double speed, ContactEstimateData& o)
{
  // The centre moving while the shell does not roll: V_C beyond standstill_speed and three standard deviations of its
  // declared noise, V_r below a tenth of it. Briefly a skid; for long, almost always the body's yaw rate published as
  // twist.angular (the shell's omega then has no x, y part), which reads as sliding at full friction.
  const double v_c = in.v_contact.head<2>().norm();
  double sd = 0.0;
  if (in.twist_covariance_status == CovarianceStatus::Ok)
    sd = std::sqrt(std::max(0.0, in.twist_covariance(0, 0) + in.twist_covariance(1, 1)));
  const bool mismatch = v_c > settings_.standstill_speed && v_c > 3.0 * sd && speed < 0.1 * v_c;
  not_rolling_time_ = mismatch ? not_rolling_time_ + o.dt : 0.0;
  if (not_rolling_time_ > kNotRollingTime)
    o.flags |= estimate_flags::kNotRolling;
}

void ContactEstimator::judgeMotion(const EstimatorInput& in, ContactEstimateData& o) const
{
  // a parked robot's odometry is its noise: said so, instead of letting its forces read as measured sliding
  // (a judgement of the input against its own declared noise: with or without the covariance carried to the outputs)
  o.motion_to_noise = -1.0;
  if (in.twist_covariance_status != CovarianceStatus::Ok)
    return;
  o.motion_to_noise = motionToNoise(usedTwist(in), usedTwistCovariance(in.twist_covariance));
  if (o.motion_to_noise >= 0.0 && o.motion_to_noise <= kMotionWithinNoise)
    o.flags |= estimate_flags::kMotionWithinNoise;
}

bool ContactEstimator::reuseBrushCovariance(const Eigen::Matrix<double, 5, 5>& S, const ContactEstimateData& o) const
{
  // the last propagation, if it was within covariance_period before this stamp (not after: an out-of-order stamp), of
  // the same twist covariance and brush parameters, and nothing since was reset or re-initialised
  const HeldCovariance& h = held_covariance_;
  const double age = o.stamp - h.stamp;
  constexpr std::uint32_t kFresh =
      estimate_flags::kTimeJumpReset | estimate_flags::kGapReset | estimate_flags::kHeadingReset;
  if (!(h.valid && settings_.covariance_period > 0.0 && age >= 0.0 && age < settings_.covariance_period &&
        !(o.flags & kFresh) && brush_->parameters() == h.parameters))
    return false;
  // the same twist covariance up to rounding: each element within 1e-9 of its scale sqrt(S_ii S_jj) (the ground frame's
  // turn of an isotropic covariance changes its last bits)
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      if (!(std::abs(S(i, j) - h.twist(i, j)) <= 1e-9 * std::sqrt(h.twist(i, i) * h.twist(j, j))))
        return false;
  return true;
}

void ContactEstimator::propagateBrushCovariance(const EstimatorInput& in, double speed, ContactEstimateData& o)
{
  // the twist's covariance to the slips by the exact Jacobian of eqs. 2, 12, 13, then through the brush model
  EstimateCovariance& c = o.covariance;
  c = EstimateCovariance{};
  if (!settings_.propagate_covariance)
  {
    c.status = CovarianceStatus::Disabled;
    walk_.lose();  // (switched on again while parked: the noise of the messages between was not walked)
    return;
  }
  c.status = in.twist_covariance_status;
  if (c.status != CovarianceStatus::Ok)
  {
    walk_.lose();  // this message's noise is unknown, and so what the state integrates from here
    return;
  }
  const Eigen::Matrix<double, 5, 5> S = usedTwistCovariance(in.twist_covariance);
  const double R = settings_.rolling_radius;
  const Eigen::Matrix<double, 1, 5> dV = speedJacobian(R, heading_);
  c.rolling_speed_variance = (dV * S * dV.transpose())(0, 0);
  if (!std::isfinite(c.rolling_speed_variance))
  {
    c = EstimateCovariance{};
    c.status = CovarianceStatus::Invalid;  // finite, but too large to carry through
    walk_.lose();
    return;
  }
  if (!brush_)
    return;
  if (!o.slips_defined)
  {
    // no slips at standstill: the forces have no stateless map here, but the bristles' state integrates the noise
    held_covariance_.valid = false;
    if (!walk_.known())
      c.status = CovarianceStatus::Undefined;
    else
      publishWalk(o);  // the walk so far (auto's target follows it); this message's share once the model has run
    return;
  }
  // the slips divide by V_r: where its spread reaches the standstill speed, the linearisation is out of its range
  const bool near_standstill = speed - 3.0 * std::sqrt(c.rolling_speed_variance) < settings_.standstill_speed;
  if (reuseBrushCovariance(S, o))
  {
    const HeldCovariance& h = held_covariance_;
    c.brush = h.brush;
    c.brush_method = h.method;
    c.brush_spread = h.spread;
    c.brush_age = o.stamp - h.stamp;
    if (near_standstill || !h.smooth)
      c.status = CovarianceStatus::Approximate;
    walk_.restart(c.brush);
    return;
  }
  held_covariance_.valid = false;
  const Eigen::Matrix<double, 4, 5> K = slipJacobian(in.omega, in.v_contact.head<2>(), R, heading_);
  Eigen::Matrix4d slips = K * S * K.transpose();
  slips = 0.5 * (slips + slips.transpose());
  const BrushParameters& p = brush_->parameters();
  const BrushModelKind kind =
      settings_.brush_model == BrushModelKind::Linear ? BrushModelKind::Linear : BrushModelKind::Steady;
  ForceCovariance f;
  try
  {
    f = propagateSlipCovariance(kind, p, paper_frame::fromRos(o.slip), paper_frame::zFromRos(o.spin), o.tilt_ratio,
                                slips, static_cast<long>(kCovarianceShare * static_cast<double>(settings_.work_budget)));
    o.work += f.work;
  }
  catch (const std::invalid_argument&)
  {
    c = EstimateCovariance{};
    c.status = CovarianceStatus::Invalid;  // the slips' covariance overflowed
    walk_.lose();
    return;
  }
  if (!f.defined)
  {
    c.status = CovarianceStatus::Undefined;
    walk_.lose();
    return;
  }
  c.brush = paper_frame::toRos(f.covariance);  // F_y and M_z change sign
  c.brush_method = f.method;
  c.brush_spread = f.spread(p);
  if (!c.brush.allFinite())
  {
    c = EstimateCovariance{};
    c.status = CovarianceStatus::Invalid;
    walk_.lose();
    return;
  }
  // where the forces kink or jump over the spread, the transform's moments are only approximate
  if (near_standstill || !f.smooth)
    c.status = CovarianceStatus::Approximate;
  walk_.restart(c.brush);
  held_covariance_ = HeldCovariance{ true, o.stamp, S, p, c.brush, c.brush_method, c.brush_spread, f.smooth };
}

void ContactEstimator::walkBrushCovariance(const EstimatorInput& in, ContactEstimateData& o)
{
  EstimateCovariance& c = o.covariance;
  const auto undefined = [&c] {
    c.brush.setZero();
    c.brush_method = CovarianceMethod::None;
    c.brush_spread = 0.0;
    c.status = CovarianceStatus::Undefined;
  };
  // Spinning in place most bristles slide, and a sliding bristle forgets the noise it integrated: a walk would
  // overstate the forces' spread (2-8 times in test_uncertainty). No covariance here. (Held, nothing slides: the walk
  // says what the held noise could do to the bristles on their bounds.)
  if (o.brush.sliding_fraction > StandstillCovariance::kSlidingShare)
  {
    undefined();
    return;
  }
  const BrushParameters& p = brush_->parameters();
  const Eigen::Matrix<double, 5, 5> G = driveJacobian(settings_.rolling_radius, heading_);
  const Eigen::Matrix<double, 5, 5> drive = G * usedTwistCovariance(in.twist_covariance) * G.transpose();
  AdhesionResponse response;
  long work = 0;
  if (!brush_->adhesionResponse(response, work, walk_.known() ? walk_.band(drive, o.dt, p.a) : 0.0))
  {
    undefined();  // no state that integrates the noise (linear, steady)
    walk_.lose();
    return;
  }
  o.work += work;
  const double limit = p.mu * p.F_z;
  walk_.advance(response, drive, o.dt, Eigen::Vector3d(limit, limit, limit * p.a), p.a);
  publishWalk(o);
}

void ContactEstimator::publishWalk(ContactEstimateData& o) const
{
  EstimateCovariance& c = o.covariance;
  c.brush = walk_.covariance();
  c.brush_method = CovarianceMethod::RandomWalk;
  ForceCovariance f;
  f.covariance = c.brush;
  c.brush_spread = f.spread(brush_->parameters());
  c.status = CovarianceStatus::Approximate;  // (StandstillCovariance: what it leaves out)
}

void ContactEstimator::propagateRollingResistanceCovariance(double speed, ContactEstimateData& o) const
{
  EstimateCovariance& c = o.covariance;
  const bool carried = c.status == CovarianceStatus::Ok || c.status == CovarianceStatus::Undefined ||
                       c.status == CovarianceStatus::Approximate;
  if (!cylinder_ || !carried)
    return;
  const CylinderSpread s = cylinderSpread(*cylinder_, speed, std::sqrt(c.rolling_speed_variance));
  const double L = cylinder_->parameters().L;
  c.rolling_resistance_method = s.method;
  c.rolling_resistance_force_variance = s.F_R_variance * L * L;
  c.mu_roll_variance = s.mu_roll_variance;
}

void ContactEstimator::visitBristles(const BristleVisitor& visit) const
{
  if (brush_)
    brush_->visitBristles([&visit](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool sliding) {
      visit(paper_frame::toRos(x), paper_frame::toRos(u), sliding);
    });
}

}  // namespace sphere_contact_estimator
