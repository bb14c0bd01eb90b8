#pragma once

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// The forces' covariance while the slips are undefined (a parked robot), where the unscented transform through the
/// steady model has no slips to work on.
///
/// There the adhering bristles integrate the drive (eq. 1 without rolling, u' = w): an error in one message's
/// (V_s, omega_z) moves the forces by dt R times it (R = BrushModel::adhesionResponse) and stays in the state. With the
/// odometry's errors independent from message to message (what a twist covariance per message says), the forces
/// walk at random: Sigma_F += (dt R) Sigma_w (dt R)^T per message, Sigma_w the drive's covariance (driveJacobian, estimate_covariance.h). The
/// walk starts from zero where the state is the model's own start (a new or reset estimator) or from the covariance the
/// forces had when the slips were last defined. It is always only approximate (COVARIANCE_APPROXIMATE): it leaves out
/// the rolling the noise in omega_x, omega_y gives the lattice (which moves the deflection at the rim: the uniform
/// pressure's bristles hold one there), and the bristles that the noise pushes onto their bounds and that forget what
/// they integrated. Its standard deviations against Monte Carlo over noise realisations: within 15 % at the default
/// robot (test_uncertainty), 0.43-1.29 times over random robots of the envelope (model_accuracy --parked-walk;
/// docs/uncertainty.md); from a field rolling left behind within 30 % after a skid. Where most bristles slide (spinning
/// in place, kSlidingShare) it overstated the spread 2-8 times: not followed there (the estimator answers without a
/// covariance and the walk resumes after). No standard deviation passes what the friction limit allows (|F| <= mu F_z,
/// |M_z| <= mu F_z a): a component that reaches it is held there (its row and column scaled, which keeps the matrix a
/// covariance). All in the ROS contact frame.
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

  /// One message of dt [s]: response the model's adhesionResponse (paper frame), drive the covariance of
  /// (V_s,x, V_s,y, omega_z) (ROS contact frame), limits the largest standard deviations (F_x, F_y, M_z).
  void advance(const Eigen::Matrix3d& response, const Eigen::Matrix3d& drive, double dt,
               const Eigen::Vector3d& limits);

  const Eigen::Matrix3d& covariance() const { return sigma_; }

private:
  Eigen::Matrix3d sigma_ = Eigen::Matrix3d::Zero();
  bool known_ = true;  // a new estimator's model starts from its own state
};

}  // namespace sphere_contact_estimator
