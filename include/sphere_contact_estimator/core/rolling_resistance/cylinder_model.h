#pragma once

// STL
#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_parameters.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_scales.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_state.h"

namespace sphere_contact_estimator
{
/// The three ways to evaluate the steady rolling state of the cylinder.
/// The rolling-resistance models, and none; the numbers are those of the node's rolling_resistance_model.
enum class CylinderModelKind : std::uint8_t
{
  Off = 0,        ///< no rolling-resistance model
  Exact = 1,      ///< eq. 18 solved by a bracketed root finder (CylinderExact)
  Expansion = 2,  ///< small-velocity expansions, eqs. 21, 23, 24, 27 (CylinderExpansion)
  Table = 3,      ///< exact solution tabulated on construction and interpolated (CylinderTable)
};

const char* toString(CylinderModelKind kind);
/// Parses "exact", "expansion" or "table".
std::optional<CylinderModelKind> parseCylinderModelKind(std::string_view name);

/// Common interface: the steady state at a rolling speed.
class CylinderModel
{
public:
  /// Validates the parameters (std::invalid_argument on non-physical values).
  explicit CylinderModel(const CylinderParameters& parameters);
  virtual ~CylinderModel() = default;
  CylinderModel(const CylinderModel&) = default;
  CylinderModel& operator=(const CylinderModel&) = default;

  /// Steady state at rolling speed v [m/s]. Throws std::invalid_argument unless 0 <= v <= kMaxSpeed
  /// (a speed is a norm; the resistance always opposes the motion).
  virtual CylinderState solve(double v) const = 0;

  /// The speed of light [m/s]: any faster rolling speed is non-physical input.
  static constexpr double kMaxSpeed = 299792458.0;
  virtual CylinderModelKind kind() const = 0;

  const CylinderParameters& parameters() const { return p_; }
  const CylinderScales& scales() const { return scales_; }

protected:
  /// Throws std::invalid_argument for a speed that is negative or not finite.
  static void checkSpeed(double v);
  /// Static state (v = 0), eqs. 22 and 25: symmetric patch, no resistance.
  CylinderState staticState() const;
  /// Fills the derived fields of a state whose v, h, xi_plus, xi_minus, F_N, F_R and regime are set.
  void finish(CylinderState& s) const;

  CylinderParameters p_;
  CylinderScales scales_;
};

/// Creates a model of the given kind.
/// The model of that kind (nullptr for Off). Throws std::invalid_argument for invalid parameters.
std::unique_ptr<CylinderModel> makeCylinderModel(CylinderModelKind kind, const CylinderParameters& parameters);

}  // namespace sphere_contact_estimator
