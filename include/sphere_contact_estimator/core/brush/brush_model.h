#pragma once

// STL
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_forces.h"
#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "sphere_contact_estimator/core/brush/contact_kinematics.h"

namespace sphere_contact_estimator
{
/// How the bristles hold the noise of a robot that stands (BrushModel::adhesionResponse), paper frame.
struct AdhesionResponse
{
  /// d(F_x, F_y, M_z)/dt per unit of (V_s,x, V_s,y, omega_z), summed over the bristles with the weights of the force
  /// sums: an adhering one moves with the drive, one held by its bound (sliding, or within the band of it) only along
  /// the bound
  Eigen::Matrix3d drive = Eigen::Matrix3d::Zero();
  static constexpr int kDirections = 32;
  /// The unit vectors at angles 2 pi j / kDirections (computed once).
  static const std::array<Eigen::Vector2d, kDirections>& directions();
  /// d(F_x, F_y, M_z) per metre the roots move along the direction at angle 2 pi j / kDirections (eq. 31: they move at
  /// -V_r): the deflection field moves with them, so the adhering bristles' moment about the patch centre changes by
  /// (displacement) x F_adhering, and what they carry out of the patch at its rim is lost (nothing comes back: it
  /// re-enters undeformed, so the change is one-sided, not linear in the displacement) [N/m, N]
  Eigen::Matrix<double, 3, kDirections> roll = Eigen::Matrix<double, 3, kDirections>::Zero();
};

/// The brush models, and none; the numbers are those of the node's brush_model parameter.
enum class BrushModelKind : std::uint8_t
{
  Off = 0,        ///< no brush model
  Linear = 1,     ///< eqs. 61-62: steady state, vanishing sliding (BrushLinear)
  Steady = 2,     ///< steady bristle field along the paths, limited friction (BrushSteady)
  Transient = 3,  ///< the brush PDE in the time domain (BrushTransient)
  Auto = 4,       ///< per update the cheapest of the above that meets accuracy_target (BrushAuto)
};

const char* toString(BrushModelKind kind);
/// Parses "linear", "steady", "transient" or "auto" (a model to run: not "off").
std::optional<BrushModelKind> parseBrushModelKind(std::string_view name);

/// One interface for the brush models: forces from the contact kinematics over a step, and what the estimator
/// needs besides (retuning, the model last used, the bristles to draw), so that it needs no concrete type.
class BrushModel
{
public:
  /// Validates the parameters (std::invalid_argument).
  explicit BrushModel(const BrushParameters& parameters);
  virtual ~BrushModel() = default;

  /// Forces after advancing by dt [s] with the kinematics held constant over the step. The steady
  /// models ignore dt; the transient model integrates over it. Throws std::invalid_argument for
  /// non-finite kinematics or a negative or non-finite dt.
  BrushForces update(const ContactKinematics& kinematics, double dt)
  {
    return update(kinematics, computeSlips(kinematics, p_.standstill_speed), dt);
  }
  /// The same with the slips of these kinematics at hand: computeSlips(kinematics, parameters().standstill_speed), which
  /// a caller that has them passes on (the estimator to its model, auto to its lattices: once per message). Slips of
  /// other kinematics or another standstill speed (their rolling speed or whether they are defined differ) throw
  /// std::invalid_argument too.
  virtual BrushForces update(const ContactKinematics& kinematics, const Slips& slips, double dt) = 0;
  /// Forgets all history (transient state); a no-op for the steady models.
  virtual void reset() {}
  /// The patch frame turned by alpha [rad] about its z axis (paper frame, z down), for heading changes the
  /// turn coupling does not carry (the rolling direction re-initialised after standstill or a reversal):
  /// state that lives in the frame is re-expressed in the new axes. Stateless models have nothing to turn.
  virtual void rotateFrame(double /*alpha*/) {}
  /// How uncertain the next update's inputs make the forces: the largest standard deviation of F_x, F_y and M_z / a
  /// as a fraction of mu F_z (EstimateCovariance::brush_spread; 0 when unknown). Only auto uses it, to spend no effort
  /// below the noise (BrushParameters::auto_noise_fraction).
  virtual void setInputSpread(double /*spread*/) {}
  /// The work the next update may do (BrushForces::work units; kUnlimitedBudget: none). The steady model stops its
  /// refinement there with the best answer reached, flagged kAccuracyNotMet and its estimate still a bound; auto also
  /// picks the transient lattice whose work fits (brush_auto.h). The transient model at a fixed resolution cuts its
  /// sliding steps or substeps short where they do not fit, flagged kSubstepsTruncated, its estimate covering what that
  /// left; its least update (BrushTransient::leastUpdateWork) it always takes.
  void setWorkBudget(long budget) { work_budget_ = budget > 0 ? budget : 1; }
  long workBudget() const { return work_budget_; }
  static constexpr long kUnlimitedBudget = 1L << 62;
  /// How far an update's work may pass its budget: the steady path or transient substep under way when it ran out.
  static constexpr long kWorkGranularity = 4000;
  virtual BrushModelKind kind() const = 0;

