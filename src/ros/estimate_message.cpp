#include "sphere_contact_estimator/ros/estimate_message.h"

// STL
#include <algorithm>
#include <cmath>
#include <limits>

namespace sphere_contact_estimator
{
// The message constants are the core's bits and enums, so the conversion copies them as they are.
static_assert(ContactEstimate::FLAG_TIME_JUMP_RESET == estimate_flags::kTimeJumpReset &&
              ContactEstimate::FLAG_GAP_RESET == estimate_flags::kGapReset &&
              ContactEstimate::FLAG_DUPLICATE_STAMP == estimate_flags::kDuplicateStamp &&
              ContactEstimate::FLAG_STANDSTILL == estimate_flags::kStandstill &&
              ContactEstimate::FLAG_HEADING_RESET == estimate_flags::kHeadingReset &&
              ContactEstimate::FLAG_MOTION_WITHIN_NOISE == estimate_flags::kMotionWithinNoise &&
              ContactEstimate::FLAG_STAMP_OUT_OF_ORDER == estimate_flags::kStampOutOfOrder &&
              ContactEstimate::FLAG_NOT_ROLLING == estimate_flags::kNotRolling &&
              ContactEstimate::FLAG_MOTION_HELD == estimate_flags::kMotionHeld);
static_assert(ContactEstimate::BRUSH_FLAG_STANDSTILL == brush_flags::kStandstill &&
              ContactEstimate::BRUSH_FLAG_NO_STEADY_STATE_TILT == brush_flags::kNoSteadyStateTilt &&
              ContactEstimate::BRUSH_FLAG_LINEAR_SATURATED == brush_flags::kLinearSaturated &&
              ContactEstimate::BRUSH_FLAG_SUBSTEPS_TRUNCATED == brush_flags::kSubstepsTruncated &&
              ContactEstimate::BRUSH_FLAG_ACCURACY_NOT_MET == brush_flags::kAccuracyNotMet &&
              ContactEstimate::BRUSH_FLAG_MODEL_FAULT == brush_flags::kModelFault &&
              ContactEstimate::BRUSH_FLAG_BUDGET_LIMITED == brush_flags::kBudgetLimited);
static_assert(ContactEstimate::BRUSH_OFF == static_cast<int>(BrushModelKind::Off) &&
              ContactEstimate::BRUSH_LINEAR == static_cast<int>(BrushModelKind::Linear) &&
              ContactEstimate::BRUSH_STEADY == static_cast<int>(BrushModelKind::Steady) &&
              ContactEstimate::BRUSH_TRANSIENT == static_cast<int>(BrushModelKind::Transient) &&
              ContactEstimate::BRUSH_AUTO == static_cast<int>(BrushModelKind::Auto));
static_assert(ContactEstimate::SLIDING_LAW_COULOMB == static_cast<int>(SlidingLaw::Coulomb) &&
              ContactEstimate::SLIDING_LAW_RIGID == static_cast<int>(SlidingLaw::Rigid));
static_assert(RollingResistance::FLAG_UNDERDAMPED == cylinder_flags::kUnderdamped &&
              RollingResistance::FLAG_SELF_INCONSISTENT == cylinder_flags::kSelfInconsistent &&
              RollingResistance::FLAG_NO_STEADY_STATE == cylinder_flags::kNoSteadyState &&
              RollingResistance::FLAG_EXPANSION_OUT_OF_RANGE == cylinder_flags::kExpansionOutOfRange &&
              RollingResistance::FLAG_LARGE_DEFORMATION == cylinder_flags::kLargeDeformation &&
              RollingResistance::FLAG_TABLE_FALLBACK == cylinder_flags::kTableFallback &&
                  RollingResistance::FLAG_ROOT_NOT_CONVERGED == cylinder_flags::kRootNotConverged &&
              RollingResistance::FLAG_MODEL_FAULT == cylinder_flags::kModelFault);
static_assert(RollingResistance::REGIME_STATIC == static_cast<int>(CylinderRegime::Static) &&
              RollingResistance::REGIME_CONTACT_PATCH == static_cast<int>(CylinderRegime::ContactPatch) &&
              RollingResistance::REGIME_POINT_CONTACT == static_cast<int>(CylinderRegime::PointContact) &&
              RollingResistance::REGIME_NO_STEADY_STATE == static_cast<int>(CylinderRegime::NoSteadyState));
static_assert(RollingResistance::MODEL_OFF == static_cast<int>(CylinderModelKind::Off) &&
              RollingResistance::MODEL_EXACT == static_cast<int>(CylinderModelKind::Exact) &&
              RollingResistance::MODEL_EXPANSION == static_cast<int>(CylinderModelKind::Expansion) &&
              RollingResistance::MODEL_TABLE == static_cast<int>(CylinderModelKind::Table));

static_assert(ContactEstimate::COVARIANCE_OK == static_cast<int>(CovarianceStatus::Ok) &&
              ContactEstimate::COVARIANCE_DISABLED == static_cast<int>(CovarianceStatus::Disabled) &&
              ContactEstimate::COVARIANCE_UNKNOWN == static_cast<int>(CovarianceStatus::Unknown) &&
              ContactEstimate::COVARIANCE_INVALID == static_cast<int>(CovarianceStatus::Invalid) &&
              ContactEstimate::COVARIANCE_UNDEFINED == static_cast<int>(CovarianceStatus::Undefined) &&
              ContactEstimate::COVARIANCE_APPROXIMATE == static_cast<int>(CovarianceStatus::Approximate));
static_assert(ContactEstimate::COVARIANCE_METHOD_NONE == static_cast<int>(CovarianceMethod::None) &&
              ContactEstimate::COVARIANCE_METHOD_ZERO == static_cast<int>(CovarianceMethod::Zero) &&
              ContactEstimate::COVARIANCE_METHOD_JACOBIAN == static_cast<int>(CovarianceMethod::Jacobian) &&
              ContactEstimate::COVARIANCE_METHOD_UNSCENTED == static_cast<int>(CovarianceMethod::Unscented) &&
              ContactEstimate::COVARIANCE_METHOD_RANDOM_WALK == static_cast<int>(CovarianceMethod::RandomWalk));

void toMessage(const ContactEstimateData& e, ContactEstimate& m)
{
  m.rolling_speed = e.rolling_speed;
  m.heading = e.heading;
  m.turn_rate = e.turn_rate;
  m.sliding_velocity.x = e.sliding_velocity.x();
  m.sliding_velocity.y = e.sliding_velocity.y();
  m.sliding_velocity.z = 0.0;
  m.slips_defined = e.slips_defined;
  m.slip.x = e.slip.x();
  m.slip.y = e.slip.y();
  m.slip.z = 0.0;
  m.spin = e.spin;
  m.spin_tilt = e.spin_tilt;
  m.spin_turn = e.spin_turn;
  m.tilt_ratio = e.tilt_ratio;
  m.epsilon.x = e.epsilon.x();
  m.epsilon.y = e.epsilon.y();
  m.epsilon.z = 0.0;

  m.brush_model = static_cast<uint8_t>(e.brush_model);
  m.brush_model_used = static_cast<uint8_t>(e.brush_model_used);
  m.brush_resolution = static_cast<uint16_t>(e.brush_resolution);
  m.sliding_law = static_cast<uint8_t>(e.sliding_law);
  m.patch_radius = e.patch_radius;
  m.load = e.load;
  m.brush_force.x = e.brush.F_x;
  m.brush_force.y = e.brush.F_y;
  m.brush_force.z = 0.0;
  m.brush_moment = e.brush.M_z;
  m.sliding_fraction = e.brush.sliding_fraction;
  m.max_utilisation = e.brush.max_utilisation;
  m.brush_error_estimate = e.brush.error_estimate;
  m.brush_accuracy_target = e.brush_target;
  m.friction = e.friction;
  m.brush_power = e.brush_power;
  m.brush_flags = e.brush.flags;
  m.brush_valid = e.brush_model == BrushModelKind::Off || e.brush.valid();

  RollingResistance& r = m.rolling_resistance;
  const CylinderState& c = e.rolling_resistance;
  r.model = static_cast<uint8_t>(e.rolling_resistance_model);
  r.speed = c.v;
  r.h = c.h;
  r.xi_plus = c.xi_plus;
  r.xi_minus = c.xi_minus;
  r.force = e.rolling_resistance_force;
  r.torque = e.rolling_resistance_torque;
  r.mu_roll = c.mu_roll;
  r.regime = static_cast<uint8_t>(c.regime);
  r.flags = c.flags;
  r.valid = e.rolling_resistance_model == CylinderModelKind::Off || c.valid();
  m.rolling_resistance_power = e.rolling_resistance_power;

  const EstimateCovariance& v = e.covariance;
  m.covariance_status = static_cast<uint8_t>(v.status);
  m.brush_covariance_method = static_cast<uint8_t>(v.brush_method);
  for (int i = 0; i < 9; ++i)
    m.brush_covariance[i] = v.brush_method == CovarianceMethod::None ? (i == 0 ? -1.0 : 0.0) : v.brush(i / 3, i % 3);
  m.brush_covariance_age = v.brush_age;
  m.rolling_resistance_force_variance =
      v.rolling_resistance_method == CovarianceMethod::None ? -1.0 : v.rolling_resistance_force_variance;

  m.valid = e.valid();
  m.motion_to_noise = std::isfinite(e.motion_to_noise) ? e.motion_to_noise : std::numeric_limits<double>::max();  // no inf on a topic
  m.flags = e.flags;
  m.compute_time = e.compute_time;
  m.work = static_cast<std::uint32_t>(std::min<long>(e.work, 0xffffffffL));
}

void brushWrench(const ContactEstimateData& e, geometry_msgs::WrenchStamped& w)
{
  w.wrench.force.x = e.brush.F_x;
  w.wrench.force.y = e.brush.F_y;
  w.wrench.force.z = 0.0;
  w.wrench.torque.x = 0.0;
  w.wrench.torque.y = 0.0;
  w.wrench.torque.z = e.brush.M_z;
}

void rollingResistanceWrench(const ContactEstimateData& e, geometry_msgs::WrenchStamped& w)
{
  w.wrench.force.x = -e.rolling_resistance_force;
  w.wrench.force.y = 0.0;
  w.wrench.force.z = 0.0;
  w.wrench.torque.x = w.wrench.torque.y = w.wrench.torque.z = 0.0;
}

}  // namespace sphere_contact_estimator
