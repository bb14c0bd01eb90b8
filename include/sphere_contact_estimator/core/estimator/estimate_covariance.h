#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/force_covariance.h"
#include "sphere_contact_estimator/core/estimator/twist_covariance.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"

namespace sphere_contact_estimator
{
/// How uncertain an estimate is because its odometry is: the twist covariance carried to the outputs (issue 13).
/// Separate from the models' error estimates, which say how far a model's answer is from its own exact solution.
struct EstimateCovariance
{
  CovarianceStatus status = CovarianceStatus::Disabled;
  CovarianceMethod brush_method = CovarianceMethod::None;
  Eigen::Matrix3d brush = Eigen::Matrix3d::Zero();  ///< of (F_x, F_y, M_z), ROS contact frame [N^2, N^2 m, N^2 m^2]
  double brush_spread = 0.0;  ///< max(sd F_x, sd F_y, sd M_z / a) / (mu F_z), the unit of accuracy_target
  double brush_age = 0.0;     ///< how long ago the brush covariance was propagated (covariance_period) [s]
  CovarianceMethod rolling_resistance_method = CovarianceMethod::None;
  double rolling_speed_variance = 0.0;             ///< of V_r [m^2/s^2]
  double rolling_resistance_force_variance = 0.0;  ///< of F_R L [N^2]
  double mu_roll_variance = 0.0;                   ///< of mu_roll [m^2]
};

/// d(sigma_x, sigma_y, phi, psi) / d(V_Cx, V_Cy, omega_x, omega_y, omega_z): slips and spin in the paper frame of the
/// contact frame at `heading`, and psi the turn of the rolling direction from that frame (about z down), against
/// the twist in the ground frame (ROS axes), at rolling speed V = R_r |(omega_x, omega_y)| along the heading
/// (eqs. 2, 12, 13; docs/conventions.md). V > 0.
Eigen::Matrix<double, 4, 5> slipJacobian(const Eigen::Vector3d& omega, const Eigen::Vector2d& v_contact, double R_r,
                                         double heading);

/// d(V_s,x, V_s,y, omega_z, V_r,x, V_r,y) / d(V_Cx, V_Cy, omega_x, omega_y, omega_z): the bristles' drive inputs (eq. 2,
/// V_s = V_C - V_r with V_r = R_r (omega_y, -omega_x)) and the roots' velocity V_r (eq. 31: they move at -V_r) in the
/// contact frame at `heading`, ROS axes, against the twist in the ground frame. Linear: it holds at any speed,
/// standstill included (StandstillCovariance).
Eigen::Matrix<double, 5, 5> driveJacobian(double R_r, double heading);

/// dV_r / d(V_Cx, V_Cy, omega_x, omega_y, omega_z), V_r = R_r |(omega_y, -omega_x)|, along the heading.
Eigen::Matrix<double, 1, 5> speedJacobian(double R_r, double heading);

/// The five components of the twist the estimator uses (V_Cx, V_Cy, omega_x, omega_y, omega_z) out of a 6 x 6
/// twist covariance (linear x, y, z, angular x, y, z).
Eigen::Matrix<double, 5, 5> usedTwistCovariance(const TwistCovariance& C);

}  // namespace sphere_contact_estimator
