#pragma once

// STL
#include <memory>
#include <vector>

// Package
#include "sphere_contact_estimator/core/brush_linear.h"
#include "sphere_contact_estimator/core/brush_steady.h"
#include "sphere_contact_estimator/core/brush_transient.h"

namespace sphere_contact_estimator
{
/// Per update, the cheapest brush model whose error estimate meets BrushParameters::accuracy_target
/// (relative to mu F_z). The estimates, each defensible on its own:
///
/// - linear: exact in steady state while no bristle reaches the bound. With the parabolic pressure the
///   trailing edge always slides; for a pure slip its band costs 0.35 (F_sigma / mu F_z)^2 (derived: the band
///   is x_L + x < |sigma| / c, c = 2 mu F_z / (pi a^4 k)), and spin raises the utilisation of the whole patch
///   by C_phi |phi| / mu F_z. The bound used, 0.5 ((C_sigma |sigma| + 2 C_phi |phi|) / mu F_z)^2, holds with a
///   margin (at most 0.69 of it) against the steady model at resolution 64 over random slips and spins
///   (test_brush_auto).
/// - steady at resolution n: 0.009 (8 / n), a first-order bound on the measured errors (docs/benchmarks.md).
/// - steady instead of transient: the bristle state remembers about one patch transit, so using the steady
///   state lags the true one by about its change over a/V_r: |dF/dt| a / V_r, with dF the change of the
///   linear force between updates.
/// - transient at resolution n: 0.055 (8 / n)^1.5, a bound on the measured errors.
///
/// Standstill, |R_gamma| < a with tilt, and unsteady inputs take the transient model. It is left only after
/// the steady conditions have held over one transit (2a travelled), when its state is the steady one; it is
/// entered from a steady state by rolling it to that state at the last rolling inputs. At every switch the
/// published forces carry the difference between the two models and let it decay over a quarter transit,
/// so they do not jump.
class BrushAuto : public BrushModel
{
public:
  explicit BrushAuto(const BrushParameters& parameters);

  BrushForces update(const ContactKinematics& kinematics, double dt) override;
  void reset() override;
  /// Turns its transient state and the force history with the frame (entering the transient later from a
  /// steady state needs no turning: that state is built in the new frame).
  void rotateFrame(double alpha) override;
  BrushModelKind kind() const override { return BrushModelKind::Auto; }

  /// The model that produced the last update, and its resolution (0 for linear).
  BrushModelKind lastModel() const { return last_model_; }
  int lastResolution() const { return last_resolution_; }
  /// Estimated cost of all updates so far [ns], from the per-evaluation costs of docs/benchmarks.md.
  double cost() const { return cost_; }
  /// The resolution of its transient model: the smallest that meets the target.
  int transientResolution() const { return transient_resolution_; }

  /// Error bounds, relative to mu F_z.
  static double linearError(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi);
  static double steadyError(int resolution) { return 0.009 * 8.0 / resolution; }
  static double transientError(int resolution);
  /// Estimated cost of one evaluation [ns] (docs/benchmarks.md, this machine kind).
  static double steadyCost(int resolution) { return 110.0 * resolution * resolution; }
  static double transientStepCost(int resolution) { return 55.0 * resolution * resolution; }
  static constexpr double kLinearCost = 60.0;

  /// The resolutions the auto model chooses from.
  static const std::vector<int>& ladder();

private:
  BrushForces runSteadyFamily(const Slips& s, const Eigen::Vector2d& sigma, double error_budget, BrushModelKind& model,
                              int& resolution);
  void enterTransient();

  BrushLinear linear_;
  std::vector<std::unique_ptr<BrushSteady>> steady_;  // one per ladder resolution
  std::unique_ptr<BrushTransient> transient_;
  int transient_resolution_ = 16;
  bool in_transient_ = false;
  double steady_distance_ = 0.0;  // travelled while the steady conditions held, in transient mode
  Eigen::Vector2d previous_force_ = Eigen::Vector2d::Zero();  // linear force of the previous update
  bool have_previous_ = false;
  ContactKinematics last_rolling_;  // the last inputs with V_r above standstill
  bool have_rolling_ = false;
  BrushForces offset_;  // carried difference at the last switch
  BrushModelKind last_model_ = BrushModelKind::Linear;
  int last_resolution_ = 0;
  double cost_ = 0.0;
};

}  // namespace sphere_contact_estimator
