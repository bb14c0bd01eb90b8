#pragma once

// STL
#include <cstdint>

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// What the odometry said of its twist's uncertainty, and what became of it; the numbers are those of
/// ContactEstimate's covariance_status.
enum class CovarianceStatus : std::uint8_t
{
  Ok = 0,           ///< propagated (a zero covariance exactly, to zero)
  Disabled = 1,     ///< propagate_covariance is off
  Unknown = 2,      ///< a component the estimate uses is marked unknown (-1 on its diagonal, the ROS convention)
  Invalid = 3,      ///< not finite, a negative variance, not symmetric or not positive semi-definite: ignored
  Undefined = 4,    ///< no brush covariance here: slips undefined (standstill), no steady state over the spread
  Approximate = 5,  ///< propagated, but the rolling speed's spread reaches the standstill speed, or the forces kink or
                    ///< jump within the spread (ForceCovariance::smooth): only approximate (docs/uncertainty.md)
};

const char* toString(CovarianceStatus status);

/// The twist covariance of nav_msgs/Odometry (rows and columns: linear x, y, z, angular x, y, z), in the frame of
/// the twist.
using TwistCovariance = Eigen::Matrix<double, 6, 6>;

/// Checks it for the five components the estimator uses (linear x, y: the contact centre's velocity; angular x, y,
/// z); linear z is never used and may hold anything. Returns Ok, Unknown (an exact -1 on a used diagonal entry) or
/// Invalid, with the reason in `reason` (nullptr when Ok).
CovarianceStatus checkTwistCovariance(const TwistCovariance& C, const char** reason = nullptr);

/// The same covariance in a frame turned by R (a vector v there is R v): blkdiag(R, R) C blkdiag(R, R)^T.
TwistCovariance rotateTwistCovariance(const TwistCovariance& C, const Eigen::Matrix3d& R);

}  // namespace sphere_contact_estimator
