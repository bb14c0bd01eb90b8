#pragma once

// STL
#include <cmath>
#include <memory>

// Package
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"

namespace sphere_contact_estimator
{
// the solver's private rooms (src/core/brush/rolling_frame.h, steady_lag.h)
class RollingFrame;
class SteadyLag;

/// Per update, the cheapest brush model whose error estimate at the point in hand meets
/// BrushParameters::accuracy_target (a fraction of mu F_z), and that estimate in BrushForces::error_estimate.
///
/// - A steady state describes the contact when the slips are defined, |R_gamma| >= a with tilt, and either
///   the step rolled at held inputs further than the longest path through the patch (V_r dt >= that length:
///   every bristle then entered under these inputs, so the state is exactly the steady one, whatever came
///   before), or the lag of the steady state behind the true one (SteadyLag: the recent changes of the
///   linear forces, weighted by the share of the patch's memory each has left) is below half the target.
///   Otherwise the transient model runs. Noisy odometry makes large changes at each message, but a message
///   interval that rolls most of a patch length leaves little of them: the lag tells when the steady model
///   is close enough.
/// - In a steady state: the linear model if its error bound meets the budget left by the lag,
///   else the steady model to that budget, which carries its own bound (BrushSteady). The linear bound is
///   BrushLinear::errorBound.
/// - The transient model at its resolution reports its own estimate (BrushTransient); when that exceeds the
///   target the resolution doubles (up to kMaxTransientResolution): rolling, a lattice of twice the resolution
///   runs beside it and takes over after the longest path (when it holds nothing of its start); at standstill,
///   from the next entry into the transient model. It comes back down too: where its estimate stays below an eighth of
///   the target for the longest path (a lattice of half the resolution is then about four times as far off, second
///   order), every other bristle forms the coarser lattice (BrushTransient::coarsen: exact for the kept bristles).
///   reset() restores the configured resolution.
/// - The work budget (setWorkBudget, BrushForces::work): every evaluation gets what is left of it; a lattice whose
///   step would not fit is coarsened first (to kMinCoarsened), a finer one is started only where its warm start and
///   both steps fit, and the warm start on entering the transient model runs at the finest resolution whose cost fits.
///   In the transient model its lattice comes first: a lag check (which only decides when to leave) waits while it does
///   not fit beside the lattice's predicted step (check_work_).
///   What the budget could not buy shows as the estimate above the target, flagged kAccuracyNotMet.
///
/// The transient model is left only after the steady conditions have held over one transit (2a travelled),
/// when its state is the steady one, and entered from a steady state by rolling it to that state at the last
/// rolling inputs; for a transit after leaving, its lattice keeps rolling, and a return within it goes on from there.
/// At every switch the published forces carry the difference between the two models and let it decay over a quarter
/// transit, so they do not jump; the carried difference counts in the estimate.
class BrushAuto : public BrushModel
{
public:
  explicit BrushAuto(const BrushParameters& parameters);
  ~BrushAuto() override;

  using BrushModel::update;
  BrushForces update(const ContactKinematics& kinematics, const Slips& slips, double dt) override;
  void reset() override;
  /// Turns its transient state and the force history with the frame (entering the transient later from a
  /// steady state needs no turning: that state is built in the new frame).
  void rotateFrame(double alpha) override;
  /// Below the noise: with BrushParameters::auto_noise_fraction f > 0, the target of the next update is
  /// max(accuracy_target, f spread), spread the forces' standard deviation from uncertain inputs (a fraction of
  /// mu F_z). The flag kAccuracyNotMet then compares the estimate with that target.
  void setInputSpread(double spread) override { input_spread_ = std::isfinite(spread) && spread > 0.0 ? spread : 0.0; }
  /// The target the last update met: accuracy_target, or above it below the noise.
  double lastTarget() const override { return target_; }
  BrushModelKind kind() const override { return BrushModelKind::Auto; }

  /// The model that produced the last update, and its resolution (0 for linear and steady).
  BrushModelKind lastModel() const override { return last_model_; }
  int lastResolution() const override { return last_resolution_; }
  /// The transient lattice's bristles when it gave the answer, else the steady field of the last slips.
  void visitBristles(const BristleVisitor& visit) const override;
  /// The lattice's that the next update advances at standstill: the one under way, or an undeformed one after a reset;
  /// false where that update would warm-start it from the steady state (after steady answers, off probation).
  bool adhesionResponse(AdhesionResponse& response, long& work, double band) const override;
  /// Estimated cost of all updates so far [ns] (per-evaluation costs measured in docs/benchmarks.md).
  double cost() const { return cost_; }
  /// The resolution its transient model runs at now.
  int transientResolution() const { return transient_resolution_; }

