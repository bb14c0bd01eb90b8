#pragma once

// Package
#include "sphere_contact_estimator/core/brush/brush_model.h"

namespace sphere_contact_estimator
{
/// Linear brush theory: steady state, vanishing sliding, small slips (Romano et al. eqs. 61-62),
/// in the frame where epsilon = (0, 1) and rotated back, so any rolling direction works:
///   F_t = C_sigma sigma + C_phi phi e_y,            C_sigma = 8/3 k a^3, C_phi = 3 pi a / 32 C_sigma
///   M_z = -C_Msigma_y sigma_y + C_Mphi phi,         C_Msigma_y = C_phi,  C_Mphi = 8/15 k a^5
/// The spin term of M_z is missing from eq. 61b. Integrating the steady field of eq. 23,
/// u = sigma Sigma + phi Sigma (-y, (x_L + x)/2) with Sigma = x_L - x, the spin part of
/// x q_y - y q_x is k phi [x (x_L^2 - x^2)/2 + y^2 (x_L - x)]; the first term is odd in x, the second
/// integrates to 8 a^5 / 15. The steady model recovers this coefficient (test_brush_linear).
/// Tilt and the turn coupling are second order in the slips and not part of the linear theory.
/// Past mu F_z the force is scaled back onto the friction circle and flagged.
class BrushLinear : public BrushSlipModel
{
public:
  explicit BrushLinear(const BrushParameters& parameters);
  BrushModelKind kind() const override { return BrushModelKind::Linear; }

  /// Forces from slips in the epsilon = (0, 1) frame; the split of phi into tilt and turn is a
  /// second-order effect the linear theory leaves out. error_estimate: errorBound.
  BrushForces evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const override;
  BrushForces evaluate(const Eigen::Vector2d& sigma, double phi) const;

  /// Bound on this model's error against the steady model with limited friction at these slips, as a fraction of
  /// mu F_z: 0.5 s^2 + 0.6 (|phi_gamma| + |phi_psi|) a s with tilt, s = (C_sigma |sigma| + 2 C_phi |phi|) / (mu F_z).
  /// Without tilt, the trailing-edge sliding band of the parabolic pressure costs 0.35 s^2 for a pure slip
  /// (derived: the band is x_L + x < |sigma| / c, c = 2 mu F_z / (pi a^4 k)); the Hertzian and uniform pressures
  /// cost less. With tilt the curved paths and the turn coupling, which the linear theory leaves out, change the
  /// forces in proportion to the turn across the patch. Both constants hold with a margin over random operating
  /// points, all three pressures (test_brush_auto, bench/brush_accuracy).
  static double errorBound(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi, double phi_gamma,
                           double phi_psi);

  /// eq. 62 for any parameters: C_sigma = 8/3 k a^3 [N], C_phi = 3 pi a / 32 C_sigma [N m].
  /// The work of one evaluation (BrushForces::work): a few products.
  static constexpr long kWork = 4;
  static double slipStiffness(const BrushParameters& p);
  static double spinStiffness(const BrushParameters& p);

  double C_sigma() const { return C_sigma_; }      ///< [N]
  double C_phi() const { return C_phi_; }          ///< [N m]
  double C_Msigma_y() const { return C_phi_; }     ///< [N m]
  double C_Mphi() const { return C_Mphi_; }        ///< [N m^2]

private:
  double C_sigma_, C_phi_, C_Mphi_;
};

}  // namespace sphere_contact_estimator
