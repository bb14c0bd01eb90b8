#pragma once

// STL
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <string>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_model.h"
#include "sphere_contact_estimator/core/estimator/estimate_covariance.h"
#include "sphere_contact_estimator/core/estimator/estimator_settings.h"
#include "sphere_contact_estimator/core/estimator/motion_hold.h"
#include "sphere_contact_estimator/core/estimator/standstill_covariance.h"
#include "sphere_contact_estimator/core/estimator/twist_covariance.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"

namespace sphere_contact_estimator
{
/// Wheel kinematics of one odometry message, rotated into a gravity-aligned ground frame with ROS axes
/// (REP 103: z up).
struct EstimatorInput
{
  /// message time [s], from any origin (the ROS layer counts from the first stamp it was given, in integer
  /// nanoseconds: seconds since 1970 as a double resolve only 2.4e-7 s)
  double stamp = 0.0;
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();        ///< angular velocity of the sphere [rad/s]
  Eigen::Vector3d v_contact = Eigen::Vector3d::Zero();    ///< velocity of the contact-patch centre [m/s]
  /// The covariance of (v_contact, omega) in the same frame (rows linear x, y, z, angular x, y, z), and what the
  /// odometry's own check of it found (checkTwistCovariance; only an Ok one is used). Zero: exact inputs.
  TwistCovariance twist_covariance = TwistCovariance::Zero();
  CovarianceStatus twist_covariance_status = CovarianceStatus::Ok;
  /// The yaw of the robot's x axis (child_frame_id) in the ground frame [rad], NaN if unknown: the contact frame's
  /// heading until the sphere first rolls (at start-up and after a reset), instead of the ground frame's x.
  double body_heading = std::numeric_limits<double>::quiet_NaN();
};

/// Bit flags of one estimate, beside the models' own (brush_flags, cylinder_flags).
namespace estimate_flags
{
constexpr std::uint32_t kTimeJumpReset = 1u << 0;   ///< stamp went backwards (looping bag): state reset
constexpr std::uint32_t kGapReset = 1u << 1;        ///< gap longer than max_step: transient state reset
constexpr std::uint32_t kDuplicateStamp = 1u << 2;  ///< within 1 ns of the last stamp: not advanced
constexpr std::uint32_t kStandstill = 1u << 3;      ///< V_r below standstill_speed: slips undefined
constexpr std::uint32_t kHeadingReset = 1u << 4;    ///< rolling direction re-initialised (after standstill
                                                    ///< or a jump): the transient state was turned with it
/// The motion is within the noise the twist covariance declares (motionToNoise <= kMotionWithinNoise): a parked
/// robot. The brush forces are then the bristles' response to that noise, not a measured sliding.
constexpr std::uint32_t kMotionWithinNoise = 1u << 6;  // (bit 5 is the ROS layer's: orientation from odometry)
/// The stamp is earlier than the last one by at most stamp_tolerance (jitter): answered at its inputs, nothing
/// advanced, nothing reset (the clock stays at the latest stamp).
constexpr std::uint32_t kStampOutOfOrder = 1u << 7;
/// For longer than kNotRollingTime the centre has moved (beyond standstill_speed and three times the declared noise)
/// while the shell rolled at less than a tenth of its speed: a long skid, or, far more likely, `twist.angular`
/// holds the body's yaw rate instead of the shell's angular velocity. (Bits 8 and 9 are the ROS layer's.)
constexpr std::uint32_t kNotRolling = 1u << 10;
/// hold_within_noise: this message's twist was within the noise, and the motion held since with it too (MotionHold):
/// the bristles were not moved, the forces are the held state's, nothing slides (sliding_fraction 0), and the walk
/// still widens the covariance.
constexpr std::uint32_t kMotionHeld = 1u << 11;
}  // namespace estimate_flags

/// How long the centre may move while the shell does not roll before kNotRolling is set [s]: a braking skid is shorter.
constexpr double kNotRollingTime = 1.0;

/// One estimate, everything in the ROS contact frame (REP 103: x along the rolling direction, y left,
/// z up; docs/conventions.md): lateral slips and forces, spins and yaw moments have the opposite sign of the
/// paper frame's.
struct ContactEstimateData
{
  double stamp = 0.0;
  double dt = 0.0;            ///< time advanced [s]
  double heading = 0.0;       ///< yaw of the contact frame in the ground frame [rad]
  double turn_rate = 0.0;     ///< psi_dot about z up [rad/s]
  double rolling_speed = 0.0; ///< V_r [m/s]
  Eigen::Vector2d sliding_velocity = Eigen::Vector2d::Zero();  ///< V_s [m/s]
  bool slips_defined = false;
  Eigen::Vector2d slip = Eigen::Vector2d::Zero();  ///< (sigma_x, sigma_y) [-]
  double spin = 0.0, spin_tilt = 0.0, spin_turn = 0.0;  ///< phi, phi_gamma, phi_psi [1/m]
  double tilt_ratio = 1.0;    ///< chi_gamma (1 when omega_z = 0)
  Eigen::Vector2d epsilon = Eigen::Vector2d::Zero();  ///< eq. 12b in the paper's contact frame: (0, 1) when defined
  double patch_radius = 0.0;  ///< a [m], of the current settings (also with the brush model off)
  double load = 0.0;          ///< F_z [N], of the current settings (also with the brush model off)

