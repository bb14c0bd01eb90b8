#pragma once

// STL
#include <functional>

// Package
#include "sphere_contact_estimator/core/brush/brush_model.h"

namespace sphere_contact_estimator::test
{
/// The package's first steady solver, kept for comparison only (bench/ and the tests): it marches cells along
/// each path and caps the deflection per cell, a first-order treatment of the events. BrushSteady replaced it.
///
/// Steady-state bristle field on a discretised patch, with limited friction (Romano et al. Sects. 3, 4, 6).
///
/// In the frame where epsilon = (0, 1) the characteristics (bristle paths) are the lines y = const
/// (eq. 18a) or, with tilt, circles about the tilting centre (0, 1/phi_gamma) (eq. 44a). Along each the
/// bristle obeys du/dsigma_s = sigma + A_phi x [+ A_phi_psi u with tilt] (eqs. 11, 32), starting
/// undeformed at the leading edge (eq. 8): without friction this is eq. 23 resp. eq. 51. With friction
/// the deflection is capped as it goes: where adhesion would need |k u| > mu q_z the bristle slides with
/// |q| = mu q_z, and where the bound later exceeds what adhesion needs it re-adheres from its capped deflection
/// (docs/conventions.md). The direction follows p.sliding_law: Rigid, along the rigid sliding field
/// sigma + A_phi x (Sect. 6); Coulomb (eq. 4b), the FASTSIM-like return mapping: the propagated (trial) deflection
/// scaled back onto the bound along itself, the backward-Euler step of the Coulomb law (first order).
///
/// Discretisation: `resolution` paths at y = a sin(theta) (or rho = |R_gamma| + a sin(theta)) with
/// theta at the midpoints of equal intervals, so the path lengths' square-root end behaviour is
/// smoothed out; kStepsPerPath x `resolution` equal steps along each path (where a bristle reaches and
/// leaves the bound matters more than the spacing across paths: at the same cost, 4 steps per path
/// spacing cut the error of slip with spin fivefold, docs/benchmarks.md), integrated by the exact rotation of the turn
/// coupling and the midpoint rule for the drive; forces by the midpoint rule along paths, with the
/// weights normalised so that the discrete integral of q_z is F_z (then |F_t| <= mu F_z exactly).
///
/// |R_gamma| < a: no steady state on an inner disc (Fig. 2): flagged, zero forces; fall back to the
/// transient model. Standstill: flagged, zero forces.
class BrushMarching : public BrushSlipModel
{
public:
  explicit BrushMarching(const BrushParameters& parameters);
  BrushModelKind kind() const override { return BrushModelKind::Steady; }

  /// phi_gamma and phi_psi are used with tilt on only.
  BrushForces evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const override;

  /// The same, showing every node of the discretised field to visit(x, u, sliding) (for drawing the zones).
  using Visitor = std::function<void(const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool sliding)>;
  BrushForces evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                       const Visitor& visit) const;

private:
  BrushForces integrate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                        const Visitor* visit) const;

  /// Tilt spin below which the paths count as straight: |R_gamma| > 1e9 a.
  static constexpr double kStraightPathTolerance = 1e-9;
  /// Steps along each path per path across the patch.
  static constexpr int kStepsPerPath = 4;
};

}  // namespace sphere_contact_estimator::test
