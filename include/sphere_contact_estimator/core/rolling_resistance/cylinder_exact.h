#pragma once

// STL
#include <cstdint>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"

namespace sphere_contact_estimator
{
/// Exact steady state: eq. 18 solved for the front boundary xi_+ (h = xi_+^2 / 2R, eq. 13) with
/// the integrals in closed form (contactPatch) and Boost's TOMS 748 bracketed root finder.
///
/// Regimes, decided from the paper's physics:
/// - v = 0: eqs. 22, 25.
/// - contact patch: the residual G(xi_+) = F_N + F'_N - M g of eq. 18 increases monotonically in
///   xi_+ on xi_+ >= m v / gamma (where f(xi_+) <= 0), so its root there is unique.
/// - point contact, v >= v_c: at xi_+ = m v / gamma the patch has closed (xi_- = xi_+) and still
///   G >= 0, so the weight is carried by F'_N alone (note 13): M g = m v^2 xi_+ / R gives
///   xi_+ = M g R / (m v^2), h = xi_+^2 / 2R, and eq. 17 reduces to F_R = M g xi_+ / R, i.e.
///   mu_roll = xi_+ (the lever arm of F'_N). h, xi_+ and F_R are continuous at v_c. Flagged as
///   self-inconsistent: the paper says its uncoupled springs no longer describe this ("water
///   skiing"), but these are the values its own equations give, and they keep h continuous.
/// - no steady state: only when m k > gamma^2 (far outside eq. 2), G(m v / gamma) >= 0 can happen
///   below v_c; the state is reported at xi_+ = m v / gamma, which is continuous with both
///   neighbouring regimes, and flagged.
class CylinderExact : public CylinderModel
{
public:
  explicit CylinderExact(const CylinderParameters& parameters);

  CylinderState solve(double v) const override;
  CylinderModelKind kind() const override { return CylinderModelKind::Exact; }

  /// Speed derivatives of the steady state, from implicit differentiation of eq. 18.
  struct Slopes
  {
    double dh_dv = 0.0;         ///< [s]
    double dxi_minus_dv = 0.0;  ///< [s]
    double dmu_roll_dv = 0.0;   ///< [s]
  };
  /// Steady state at v and, when slopes is not null, its derivatives with respect to v.
  CylinderState solve(double v, Slopes* slopes) const;

  /// Residual of eq. 18 at front boundary xi_+ and speed v: F_N + F'_N - M g [N/m].
  double residual(double xi_plus, double v) const;

  /// Iteration limit of the root finder (TOMS 748); a root not found to tolerance within it is flagged
  /// kRootNotConverged, which invalidates the state. The default is never reached on the parameters' range
  /// (it needs about 10); tests lower it.
  void setMaxIterations(std::uintmax_t iterations) { max_iterations_ = iterations; }

  /// Relative tolerance of the root finder on xi_+ (the issue asks for about 1e-12).
  static constexpr int kToleranceBits = 48;  // 2^(1-48) = 7.1e-15
  static constexpr double kLargeDeformation = 0.5;  ///< xi_+ / R beyond which eq. 4 is poor

private:
  std::uintmax_t max_iterations_ = 200;
};

}  // namespace sphere_contact_estimator
