#pragma once

// Parameters of the hard cylinder on a viscous plane (Poeschel, Schwager, Brilliantov, Sect. II).
// The plane is a bed of independent damped springs; k, gamma and m are per unit area, so that
// k dx, gamma dx and m dx act per unit length along the cylinder axis.

namespace sphere_contact_estimator
{
/// Physical parameters of the cylinder model, SI units throughout.
struct CylinderParameters
{
  double R = 0.1;        ///< cylinder radius R [m]
  double M = 250.0;      ///< cylinder mass per unit length M [kg/m]
  double k = 1.0e7;      ///< surface stiffness k [N/m^3]
  double gamma = 5.0e5;  ///< surface damping gamma [kg/(m^2 s)]
  double m = 100.0;      ///< surface mass density m [kg/m^2]
  double g = 9.81;       ///< gravitational acceleration [m/s^2]
  double L = 1.0;        ///< effective length turning per-unit-length results into totals [m]

  /// Throws std::invalid_argument naming the first non-physical value: R, M, k, g, L must be
  /// finite and > 0; gamma and m finite and >= 0. Values must also lie in the supported range
  /// (kRange), which spans many orders of magnitude beyond any real wheel and surface and keeps every
  /// intermediate of the solution representable in double precision.
  void validate() const;

  /// Supported magnitude of each parameter: {smallest non-zero, largest}.
  struct Range
  {
    double lo, hi;
  };
  static constexpr Range kRangeR{ 1e-9, 1e6 };
  static constexpr Range kRangeM{ 1e-12, 1e12 };
  static constexpr Range kRangeK{ 1e-6, 1e20 };
  static constexpr Range kRangeGamma{ 1e-12, 1e18 };  // or exactly 0
  static constexpr Range kRangeSurfaceDensity{ 1e-12, 1e12 };  // or exactly 0
  static constexpr Range kRangeG{ 1e-6, 1e6 };
  static constexpr Range kRangeL{ 1e-9, 1e9 };

  /// Weight per unit length M g [N/m], the load that eq. 9 balances.
  double weight() const { return M * g; }
};

bool operator==(const CylinderParameters& a, const CylinderParameters& b);
inline bool operator!=(const CylinderParameters& a, const CylinderParameters& b) { return !(a == b); }

}  // namespace sphere_contact_estimator
