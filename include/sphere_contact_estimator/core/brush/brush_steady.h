#pragma once

// STL
#include <functional>

// Package
#include "sphere_contact_estimator/core/brush/brush_model.h"
#include "sphere_contact_estimator/core/brush/coulomb_stepper.h"

namespace sphere_contact_estimator
{
struct BristleField;  // the solver's dimensionless problem (private: src/core/brush/bristle_path.h)

/// Steady-state bristle field with limited friction (Romano et al. Sects. 3, 4, 6), to a requested accuracy.
///
/// In the frame where epsilon = (0, 1) the characteristics (bristle paths) are the lines y = const (eq. 18a)
/// or, with tilt, circles about the tilting centre (0, 1/phi_gamma) (eq. 44a). Along each the bristle obeys
/// du/dsigma_s = sigma + A_phi x [+ A_phi_psi u with tilt] (eqs. 11, 32), starting undeformed at the leading
/// edge (eq. 8): without friction this is eq. 23 resp. eq. 51. With friction (eq. 4) it slides where |k u|
/// would exceed mu q_z, with |q| = mu q_z, its direction by the sliding law (BrushParameters::sliding_law): eq. (4b),
/// opposing the tip's full micro-sliding velocity (the direction turns towards the drive at a rate inversely
/// proportional to the bound; it re-adheres where its own sliding speed vanishes), or Sect. 6's rigid approximation,
/// along the rigid sliding field sigma + A_phi x (it re-adheres from its capped deflection where the bound grows along
/// the path faster than that field pushes it: the re-adhesion region G). Events are located exactly on every path
/// (solvePath); adhesion pieces are integrated exactly, sliding pieces by graded Gauss rules (rigid) or by stiff
/// collocation of the direction equation (eq. 4b, path/coulomb_collocation.h); across paths an adaptive Gauss-Kronrod
/// quadrature, split where the event structure changes, integrates until its error estimate meets the tolerance
/// (integratePatch).
///
/// The tolerance is BrushParameters::accuracy_target, a fraction of mu F_z bounding each of F_x, F_y and
/// M_z / a; every answer carries its estimate in BrushForces::error_estimate (flagged kAccuracyNotMet when
/// the path budget ran out first). `resolution` is not used.
///
/// |R_gamma| < a: no steady state on an inner disc (Fig. 2): flagged, zero forces; fall back to the
/// transient model. Standstill: flagged, zero forces.
class BrushSteady : public BrushSlipModel
{
public:
  explicit BrushSteady(const BrushParameters& parameters);
  BrushModelKind kind() const override { return BrushModelKind::Steady; }
  /// Builds the quadrature rules the solver builds on first use (about half a millisecond, once per process), so that
  /// no evaluation pays for them: ContactEstimator calls it at construction, before the first message.
  static void prepareRules();
  /// The field of the last update's slips on kVisitPaths x kVisitPoints points.
  void visitBristles(const BristleVisitor& visit) const override;
  /// The same for given slips (as update() takes them).
  void visitBristles(const Slips& slips, const BristleVisitor& visit) const;

  /// Forces to the parameters' accuracy target; phi_gamma and phi_psi are used with tilt on only.
  BrushForces evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const override;
  /// What one evaluation took.
  struct Stats
  {
    int paths = 0;  ///< characteristics solved
    long work = 0;  ///< their work (PathIntegrals::work)
  };
  /// The same to `tolerance` (a fraction of mu F_z), in (0, 1], within `max_work` (references for tests and
  /// benchmarks ask for more than kMaxWork), eq. (4b)'s sliding pieces stepped by `stepper` (CoulombStepper::General:
  /// an independent solution to check the default's against).
  BrushForces evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi, double tolerance,
                       Stats* stats = nullptr, long max_work = kMaxWork,
                       CoulombStepper stepper = CoulombStepper::Collocation) const;

  /// The same, and the field on a regular grid of paths and points along them to visit(x, u, sliding) [m]
  /// (for drawing the zones).
  using Visitor = std::function<void(const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool sliding)>;
  BrushForces evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                       const Visitor& visit) const;

  /// The dimensionless problem of these slips (BristleField): deflections in units of mu q_z(0) / k, lengths
  /// in units of a. False (and no field) when there is nothing to integrate: no friction or no load. For the package's
  /// own tests: the type is the solver's, not installed.
  bool field(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi, BristleField& out) const;

  /// Largest work (PathIntegrals::work) one evaluation may do; beyond, kAccuracyNotMet.
  static constexpr long kMaxWork = 4000000;
  /// A budget for converged references (tests, benchmarks): about 0.3 s at worst.
  static constexpr long kReferenceWork = 16 * kMaxWork;
  /// Paths and points per path shown to a visitor.
  static constexpr int kVisitPaths = 24;
  static constexpr int kVisitPoints = 24;

private:
  BrushForces solve(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi, double tolerance,
                    const Visitor* visit, Stats* stats = nullptr, long max_work = kMaxWork,
                    CoulombStepper stepper = CoulombStepper::Collocation) const;
};

}  // namespace sphere_contact_estimator