  BrushModelKind brush_model = BrushModelKind::Off;       ///< as configured
  BrushModelKind brush_model_used = BrushModelKind::Off;  ///< the model that ran (differs under auto)
  SlidingLaw sliding_law = SlidingLaw::Coulomb;           ///< as configured (the linear model has no sliding)
  int brush_resolution = 0;                         ///< the transient model's resolution (0: linear, steady, off)
  double brush_target = 0.0;  ///< the accuracy target the brush answer was computed to (BrushModel::lastTarget)
  BrushForces brush;          ///< F_x, F_y [N], M_z [N m] on the sphere, ROS contact frame
  double friction = 0.0;      ///< mu in force (0 with the brush model off)
  /// Power the ground's stresses take from the sphere's contact material, -(F_t . V_s + M_z omega_z) [W]:
  /// the material at x moves at V_s + omega_z e_z x x relative to the ground. In a steady state it is what
  /// sliding and the released bristles dissipate; in a transient, part of it is stored in the bristles.
  double brush_power = 0.0;
  double rolling_resistance_power = 0.0;   ///< F_R L V_r [W], dissipated by the viscous surface (eq. 17)

  CylinderModelKind rolling_resistance_model = CylinderModelKind::Off;
  CylinderState rolling_resistance;  ///< per unit length, as CylinderModel::solve returns it
  double rolling_resistance_force = 0.0;   ///< F_R L [N], against the rolling direction
  double rolling_resistance_torque = 0.0;  ///< R F_R L [N m]
  /// How uncertain the outputs are because the odometry is (its twist covariance carried through the models).
  EstimateCovariance covariance;
  /// The twist's distance from rest in units of its declared noise (motionToNoise; -1: no usable covariance, whether or
  /// not propagate_covariance carries it to the outputs). At most kMotionWithinNoise: flag kMotionWithinNoise.
  double motion_to_noise = -1.0;

  std::uint32_t flags = 0;    ///< estimate_flags
  double compute_time = 0.0;  ///< wall time of update() [s]
  /// The work this message took, counted (BrushForces::work units): the covariance's sigma points and the brush model;
  /// never much above EstimatorSettings::work_budget (the path under way when it ran out).
  long work = 0;

