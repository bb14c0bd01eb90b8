#pragma once

// STL
#include <cstdint>

// Package
#include "sphere_contact_estimator/core/brush/brush_model.h"
#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_parameters.h"

namespace sphere_contact_estimator
{
/// Where the turning rate psi_dot of the contact frame comes from.
enum class TiltRatioSource : std::uint8_t
{
  Estimate = 0,  ///< from the heading of V_r over time; chi_gamma follows
  Fixed = 1,     ///< psi_dot = (1 - tilt_ratio) omega_z
};

/// Everything a scene sets; the node's parameters have the same names. SI units. These defaults are the
/// package's only definition of them: cfg/ContactEstimator.cfg and config/contact_estimator.yaml repeat them
/// (for dynamic_reconfigure and rosparam), and test_parameters fails when either disagrees. The scene: a
/// 20 cm, 5 kg spherical robot with a rubber shell on a firm, slightly viscous floor.
struct EstimatorSettings
{
  // sphere and load
  double rolling_radius = 0.1;  ///< R_r [m]
  double robot_mass = 5.0;      ///< [kg]; the load is robot_mass * gravity unless load > 0
  double load = 0.0;            ///< F_z [N]; 0: robot_mass * gravity
  double gravity = 9.81;        ///< [m/s^2]
  // brush
  BrushModelKind brush_model = BrushModelKind::Auto;  ///< the default: chosen on the demo bag (docs/speed_and_accuracy.md)
  double patch_radius = 0.01;      ///< a [m], unless contact_modulus > 0
  double contact_modulus = 0.0;    ///< E* [Pa]; > 0: a from Hertz with R = rolling_radius
  double bristle_stiffness = 2e8;  ///< k [N/m^3]
  double friction = 0.8;           ///< mu
  PressureDistribution pressure = PressureDistribution::Parabolic;
  SlidingLaw sliding_law = SlidingLaw::Coulomb;  ///< eq. (4b); rigid: Sect. 6's approximation (docs/models.md: Sliding law)
  bool tilt = false;               ///< Sect. 4 formulation (eq. 31, 32)
  TiltRatioSource tilt_ratio_source = TiltRatioSource::Estimate;
  double tilt_ratio = 1.0;         ///< chi_gamma for TiltRatioSource::Fixed
  int resolution = 32;             ///< transient: lattice spacings across 2a (auto starts there)
  double accuracy_target = 0.01;   ///< steady: its error bound; auto: largest error; relative to mu F_z
  double standstill_speed = 0.05;  ///< V_r below which slips are undefined [m/s] (above odometry noise)
  double turn_rate_time_constant = 0.05;  ///< low-pass of the psi_dot estimate [s]
  double max_step = 0.5;           ///< a longer gap between messages resets the transient state [s]
  /// A stamp earlier than the last by at most this (a source whose stamps jitter) is answered at the inputs it
  /// brings without advancing or resetting anything (flag kStampOutOfOrder); further back, the state resets [s]
  double stamp_tolerance = 0.005;
  /// The work one message may take, counted (BrushForces::work units, about 10 ns each on this machine kind), the
  /// covariance's sigma points and the brush model together: where the accuracy target cannot be met within it, the
  /// best answer reached, flagged kAccuracyNotMet with an estimate that bounds its error. Counted, not timed, so a
  /// replay gives the same answers on every machine. The default keeps a message within about 1 ms.
  long work_budget = kDefaultWorkBudget;
  static constexpr long kDefaultWorkBudget = 100000;
  static constexpr long kMinWorkBudget = 10000, kMaxWorkBudget = 1000000000;  // below, hardly a path fits
  /// The covariance's sigma points take at most this share of the budget (ContactEstimator); the brush model the rest.
  static constexpr double kCovarianceShare = 0.4;
  /// The least work_budget these settings take: kMinWorkBudget, and with the transient model at a fixed resolution
  /// (bound by the budget like every model) enough for its lattice's least update (BrushTransient::leastUpdateWork)
  /// beside the covariance's share.
  long leastWorkBudget() const;
  // rolling resistance (Poeschel et al.), the sphere taken as a cylinder of effective length L
  CylinderModelKind rolling_resistance_model = CylinderModelKind::Table;
  double surface_stiffness = 1e8;  ///< k [N/m^3]
  double surface_damping = 1e5;    ///< gamma [kg/(m^2 s)]
  double surface_density = 10.0;   ///< m [kg/m^2]
  double mass_per_length = 0.0;    ///< M [kg/m]; 0: load / (gravity L)
  double effective_length = 0.1;   ///< L [m]
  // uncertainty (issue 13)
  bool propagate_covariance = true;  ///< carry the odometry's twist covariance to the outputs
  double auto_noise_fraction = 0.25; ///< auto's target rises to this fraction of the forces' propagated standard
                                     ///< deviation where that is larger (0: never) [-]
  /// The brush covariance's sigma points are propagated again once this long has passed since the last time; a message
  /// sooner carries the last one (EstimateCovariance::brush_age says how old), as long as the twist covariance and the
  /// brush parameters are the same and nothing was reset. It is the forces' sensitivity to an input error held over a
  /// transit (docs/uncertainty.md), which a faster source does not resolve better. 0: at every message [s]
  double covariance_period = 0.005;
  /// While the twist is within the noise its covariance declares (7 sd, MotionHold::kHoldWithinNoise) and the patch moves
  /// nowhere faster than standstill_speed, the transient and auto models' bristles are not moved by it: the motion is
  /// summed and applied in one step once the sum leaves its own noise (MotionHold, a zero-velocity update). Off: every
  /// message's twist moves them, noise and all, which ratchets the deflection off its bounds (a parked robot's M_z
  /// after spinning in place fell to a tenth in 3 s).
  bool hold_within_noise = true;

  /// F_z [N].
  double verticalLoad() const { return load > 0.0 ? load : robot_mass * gravity; }
  /// The brush model's parameters (patch radius from Hertz when contact_modulus > 0).
  BrushParameters brushParameters() const;
  /// The cylinder model's parameters.
  CylinderParameters cylinderParameters() const;
  /// Throws std::invalid_argument naming the first bad value (parameter names as the node's).
  void validate() const;
};

}  // namespace sphere_contact_estimator
