#pragma once

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"

namespace sphere_contact_estimator
{
/// The small-velocity expansions of the paper: xi_+ (eq. 21), xi_- (eq. 23), h (eq. 24) and
/// mu_roll (eq. 27), with torque mu_roll M g (eq. 26).
///
/// Error estimate: continuing the paper's perturbation solution of eq. 18 (derived with a computer
/// algebra system, checked by the convergence tests) gives zero v^3 term and
///   mu_roll = gamma/k v - 3 lambda/(4 xi0) v^2 + 3 (gamma^4 - 4 gamma^2 k m + 2 k^2 m^2)/(8 xi0^3 k^4) v^4 + O(v^5),
/// so |c4| v^4 estimates the error of eq. 27. The state is flagged out of range when that exceeds
/// kTolerance of mu_roll, or when the truncated series turns unphysical (h <= 0, xi_- >= xi_+,
/// v >= v_c); unphysical values are clamped (h, mu_roll >= 0; xi_- <= xi_+).
class CylinderExpansion : public CylinderModel
{
public:
  explicit CylinderExpansion(const CylinderParameters& parameters);

  CylinderState solve(double v) const override;
  CylinderModelKind kind() const override { return CylinderModelKind::Expansion; }

  /// Relative error of mu_roll, estimated by the next term, above which the state is flagged.
  static constexpr double kTolerance = 0.01;

  /// Coefficient c4 of v^4 in the expansion of mu_roll [s^4/m^3].
  double c4() const { return c4_; }

private:
  double c4_ = 0.0;
};

}  // namespace sphere_contact_estimator
