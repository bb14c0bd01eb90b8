#pragma once

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// The five twist components the estimator uses: (V_Cx, V_Cy, omega_x, omega_y, omega_z), ROS axes.
using UsedTwist = Eigen::Matrix<double, 5, 1>;

/// How far the sphere's motion is from rest in units of the noise its odometry declares: the Mahalanobis distance
/// sqrt(x^T S^+ x) of the used twist x under its covariance S (usedTwistCovariance). Everything that drives the
/// bristles (V_s = V_C - V_r, V_r = R_r (omega_y, -omega_x), omega_z) is a linear map of x, so a motion within the
/// noise drives them within the noise too. A direction S declares exact (zero variance) is infinitely far unless x
/// has no component along it. Returns -1 when S is not finite or not symmetric positive semi-definite.
double motionToNoise(const UsedTwist& x, const Eigen::Matrix<double, 5, 5>& S);

/// At rest the motion is the noise: for Gaussian noise x^T S^-1 x is chi-squared with five degrees of freedom, and
/// 99.9 % of a parked robot's messages lie within sqrt(chi2_5(0.999)) = sqrt(20.515).
constexpr double kMotionWithinNoise = 4.5293;

}  // namespace sphere_contact_estimator
