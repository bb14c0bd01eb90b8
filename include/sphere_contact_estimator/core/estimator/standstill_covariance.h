#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_model.h"

namespace sphere_contact_estimator
{
/// The forces' covariance while the slips are undefined (a parked robot), where the unscented transform through the
/// steady model has no slips to work on.
///
/// There the adhering bristles integrate the drive (eq. 1 without rolling, u' = w): an error in one message's
/// (V_s, omega_z) moves the forces by dt R times it (AdhesionResponse::drive) and stays in the state. The noise in
/// omega_x, omega_y also rolls the roots by d = -V_r dt (eq. 31): the deflection field moves with them, which turns its
/// moment about the patch centre by d x F, and carries what lies at the rim out of the patch, one-sided (what leaves is
/// lost, what enters is undeformed): AdhesionResponse::roll, L(d) = |d| L(d / |d|). With the odometry's errors
/// independent from message to message (what a twist covariance per message says), the forces walk at random:
/// Sigma_F += Var(dt R w + L(d)) per message, w = (V_s, omega_z) and V_r jointly Gaussian (driveJacobian,
/// estimate_covariance.h; part of V_s's noise is -V_r's): L's moments over d in closed form along the radius and by
/// the mean over kRollNodes directions, its covariance with the linear part through d (the regression of w on d).
/// The walk starts from zero where the state is the model's own start (a new or reset estimator) or from the
/// covariance the forces had when the slips were last defined. It is always only approximate
/// (COVARIANCE_APPROXIMATE): it leaves out the bristles that the noise pushes onto their bounds and that forget what
/// they integrated, and takes each message's share at the state the model reached, not over the realisations'
/// states. Its standard deviations against Monte Carlo over noise realisations: within 16 % at the default robot, 23 %
/// at a uniform pressure's (test_uncertainty); 0.91-2.19 times over random robots of the envelope, median 1.03
/// (model_accuracy --parked-walk; 0.43-1.29 before the roll was walked; docs/uncertainty.md), the highest for M_z of
/// a 1.9-kg robot at 30 Hz whose roots rolled about a lattice spacing (not explained: a lattice shifted by less than a
/// spacing turned a uniform field's moment by a few per cent of d x F, where the continuum turns it by half). Where
/// most bristles slide (spinning in place, kSlidingShare) it overstated the spread 2-8 times: not followed there (the
/// estimator answers without a covariance and the walk resumes after). No standard deviation passes what the friction
/// limit allows (|F| <= mu F_z, |M_z| <= mu F_z a): a component that reaches it is held there (its row and column
/// scaled, which keeps the matrix a covariance). All in the ROS contact frame.
class StandstillCovariance
{
public:
  /// From a known covariance.
  void restart(const Eigen::Matrix3d& start);
  /// Unknown from here (a message without a usable covariance, a retune of the model) until restart.
  void lose() { known_ = false; }
  bool known() const { return known_; }
  /// Beyond this share of the bristles sliding (spinning in place) the walk is not followed.
  static constexpr double kSlidingShare = 0.5;
  /// Directions over which the roll's moments are averaged (AdhesionResponse::directions).
  static constexpr int kRollNodes = AdhesionResponse::kDirections;

  /// One message of dt [s]: response the model's (paper frame), drive the covariance of
  /// (V_s,x, V_s,y, omega_z, V_r,x, V_r,y) (ROS contact frame, driveJacobian), limits the largest standard deviations
  /// (F_x, F_y, M_z).
  void advance(const AdhesionResponse& response, const Eigen::Matrix<double, 5, 5>& drive, double dt,
               const Eigen::Vector3d& limits);

  const Eigen::Matrix3d& covariance() const { return sigma_; }

private:
  Eigen::Matrix3d sigma_ = Eigen::Matrix3d::Zero();
  bool known_ = true;  // a new estimator's model starts from its own state
};

}  // namespace sphere_contact_estimator