  /// Estimated cost [ns] of one evaluation (docs/benchmarks.md, this machine kind).
  static constexpr double kLinearCost = 60.0;
  static constexpr double kSteadyPathCost = 250.0;
  static double transientStepCost(int resolution) { return 55.0 * resolution * resolution; }
  static constexpr int kMaxTransientResolution = 128;
  /// Below this much work left (BrushForces::work units), a switch from the steady model carries no difference.
  static constexpr long kMinSwitchWork = 2000;

private:
  // the phases of update(): is a steady state good enough (and its lag), which family answers (entering or
  // leaving the transient model), the transient answer (growing its lattice), continuity across switches
  struct SteadyCheck
  {
    bool steady = false;   // a steady state describes the contact to half the target
    bool renewed = false;  // this step rolled the longest path: the state is exactly the steady one
    double lag = 0.0;      // of the steady state behind the true one, a fraction of mu F_z
  };
  SteadyCheck checkSteady(const ContactKinematics& kin, const Slips& s, const Eigen::Vector2d& sigma,
                          const RollingFrame& frame, double dt, double target);
  SteadyCheck last_check_;   // the last evaluated check, and the travel since (in the transient model)
  bool have_check_ = false;
  double lag_travel_ = 0.0;
  // In the transient model the lattice's step answers and a check only decides when to leave it: a check waits, for a
  // transit at most, while its steady evaluation (the last one's work, or twice the room of one that ran out of it) and
  // the lattice's predicted step do not both fit what is left of the budget, and gets only what the step leaves.
  // Before, the check took up to half of what was left and a lattice whose step no longer fitted was coarsened for
  // good: at a 0.1 % target on data/manoeuvre.bag one 36 k-unit check at the pivot halved the lattice twice (32 to 8),
  // and at 16 (a finer one needs eight times its step) it stayed through the pivot, the skid and the spin in place:
  // their largest errors, and the park's after them, 4-9x those at the default 1 % target (docs/speed_and_accuracy.md).
  long check_work_ = 0;
  // Checks in a row that ran out of their room in the transient model. The next one waits for room for 2^n transits
  // at most (n up to kMaxChecksShort), not one. Along data/manoeuvre.bag's pivot no check fits beside the lattice's
  // step: retried every transit, a seventh of its messages spent the rest of the budget on one that gave no verdict
  // (the recording's p99 work 88 k units; 73 k with the wait growing, the answers the same bit for bit).
  int checks_short_ = 0;
  static constexpr int kMaxChecksShort = 3;
  // how far [patch radii] a check waits for room at most
  double roomWait() const { return kFarLagStride * static_cast<double>(1 << checks_short_); }
  // The lag that leaving the transient model allows, a share of the target: the steady family then has the rest
  static constexpr double kLeavingLag = 0.5;
  static constexpr double kLagStride = 0.25;  // of the patch radius: how far the transient rolls between lag checks
  // Where the last check's lag was kFarLag times what leaving allows, the next waits a transit (2a, after which no change
  // is remembered): a lag that large falls under the limit sooner only where new changes cancel it (the slowest kernel
  // keeps 0.41 of a change after a radius); checking late only delays leaving, which takes checks under the limit at
  // the usual stride over a whole transit, and the lag at leaving holds no change older than that transit. (A radius
  // was one check per message for a 1-cm patch at 1 m/s and 100 Hz, a fifth of the manoeuvre's weave.)
  static constexpr double kFarLag = 4.0;
  static constexpr double kFarLagStride = 2.0;
  void chooseFamily(const ContactKinematics& kin, const Slips& s, double dt, const SteadyCheck& check);
  BrushForces transientAnswer(const ContactKinematics& kin, const Slips& s, double dt, double target, int& resolution);
  void carryAcrossSwitches(BrushForces& out, const Slips& s, const Eigen::Vector2d& sigma, const RollingFrame& frame,
                           double dt, BrushModelKind before, int before_resolution, BrushModelKind model, int resolution);
  BrushForces steadyFamily(const Slips& s, const Eigen::Vector2d& sigma, double budget, BrushModelKind& model);
  // whether stepLag evaluates the steady model (else the linear forces): where one exists and the linear bound is above
  // a quarter of the target
  bool lagNeedsSteady(bool steady_exists, double target) const
  {
    return steady_exists && !(linear_bound_ <= 0.25 * target);
  }
  // the lag one step on; max_work: what its steady evaluation may take. False where that evaluation ran out of it.
  bool stepLag(const Slips& s, const Eigen::Vector2d& sigma, const RollingFrame& frame, double target,
               bool steady_exists, double travel, long max_work);
  void enterTransient(const ContactKinematics& kin, double dt);
  void rollOnProbation(const ContactKinematics& kin, const Slips& s, double dt);
  // A lattice's forces as they stand (its last step's answer, or a pass of the sums where its state changed since),
  // their work spent.
  BrushForces latticeForces(const BrushTransient& lattice);
  // One step of a lattice at its resolution within what is left of the budget: its work spent and its cost counted.
  BrushForces stepLattice(BrushTransient& lattice, int resolution, const ContactKinematics& kin, const Slips& s,
                          double dt);
  // The transient model's own lattice one step on (stepLattice), and the entry error decayed at its slowest renewal.
  BrushForces stepTransient(const ContactKinematics& kin, const Slips& s, double dt);
  double effectiveTarget() const;
  long remaining() const { return std::max(1L, work_budget_ - spent_); }

