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
/// There the adhering bristles integrate the drive (eq. 1 without rolling, u' = w): an error in one message's (V_s,
/// omega_z) moves the forces by dt R times it (AdhesionResponse::drive) and stays in the state. The noise in omega_x,
/// omega_y also rolls the roots by d = -V_r dt (eq. 31): the deflection field moves with them, which turns its moment
/// about the patch centre by d x F, and carries what lies at the rim out of the patch, one-sided (what leaves is lost,
/// what enters is undeformed): AdhesionResponse::roll, L(d) = |d| L(d / |d|). With the odometry's errors independent
/// from message to message (what a twist covariance per message says), the forces walk at random: Sigma_F += Var(dt R w
/// + L(d)) per message, w = (V_s, omega_z) and V_r jointly Gaussian (driveJacobian, estimate_covariance.h; part of
/// V_s's noise is -V_r's): L's moments over d in closed form along the radius and by the mean over kRollNodes
/// directions, its covariance with the linear part through d (the regression of w on d). The walk starts from zero
/// where the state is the model's own start (a new or reset estimator) or from the covariance the forces had when the
/// slips were last defined. A bristle on its bound (sliding) moves only along it (eq. 4b), and one near it walks with
/// the noise until the bound holds it (a reflected walk): those within half the noise's push since the walk started
/// count as held (band). It is always only approximate (COVARIANCE_APPROXIMATE): the band takes the reflection in only
/// on average, and each message's share is taken at the state the model reached, not over the realisations' states. Its
/// standard deviations against Monte Carlo over noise realisations: within 18 % at the default robot, 17 % after a
/// lateral skid, 23 % at a uniform pressure's (test_uncertainty); 0.91-2.06 times over random robots of the envelope,
/// median 1.03 (model_accuracy --parked-walk 7 60; 0.43-1.29 before the roll was walked; docs/uncertainty.md),
/// 0.87-1.56 after a skid (11 60 --after-skid), the highest for M_z of a 1.9-kg robot at 30 Hz whose roots rolled about
/// a lattice spacing (not explained: a lattice shifted by less than a spacing turned a uniform field's moment by a few
/// per cent of d x F, where the continuum turns it by half); parked after spinning in place M_z's 1.55-1.75 times (the
/// noise ratchets the bristles off their bounds, which no per-message share sees). Where most bristles slide (spinning
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
  /// Directions over which the roll's moments are averaged (AdhesionResponse::directions).
  static constexpr int kRollNodes = AdhesionResponse::kDirections;

  /// One message of dt [s]: response the model's (paper frame), drive the covariance of
  /// (V_s,x, V_s,y, omega_z, V_r,x, V_r,y) (ROS contact frame, driveJacobian), limits the largest standard deviations
  /// (F_x, F_y, M_z), a the patch radius [m] (for band).
  void advance(const AdhesionResponse& response, const Eigen::Matrix<double, 5, 5>& drive, double dt,
               const Eigen::Vector3d& limits, double a);
  /// The band [m] within which an adhering bristle counts as held by its bound for this message's response
  /// (BrushModel::adhesionResponse: it moves only along the bound, as a sliding one): kBand times how far the noise has
  /// pushed a bristle along its bound's normal since the walk (re)started, this message's push included (drive and dt
  /// as advance takes them, a the patch radius). A bristle walks at random with the noise, and one that reaches its
  /// bound is held there: a reflected walk, whose spread across the bound is about 0.36 of the free one's. Each
  /// message's share taken from the state the noise has reached cannot see that (its sum over messages is the free
  /// walk's: the reflection's pull is correlated with the noise that went before), so the bristles the walk may have
  /// brought to the bound move only along it.
  double band(const Eigen::Matrix<double, 5, 5>& drive, double dt, double a) const;
  /// Half the push. After a lateral skid (test_uncertainty) the F_y-M_z correlation walked 0.45-0.49 against
  /// 0.59-0.65 over the noise's realisations (0.08-0.18 with the sliding bristles alone held; 0.57-0.62 at 0.75, where
  /// M_z's standard deviation rose to 1.28 times the realisations'), the standard deviations 1.03-1.17 times theirs
  /// (0.80-1.22); parked from the model's own start 1.11 and 1.18 at worst (1.15 and 1.23 with the sliding ones alone
  /// held, 1.14 and 1.16 with those left out of the response before); over 60 random robots after a skid
  /// (model_accuracy --parked-walk 11 60 --after-skid) 0.87-1.56 (0.54-1.54 before), from their own start (7 60)
  /// 0.91-2.06 (0.91-2.19). Leaving the held bristles out of the drive's response instead of moving them along their
  /// bound matched these as well but lost a loud noise's walk (every bristle held: no response).
  static constexpr double kBand = 0.5;

  const Eigen::Matrix3d& covariance() const { return sigma_; }

private:
  Eigen::Matrix3d sigma_ = Eigen::Matrix3d::Zero();
  bool known_ = true;  // a new estimator's model starts from its own state
  double pushed2_ = 0.0;  // the pushes' variance along a bound's normal since the walk (re)started [m^2]
  static double push2(const Eigen::Matrix<double, 5, 5>& drive, double dt, double a);
};

}  // namespace sphere_contact_estimator
