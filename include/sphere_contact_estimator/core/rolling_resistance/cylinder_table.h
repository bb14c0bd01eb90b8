#pragma once

// STL
#include <cstddef>
#include <optional>
#include <vector>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/numerics/uniform_hermite.h"

namespace sphere_contact_estimator
{
/// The exact solution tabulated once, on construction, and interpolated by cubic Hermite polynomials
/// through the exact values and exact slopes (CylinderExact::Slopes), so the interpolation error falls
/// as n^-4. The nodes are evenly spaced in u = sqrt(v / v_max): mu_roll and h change on the scale of
/// v* near the origin, far below v_c, and the square root puts the nodes there (the solution, a
/// series in v, is smooth in u as well).
///
/// The table covers the contact-patch regime only: v_max never exceeds v_c, where the solution
/// has a kink. Past v_c the point-contact state is closed-form and evaluated directly. Between
/// v_max and v_c (a user-chosen v_max) the exact solver is used and the state flagged
/// kTableFallback. Surfaces with m k > gamma^2 get no table.
///
/// The construction measures the error: the exact solution at every cell midpoint against the
/// interpolant, where a cubic Hermite interpolant's error peaks.
class CylinderTable : public CylinderModel
{
public:
  static constexpr std::size_t kDefaultSize = 512;

  /// @param size number of tabulated speeds (>= 2)
  /// @param v_max upper end of the table [m/s]; 0 picks v_c, or, when v_c is infinite (m = 0),
  ///        kAutoRangeFactor k xi0 / gamma, the speed by which the rear boundary has moved by
  ///        that many static patch half-widths.
  explicit CylinderTable(const CylinderParameters& parameters, std::size_t size = kDefaultSize,
                         double v_max = 0.0);

  CylinderState solve(double v) const override;
  CylinderModelKind kind() const override { return CylinderModelKind::Table; }

  /// mu_roll(v) alone [m], the cheapest lookup.
  double muRoll(double v) const;

  /// Largest interpolation errors found at the cell midpoints, absolute.
  struct Error
  {
    double mu_roll = 0.0;   ///< [m]
    double h = 0.0;         ///< [m]
    double xi_minus = 0.0;  ///< [m]
  };
  const Error& measuredError() const { return error_; }
  /// Upper end of the tabulated range [m/s]; 0 when there is no table.
  double vMax() const { return v_max_; }
  std::size_t size() const { return size_; }

  static constexpr double kAutoRangeFactor = 100.0;

private:
  /// Table coordinate u = sqrt(v / v_max) of a speed in [0, v_max].
  double u(double v) const;

  CylinderExact exact_;
  double v_max_ = 0.0;
  std::size_t size_ = 0;
  double inv_v_max_ = 0.0;
  UniformHermite<3> table_;  // h, xi_minus, mu_roll as functions of u = sqrt(v / v_max)
  Error error_;
};

}  // namespace sphere_contact_estimator
