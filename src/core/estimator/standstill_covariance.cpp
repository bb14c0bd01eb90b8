#include "sphere_contact_estimator/core/estimator/standstill_covariance.h"

// STL
#include <cmath>

namespace sphere_contact_estimator
{
void StandstillCovariance::restart(const Eigen::Matrix3d& start)
{
  sigma_ = start;
  known_ = true;
}

void StandstillCovariance::advance(const Eigen::Matrix3d& response, const Eigen::Matrix3d& drive, double dt,
                                   const Eigen::Vector3d& limits)
{
  if (!known_ || !(dt > 0.0))
    return;
  // paper (x, y, z) = ROS (x, -y, -z), for the forces and the drive alike
  const Eigen::Matrix3d D = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  const Eigen::Matrix3d J = dt * (D * response * D);
  sigma_ += J * drive * J.transpose();
  sigma_ = 0.5 * (sigma_ + sigma_.transpose());
  for (int i = 0; i < 3; ++i)
  {
    const double limit2 = limits(i) * limits(i);
    if (sigma_(i, i) > limit2)
    {
      const double scale = std::sqrt(limit2 / sigma_(i, i));
      sigma_.row(i) *= scale;
      sigma_.col(i) *= scale;
    }
  }
}

}  // namespace sphere_contact_estimator
