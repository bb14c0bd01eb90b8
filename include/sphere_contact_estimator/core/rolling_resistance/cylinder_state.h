#pragma once

// STL
#include <cstdint>
#include <string>
#include <vector>

namespace sphere_contact_estimator
{
/// Which physical situation a steady state describes.
enum class CylinderRegime : std::uint8_t
{
  Static = 0,         ///< v = 0: symmetric contact, eqs. 22, 25
  ContactPatch = 1,   ///< 0 < v < v_c: contact on [xi_-, xi_+], eq. 18
  PointContact = 2,   ///< v >= v_c: the weight is carried by F'_N at xi_+ alone (eq. 8, note 13)
  NoSteadyState = 3,  ///< surface so underdamped (m k > gamma^2) that eq. 18 has no consistent root
};

const char* toString(CylinderRegime regime);

/// Bit flags qualifying a steady state. Those in kInvalidatingFlags make it invalid.
namespace cylinder_flags
{
constexpr std::uint32_t kUnderdamped = 1u << 0;        ///< eq. 2 fails: surface waves, multiple contacts
constexpr std::uint32_t kSelfInconsistent = 1u << 1;   ///< h <= m^2 v^2 / (2 gamma^2 R) (after eq. 15)
constexpr std::uint32_t kNoSteadyState = 1u << 2;      ///< no root of eq. 18 with f(xi_+) <= 0
constexpr std::uint32_t kExpansionOutOfRange = 1u << 3;///< small-v expansion's next term exceeds tolerance
constexpr std::uint32_t kLargeDeformation = 1u << 4;   ///< xi_+ not small against R: eq. 4 is poor
constexpr std::uint32_t kTableFallback = 1u << 5;      ///< speed outside the table: exact solver used
constexpr std::uint32_t kRootNotConverged = 1u << 6;   ///< eq. 18's root not found to tolerance in the iterations
constexpr std::uint32_t kModelFault = 1u << 7;         ///< the model failed (threw: a defect): no state (zero)
constexpr std::uint32_t kInvalidatingFlags = kUnderdamped | kSelfInconsistent | kNoSteadyState | kExpansionOutOfRange |
                                             kLargeDeformation | kRootNotConverged | kModelFault;

/// One human-readable sentence per set flag, in bit order.
std::vector<std::string> describe(std::uint32_t flags);
}  // namespace cylinder_flags

/// Steady rolling state of the cylinder at one speed. Forces and torque are per unit length of the
/// cylinder, as in the paper; multiply by L for a scene (CylinderParameters::L).
struct CylinderState
{
  double v = 0.0;           ///< rolling speed [m/s]
  double h = 0.0;           ///< penetration depth [m]
  double xi_plus = 0.0;     ///< front boundary, comoving, eq. 13 [m]
  double xi_minus = 0.0;    ///< rear boundary, comoving, eq. 15 (= xi_plus in point contact) [m]
  double F_N = 0.0;         ///< distributed support -integral f dxi, eq. 7 [N/m]
  double F_N_impact = 0.0;  ///< impact support F'_N = m v^2 xi_+ / R, eq. 8 [N/m]
  double F_R = 0.0;         ///< resisting force, eq. 17 [N/m]
  double F_R_impact = 0.0;  ///< part of F_R from the impact at xi_+: m v^2 2h/R (eq. 17) [N/m]
  double torque = 0.0;      ///< resisting torque R F_R (before eq. 26) [N m/m]
  double mu_roll = 0.0;     ///< rolling-friction coefficient torque / (M g), eq. 26 [m]
  /// Error estimate of mu_roll [m]: 0 for the exact solver (converged to round-off), the measured
  /// maximum interpolation error for the table, the first neglected term for the expansion.
  double mu_roll_error = 0.0;
  CylinderRegime regime = CylinderRegime::Static;
  std::uint32_t flags = 0;  ///< cylinder_flags bits

  bool valid() const { return (flags & cylinder_flags::kInvalidatingFlags) == 0; }
};

}  // namespace sphere_contact_estimator
