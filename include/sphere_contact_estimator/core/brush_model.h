#pragma once

// STL
#include <memory>
#include <optional>
#include <string_view>

// Package
#include "sphere_contact_estimator/core/brush_forces.h"
#include "sphere_contact_estimator/core/brush_parameters.h"
#include "sphere_contact_estimator/core/contact_kinematics.h"

namespace sphere_contact_estimator
{
enum class BrushModelKind
{
  Linear,     ///< eqs. 61-62: steady state, vanishing sliding (BrushLinear)
  Steady,     ///< steady bristle field on a discretised patch, limited friction (BrushSteady)
  Transient,  ///< the brush PDE in the time domain (BrushTransient)
  Auto,       ///< the cheapest of the above that meets an accuracy target, per update (BrushAuto)
};

const char* toString(BrushModelKind kind);
std::optional<BrushModelKind> parseBrushModelKind(std::string_view name);

/// One small interface for the three brush models: forces from the contact kinematics over a step.
class BrushModel
{
public:
  /// Validates the parameters (std::invalid_argument).
  explicit BrushModel(const BrushParameters& parameters);
  virtual ~BrushModel() = default;

  /// Forces after advancing by dt [s] with the kinematics held constant over the step. The steady
  /// models ignore dt; the transient model integrates over it. Throws std::invalid_argument for
  /// non-finite kinematics or a negative or non-finite dt.
  virtual BrushForces update(const ContactKinematics& kinematics, double dt) = 0;
  /// Forgets all history (transient state); a no-op for the steady models.
  virtual void reset() {}
  /// The patch frame turned by alpha [rad] about its z axis (paper frame, z down), for heading changes the
  /// turn coupling does not carry (the rolling direction re-initialised after standstill or a reversal):
  /// state that lives in the frame is re-expressed in the new axes. Stateless models have nothing to turn.
  virtual void rotateFrame(double /*alpha*/) {}
  virtual BrushModelKind kind() const = 0;

  const BrushParameters& parameters() const { return p_; }

protected:
  static void checkInput(const ContactKinematics& kinematics, double dt);

  BrushParameters p_;
};

/// The steady models, which work on slips (eq. 12) in the frame where epsilon = (0, 1): update()
/// computes the slips, rotates into that frame, evaluates and rotates the forces back. Below the
/// standstill speed the slips are undefined: zero forces, flagged kStandstill.
class BrushSlipModel : public BrushModel
{
public:
  using BrushModel::BrushModel;
  BrushForces update(const ContactKinematics& kinematics, double dt) override;

  /// Forces from slips in the epsilon = (0, 1) frame: sigma, spin phi, and its tilt and turn parts
  /// phi_gamma + phi_psi = phi (eq. 13).
  virtual BrushForces evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const = 0;
};

std::unique_ptr<BrushModel> makeBrushModel(BrushModelKind kind, const BrushParameters& parameters);

}  // namespace sphere_contact_estimator
