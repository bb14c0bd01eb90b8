#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_model.h"
#include "sphere_contact_estimator/core/numerics/covariance.h"

namespace sphere_contact_estimator
{
/// The covariance of the brush forces and moment (F_x, F_y, M_z) [N^2, N^2 m, N^2 m^2] at slips (sigma_x, sigma_y,
/// phi) whose covariance is Sigma (paper frame, the rolling frame epsilon = (0, 1); chi_gamma is held, so a change
/// of phi goes to phi_gamma and phi_psi in proportion). It is the uncertainty of the model's answer to uncertain
/// inputs, never folded into its error_estimate. The 4 x 4 form adds the rolling direction's angle psi from the
/// frame the forces are reported in (paper frame, about z down): the slips, given in the reported frame, turn by
/// -psi into the rolling frame, and the forces turn back by psi (an uncertain heading of V_r).
///
/// - Sigma zero: exactly zero (Zero).
/// - The linear model: J Sigma J^T with the exact Jacobian of eqs. 61-62 and of the scaling onto the friction circle
///   past mu F_z (Jacobian).
/// - The steady, transient and auto models: the unscented transform (2 sigma points at +-sqrt(3) standard
///   deviations along each of Sigma's principal axes with a spread, up to 8, and the mean, for the bend) through the
///   steady model, each to a tolerance of a twentieth of the largest spread it resolves (a component whose spread is
///   far smaller is resolved to that, not to its own), and never below 1e-4 of mu F_z (a spread below 2e-3 of mu F_z
///   is known to about 1e-4 of it). A stateless map is needed for sigma points, and an error in the inputs that persists over the patch's
///   memory moves the transient state to the steady one of the moved inputs: the steady sensitivity is that of an
///   input error held for a transit (a bias); white noise on messages closer than a transit moves the forces less.
///   The linearisation is exact only while the model is smooth over the spread; the sliding limit, the onset of
///   sliding and the kink of the sliding direction are not (measured against Monte Carlo: docs/benchmarks.md).
/// - No steady state at the sigma points (|R_gamma| < a with tilt): not propagated (None, defined false).
/// - A work budget (max_work, BrushForces::work units) the sigma points would overrun (an evaluation stopped by its
///   share, flagged kAccuracyNotMet): the linear model's Jacobian instead, smooth false (only approximate).
struct ForceCovariance
{
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  CovarianceMethod method = CovarianceMethod::None;
  bool defined = false;  ///< false: no covariance (the steady state does not exist at the inputs' spread)
  int evaluations = 0;   ///< model evaluations spent
  long work = 0;         ///< their work (BrushForces::work units)
  /// False where the forces bend over the spread as much as they change across it (a kink or a jump: the onset of
  /// sliding, the friction limit; Unscented::curvature above kSmooth), or, with tilt, where phi_gamma's spread
  /// reaches the edge of the steady state (|R_gamma| = a) within three standard deviations: the covariance is then
  /// only approximate. Always true for Zero and Jacobian.
  bool smooth = true;
  static constexpr double kSmooth = 0.25;
  /// The largest standard deviation, max(sd F_x, sd F_y, sd M_z / a) / (mu F_z), the unit of accuracy_target.
  double spread(const BrushParameters& p) const;
};

/// Sigma must be a valid covariance (covarianceProblem); throws std::invalid_argument otherwise.
ForceCovariance propagateSlipCovariance(BrushModelKind kind, const BrushParameters& p, const Eigen::Vector2d& sigma,
                                        double phi, double chi_gamma, const Eigen::Matrix3d& Sigma,
                                        long max_work = BrushModel::kUnlimitedBudget);
/// The same with the rolling direction's angle: Sigma of (sigma_x, sigma_y, phi, psi).
ForceCovariance propagateSlipCovariance(BrushModelKind kind, const BrushParameters& p, const Eigen::Vector2d& sigma,
                                        double phi, double chi_gamma, const Eigen::Matrix4d& Sigma,
                                        long max_work = BrushModel::kUnlimitedBudget);

}  // namespace sphere_contact_estimator