  bool valid() const;
  /// A model threw for this estimate (brush_flags::kModelFault or cylinder_flags::kModelFault): a defect.
  bool modelFault() const;
};

/// The estimator behind the node, the nodelet and the bag tools: odometry kinematics in, slips, brush
/// forces and rolling resistance out, with the state that links messages (time, heading, turn rate, the
/// transient bristles). ROS-free; the ROS layer converts messages and frames.
///
/// Per message: V_r = R_r (omega_y, -omega_x) in the ground frame (docs/conventions.md); the contact frame's x
/// follows V_r (held at standstill); psi_dot is the low-passed rate of that heading (or (1 - chi_gamma)
/// omega_z); vectors are rotated into the contact frame, converted to the paper frame (x, -y, -z), fed to
/// the models, and the results converted back. The twist's covariance goes the same way (EstimateCovariance): the
/// exact Jacobian of the kinematics to the slips, then the brush model's own propagation (force_covariance.h) and
/// the cylinder's (cylinder_spread.h); the brush forces' spread is passed to the brush model first, so that auto
/// spends no effort below the noise. A twist within the noise its covariance declares does not move the bristles
/// (hold_within_noise, MotionHold): summed, it is applied once the sum leaves the noise.
class ContactEstimator
{
public:
  /// Throws std::invalid_argument for invalid settings.
  explicit ContactEstimator(const EstimatorSettings& settings);

  /// New settings. Throws std::invalid_argument and keeps the old ones when they are invalid. Models are
  /// rebuilt only when their parameters change; the transient state survives unless its lattice changes.
  void configure(const EstimatorSettings& settings);
  const EstimatorSettings& settings() const { return settings_; }

  /// Processes one message. Returns nullptr, changing nothing, when the input is not finite or impossible
  /// (a speed or the sphere's surface faster than light, slips past the range of a double); otherwise the
  /// estimate, valid until the next call.
  const ContactEstimateData* update(const EstimatorInput& input);

  /// Forgets the history: time, heading, turn rate, transient bristles.
  void reset();

  /// The brush model (null when off).
  const BrushModel* brushModel() const { return brush_.get(); }

  /// A brush model of the caller's own in place of the configured one (a model under development, a test's), kept
  /// until a configure() that changes the brush settings. Null: none (as brush_model off).
  void useBrushModel(std::unique_ptr<BrushModel> model) { brush_ = std::move(model); }

  /// Models that threw since construction: each such estimate carries brush_flags::kModelFault or
  /// cylinder_flags::kModelFault, zero forces, and the model's state was reset. A defect, never an input's doing
  /// (inputs are refused or flagged before the models see them); what the last one said, or "".
  std::uint64_t faults() const { return faults_; }
  const std::string& lastFault() const { return last_fault_; }

  /// Shows the bristles behind the last estimate to visit(x, u, sliding), position x and deflection u in the ROS
  /// contact frame [m]: the transient model's lattice, or the steady model's field at the last slips (none for the
  /// linear model, which has no zones, or when the slips were undefined).
  using BristleVisitor = BrushModel::BristleVisitor;
  void visitBristles(const BristleVisitor& visit) const;

