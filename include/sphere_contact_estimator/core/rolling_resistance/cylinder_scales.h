#pragma once

// STL
#include <optional>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_parameters.h"

namespace sphere_contact_estimator
{
/// Characteristic quantities of a cylinder scene that do not depend on the speed.
struct CylinderScales
{
  double xi0 = 0.0;         ///< static front boundary xi_+^(0) = (3 R M g / (2 k))^(1/3), eq. 22 [m]
  double h0 = 0.0;          ///< static penetration depth h_0 = xi0^2 / (2R), eq. 25 [m]
  double lambda = 0.0;      ///< lambda = gamma^2/k^2 - 2 m/k, after eq. 20 [s^2]
  /// Speed at which the rear boundary reaches the front one and the contact shrinks to a line
  /// (note 13). There xi_- = xi_+ = m v / gamma and M g = F'_N = m v^2 xi_+ / R (eqs. 8, 9), so
  /// v_c = (M g gamma R / m^2)^(1/3); +inf when m = 0 (no impact force, the patch never closes).
  double v_critical = 0.0;  ///< [m/s]
  bool overdamped = false;  ///< eq. 2: m/k < gamma^2 / (4 k^2); false means surface waves are possible
  /// Maximum of the second-order expansion eq. 27: mu*_roll (eq. 28) [m] at v* (eq. 29) [m/s].
  /// Defined only for lambda > 0; for lambda <= 0 eq. 27 has no maximum.
  std::optional<double> v_star;
  std::optional<double> mu_star;

  /// Computes the scales of validated parameters.
  static CylinderScales of(const CylinderParameters& p);
};

}  // namespace sphere_contact_estimator
