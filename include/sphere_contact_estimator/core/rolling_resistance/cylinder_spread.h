#pragma once

// Package
#include "sphere_contact_estimator/core/numerics/covariance.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"

namespace sphere_contact_estimator
{
/// How uncertain the rolling resistance is when the rolling speed is: the variances of F_R (per unit length, eq. 17)
/// and of mu_roll (eq. 26) for a speed v with standard deviation sd.
///
/// By the unscented transform in one dimension (v and v +- sqrt(3) sd, weighted 2/3 and 1/6; exact for the mean and
/// variance of a function linear over the spread): F_R(v) is smooth but for its kinks at the critical speed v_c (the
/// patch closing to a point) and at v = 0, where a speed, a norm, folds the spread back onto itself (a sigma point
/// below zero is taken at its absolute value). Zero sd gives exactly zero.
struct CylinderSpread
{
  double F_R_variance = 0.0;      ///< [N^2/m^2]
  double mu_roll_variance = 0.0;  ///< [m^2]
  CovarianceMethod method = CovarianceMethod::None;
};

/// Throws std::invalid_argument for a speed the model refuses or a sd that is negative or not finite.
CylinderSpread cylinderSpread(const CylinderModel& model, double v, double sd);

}  // namespace sphere_contact_estimator