  /// Heading changes larger than this between two messages re-initialise the frame instead of counting
  /// as a turn rate [rad].
  static constexpr double kHeadingJump = 0.5;
  /// The covariance's share of the work budget at most; the brush model has the rest.
  static constexpr double kCovarianceShare = EstimatorSettings::kCovarianceShare;
  /// Stamps closer than a ROS stamp's resolution (1 ns) count as duplicates.
  static constexpr double kMinStep = 1e-9;

private:
  void adopt();
  // the phases of update(): refuse impossible input, advance the clock (dt and the time flags), follow the
  // contact frame's heading (turn rate), the kinematics in the paper frame (slips into the estimate), the models
  bool acceptable(const EstimatorInput& in, const Eigen::Vector2d& V_r, double speed) const;
  double advanceClock(double stamp, std::uint32_t& flags);
  void judgeMotion(const EstimatorInput& in, ContactEstimateData& o) const;
  void judgeRolling(const EstimatorInput& in, double speed, ContactEstimateData& o);
  void followHeading(const Eigen::Vector2d& V_r, double speed, double body_heading, double dt, bool first,
                     std::uint32_t& flags);
  ContactKinematics contactKinematics(const EstimatorInput& in, double psi_dot, ContactEstimateData& out,
                                      Slips& slips) const;
  ContactKinematics paperKinematics(const Eigen::Vector3d& omega, const Eigen::Vector3d& v_contact,
                                    double psi_dot) const;
  Eigen::Vector2d rollingVelocity(const Eigen::Vector3d& omega) const;  // V_r = R_r (omega_y, -omega_x), ROS axes
  double turnRate(double omega_z) const;  // psi_dot: (1 - chi_gamma) omega_z where fixed, else the heading's rate
  // hold_within_noise: whether this message's twist moves the bristles (MotionHold), flagged kMotionHeld where not
  MotionHold::Decision holdMotion(const EstimatorInput& in, const Eigen::Vector2d& V_r, ContactEstimateData& out);
  // the brush model advanced as the hold decided: by this message, not at all, or by the held sum with it
  void advanceBrush(const EstimatorInput& in, const ContactKinematics& kin, const Slips& slips,
                    MotionHold::Decision hold, ContactEstimateData& out);
  void clearBrush(ContactEstimateData& out) const;  // no brush answer: the configured model's, zero
  void runBrush(const ContactKinematics& kin, const Slips& slips, double dt, double omega_z, ContactEstimateData& out);
  void runRollingResistance(double speed, ContactEstimateData& out) const;
  void propagateBrushCovariance(const EstimatorInput& in, double speed, ContactEstimateData& out);
  bool reuseBrushCovariance(const Eigen::Matrix<double, 5, 5>& S, const ContactEstimateData& out) const;
  // at standstill: the covariance the bristles' state integrates (StandstillCovariance), this message's share after
  // the model advanced the state; publishWalk puts the walk so far into out
  void walkBrushCovariance(const EstimatorInput& in, ContactEstimateData& out);
  void publishWalk(ContactEstimateData& out) const;
  void propagateRollingResistanceCovariance(double speed, ContactEstimateData& out) const;
  bool slipsRepresentable(const EstimatorInput& in, const Eigen::Vector2d& V_r, double speed) const;
  void rebuildBrush(const EstimatorSettings& next);
  void rebuildCylinder(const EstimatorSettings& next);
  void fault(const char* model, const std::exception& error, const ContactEstimateData& o);

  EstimatorSettings settings_;
  double patch_radius_ = 0.0, load_ = 0.0;  // of settings_, set by adopt()
  std::unique_ptr<BrushModel> brush_;
  std::unique_ptr<CylinderModel> cylinder_;
  ContactEstimateData out_;
  bool have_last_ = false;
  double last_stamp_ = 0.0;
  bool have_heading_ = false;  // heading_ is the robot's: a rolling direction, or its body's yaw
  double not_rolling_time_ = 0.0;  // how long the centre has moved while the shell did not roll (judgeRolling)
  bool was_rolling_ = false;
  double heading_ = 0.0;
  double turn_rate_ = 0.0;
  std::uint64_t faults_ = 0;
  std::string last_fault_;
  // the brush covariance last propagated (covariance_period): what it was of, and when
  struct HeldCovariance
  {
    bool valid = false;
    double stamp = 0.0;
    Eigen::Matrix<double, 5, 5> twist = Eigen::Matrix<double, 5, 5>::Zero();  // the used twist covariance
    BrushParameters parameters;
    Eigen::Matrix3d brush = Eigen::Matrix3d::Zero();  // ROS contact frame
    CovarianceMethod method = CovarianceMethod::None;
    double spread = 0.0;
    bool smooth = true;
  } held_covariance_;
  // the brush covariance while the slips are undefined, from the last one while they were
  StandstillCovariance walk_;
  // the motion within the noise not yet applied to the bristles (hold_within_noise)
  MotionHold hold_;
};

}  // namespace sphere_contact_estimator
