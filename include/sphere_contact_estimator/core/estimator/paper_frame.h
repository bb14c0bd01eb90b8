#pragma once

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// The papers' frame (SAE: x forward, y right, z down) and ROS's (REP 103: x forward, y left, z up) at the
/// contact point are one turned by half a turn about x: paper (x, y, z) = ROS (x, -y, -z), for vectors and
/// axial vectors (angular velocities, moments) alike (docs/conventions.md). The map is its own inverse; the
/// two names say which way a value goes. Every sign flip between the core's paper-frame models and the
/// messages goes through these.
namespace paper_frame
{
/// A horizontal vector (velocity, slip, force, position in the patch).
inline Eigen::Vector2d fromRos(const Eigen::Vector2d& v) { return { v.x(), -v.y() }; }
inline Eigen::Vector2d toRos(const Eigen::Vector2d& v) { return { v.x(), -v.y() }; }
/// A vector or axial vector in space.
inline Eigen::Vector3d fromRos(const Eigen::Vector3d& v) { return { v.x(), -v.y(), -v.z() }; }
inline Eigen::Vector3d toRos(const Eigen::Vector3d& v) { return { v.x(), -v.y(), -v.z() }; }
/// A linear map between such vectors, or their covariance: D M D, D = diag(1, -1, -1) (its own inverse too).
inline Eigen::Matrix3d toRos(const Eigen::Matrix3d& M)
{
  const Eigen::Vector3d d(1.0, -1.0, -1.0);
  return d.asDiagonal() * M * d.asDiagonal();
}
/// A z component: a spin, a yaw rate or a yaw moment.
inline double zFromRos(double z) { return -z; }
inline double zToRos(double z) { return -z; }
}  // namespace paper_frame

}  // namespace sphere_contact_estimator
