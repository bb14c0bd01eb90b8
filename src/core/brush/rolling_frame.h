#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_forces.h"

namespace sphere_contact_estimator
{
/// The rotation about z that turns a patch frame with any epsilon into the one with epsilon = (0, 1),
/// where the closed forms of Sect. 6 hold ("the original reference frame may always be re-oriented to
/// yield epsilon_x = 0, epsilon_y = 1"). The isotropic patch makes the models invariant under it.
class RollingFrame
{
public:
  /// @param epsilon unit vector of eq. 12b; the rolling direction is (epsilon_y, -epsilon_x)
  explicit RollingFrame(const Eigen::Vector2d& epsilon) : c_(epsilon.y()), s_(-epsilon.x()) {}

  /// A patch-frame vector in the rolling frame (x along the rolling direction).
  Eigen::Vector2d toRolling(const Eigen::Vector2d& v) const { return { c_ * v.x() + s_ * v.y(), -s_ * v.x() + c_ * v.y() }; }
  /// A rolling-frame vector back in the patch frame.
  Eigen::Vector2d toPatch(const Eigen::Vector2d& v) const { return { c_ * v.x() - s_ * v.y(), s_ * v.x() + c_ * v.y() }; }
  /// Rotates F_x, F_y of rolling-frame forces into the patch frame (M_z is invariant).
  void forcesToPatch(BrushForces& f) const
  {
    const Eigen::Vector2d F = toPatch({ f.F_x, f.F_y });
    f.F_x = F.x();
    f.F_y = F.y();
  }

private:
  double c_, s_;  // cos and sin of the rolling direction's angle
};

}  // namespace sphere_contact_estimator