  /// New parameters in place, keeping the state where it still means something. False when this model
  /// cannot (the default): the caller makes a new one. Throws std::invalid_argument, changing nothing, for
  /// invalid parameters.
  virtual bool retune(const BrushParameters& /*parameters*/) { return false; }
  /// The model that gave the last answer (auto: the one it chose), and the transient lattice's resolution
  /// it used (0 when none ran).
  virtual BrushModelKind lastModel() const { return kind(); }
  virtual int lastResolution() const { return 0; }
  /// The accuracy target the last answer was computed to: accuracy_target, or for auto below the noise the larger
  /// target the forces' spread allowed (a fraction of mu F_z).
  virtual double lastTarget() const { return p_.accuracy_target; }
  /// Visits the bristles behind the last answer, for drawing: visit(position x [m], deflection u [m], sliding),
  /// paper frame. Models without a bristle field (linear), and every model at standstill without state, visit none.
  using BristleVisitor = std::function<void(const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool sliding)>;
  virtual void visitBristles(const BristleVisitor& /*visit*/) const {}
  /// How the bristle state integrates the drive while the patch does not roll (eq. 1 at V_r = 0: an adhering bristle's
  /// u' = w = -V_s - A_omega_z x, a sliding one moves along its bound by w's part across its normal, eq. 4b), and what a
  /// small roll of the roots (V_r from the noise) does to it (AdhesionResponse); `work` what that pass costs
  /// (BrushForces::work units). An input error of one message stays in the state, so at standstill the forces'
  /// covariance integrates the inputs' (StandstillCovariance). `band` [m]: an adhering bristle closer than this to its
  /// bound counts as held by it, moving only along it as a sliding one (the noise's reflected walk,
  /// StandstillCovariance::band); 0: only the sliding ones.
  /// False where there is no such state (linear, steady: zero forces at standstill).
  virtual bool adhesionResponse(AdhesionResponse& /*response*/, long& /*work*/, double /*band*/) const { return false; }

  const BrushParameters& parameters() const { return p_; }

protected:
  // finite kinematics, their slips (update's), and dt finite and >= 0; else std::invalid_argument
  void checkInput(const ContactKinematics& kinematics, const Slips& slips, double dt) const;

  BrushParameters p_;
  long work_budget_ = kUnlimitedBudget;
};

/// The steady models, which work on slips (eq. 12) in the frame where epsilon = (0, 1): update()
/// computes the slips, rotates into that frame, evaluates and rotates the forces back. Below the
/// standstill speed the slips are undefined: zero forces, flagged kStandstill.
class BrushSlipModel : public BrushModel
{
public:
  using BrushModel::BrushModel;
  using BrushModel::update;
  BrushForces update(const ContactKinematics& kinematics, const Slips& slips, double dt) override;

  /// Forces from slips in the epsilon = (0, 1) frame: sigma, spin phi, and its tilt and turn parts
  /// phi_gamma + phi_psi = phi (eq. 13).
  virtual BrushForces evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const = 0;

protected:
  Slips last_;  ///< the slips of the last update (defined false at standstill)
};

/// The model of that kind (nullptr for Off). Throws std::invalid_argument for invalid parameters.
std::unique_ptr<BrushModel> makeBrushModel(BrushModelKind kind, const BrushParameters& parameters);

}  // namespace sphere_contact_estimator
