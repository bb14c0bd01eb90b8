#pragma once

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// d(V_s,x, V_s,y, omega_z) / d(V_Cx, V_Cy, omega_x, omega_y, omega_z): the bristles' drive inputs (eq. 2, V_s = V_C -
/// V_r with V_r = R_r (omega_y, -omega_x)) in the contact frame at `heading`, ROS axes, against the twist in the
/// ground frame. Linear: it holds at any speed, standstill included.
Eigen::Matrix<double, 3, 5> driveJacobian(double R_r, double heading);

/// The forces' covariance while the slips are undefined (a parked robot), where the unscented transform through the
/// steady model has no slips to work on.
///
/// There the adhering bristles integrate the drive (eq. 1 without rolling, u' = w): an error in one message's
/// (V_s, omega_z) moves the forces by dt R times it (R = BrushModel::adhesionResponse) and stays in the state. With the
/// odometry's errors independent from message to message (what a twist covariance per message says), the forces
/// walk at random: Sigma_F += (dt R) Sigma_w (dt R)^T per message, Sigma_w the drive's covariance (driveJacobian). The
/// walk starts from zero where the state is the model's own start (a new or reset estimator: within 15 % of Monte
/// Carlo over noise realisations, test_uncertainty, though up to a third of the bristles slide at times), or from the
/// covariance the forces had when the slips were last defined: only approximate, as the steady model's sensitivity near
/// standstill is, and because the field rolling left behind has bristles near their bounds that slide as the noise
/// walks them and forget what they integrated (within 30 % after a skid). Where most bristles slide (spinning in
/// place, kSlidingShare) it overstates the spread 2-8 times: not followed there. No standard deviation passes what the
/// friction limit allows (|F| <= mu F_z, |M_z| <= mu F_z a): a component that reaches it is held there (its row and
/// column scaled, which keeps the matrix a covariance) and the walk is then only approximate. All in the ROS contact
/// frame.
class StandstillCovariance
{
public:
  /// From a known covariance (approximate: only approximately known).
  void restart(const Eigen::Matrix3d& start, bool approximate);
  /// Unknown from here (a message without a usable covariance, a retune of the model) until restart.
  void lose() { known_ = false; }
  bool known() const { return known_; }
  /// Still known, but only approximately from here (the state moved in a way the walk does not follow).
  void degrade() { approximate_ = true; }
  /// Beyond this share of the bristles sliding (spinning in place) the walk is not followed: the estimator says the
  /// covariance is undefined there, and degrades the walk.
  static constexpr double kSlidingShare = 0.5;

  /// One message of dt [s]: response the model's adhesionResponse (paper frame), drive the covariance of
  /// (V_s,x, V_s,y, omega_z) (ROS contact frame), limits the largest standard deviations (F_x, F_y, M_z).
  void advance(const Eigen::Matrix3d& response, const Eigen::Matrix3d& drive, double dt,
               const Eigen::Vector3d& limits);

  const Eigen::Matrix3d& covariance() const { return sigma_; }
  bool approximate() const { return approximate_; }

private:
  Eigen::Matrix3d sigma_ = Eigen::Matrix3d::Zero();
  bool known_ = true;  // a new estimator's model starts from its own state
  bool approximate_ = false;
};

}  // namespace sphere_contact_estimator