  BrushLinear linear_;
  BrushSteady steady_;
  std::unique_ptr<BrushTransient> transient_;
  std::unique_ptr<BrushTransient> finer_;  // twice the resolution, rolling beside transient_ until it takes over
  // A lattice auto no longer rolls (a finer one dropped, a coarse one taken over), kept so that the next finer lattice
  // reuses its storage: a refinement allocates only where it is finer than any before and than twice the configured
  // resolution, which both lattices hold from the start (test_hot_path_allocations)
  std::unique_ptr<BrushTransient> spare_;
  void retire(std::unique_ptr<BrushTransient>& lattice);  // into spare_ where its storage is the larger; null after
  std::unique_ptr<BrushTransient> latticeAt(int resolution);  // a new lattice (BrushTransient(...)), spare_'s storage
  void resizeTransient(int resolution);  // transient_->setParameters at it, with spare_'s storage where that is larger
  // the storage transient_ (resizeTransient) or, finer, a finer lattice (latticeAt) at `resolution` would grow
  long growthWork(int resolution, bool finer) const;
  double finer_travel_ = 0.0;
  int transient_resolution_ = 16;
  int configured_resolution_ = 16;  // what reset() restores
  int pending_resolution_ = 0;  // asked for by a missed target, applied at the next entry
  // The resolution the work budget coarsened the lattice from (0: none since the lattice last chose its own): up to it,
  // a missed target refines at what the finer lattice is predicted to cost (BrushTransient::predictFinerWork)
  int budget_cut_ = 0;
  double easy_travel_ = 0.0;    // rolled with the transient estimate below an eighth of the target
  long spent_ = 0;              // work of the update under way
  // the update under way: the work budget held the answer back (a coarser lattice than its target asks, a finer one
  // dropped or not started, a warm start short of its roll, a steady answer short of its tolerance): kBudgetLimited
  // where the target is then missed
  bool budget_held_ = false;
  bool in_transient_ = false;
  double steady_distance_ = 0.0;  // travelled while the steady conditions held, in transient mode
  // For a transit after leaving the transient model its lattice keeps rolling beside the steady family's answers, so
  // that a lag that comes back within it returns to the lattice as it is, not to a warm start (2.5 transits rolled in
  // one message): on the manoeuvre's weave at 100 Hz every one of the five visits to the steady family ended one message
  // later, and those re-entries were its five slowest messages, up to 2.5 times an ordinary one.
  bool probation_ = false;
  double probation_travel_ = 0.0;
  std::unique_ptr<SteadyLag> lag_;  // of the steady state behind the true one
  BrushForces steady_cache_;    // the steady model at this update's inputs, if stepLag evaluated it
  bool steady_cached_ = false;
  bool steady_short_ = false;   // the steady family's last steady answer ran out of the budget before its target
  double linear_bound_ = 0.0;   // BrushLinear::errorBound at this update's inputs
  Eigen::Vector2d last_lag_sigma_ = Eigen::Vector2d::Zero();  // the slips and spin of the last lag step
  double last_lag_phi_ = 0.0;
  double last_lag_ = 0.0;     // its last value, a fraction of mu F_z
  double entry_error_ = 0.0;  // the warm start's deviation from the true state, forgotten as bristles renew
  ContactKinematics last_rolling_;  // the last inputs with V_r above standstill
  bool have_rolling_ = false;
  BrushForces offset_;  // carried difference at the last switch
  // The last answer before its offset (the model's own), and the lattice's forces before this update's step: the two
  // models at the same state, for the switch's offset (warm_entered_: this update's warm start rolled the longest path
  // under the last update's inputs, no step cut, so it holds their steady state; or the lattice that rolled on beside
  // the last steady answers goes on)
  BrushForces last_raw_;
  BrushForces warm_forces_;
  bool warm_entered_ = false;
  bool rolled_before_ = false;  // the last update's slips were defined: last_rolling_ holds its inputs
  bool answered_ = false;  // an answer since the last reset: switches are then smoothed
  BrushModelKind last_model_ = BrushModelKind::Linear;
  Slips last_slips_;  // of the last update, for visitBristles
  int last_resolution_ = 0;
  double cost_ = 0.0;
  double input_spread_ = 0.0;  // setInputSpread
  double target_ = 0.0;        // of the last update
};

}  // namespace sphere_contact_estimator
