#pragma once

// STL
#include <array>
#include <cstdint>
#include <string>
#include <vector>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/calibration/calibration_sample.h"
#include "sphere_contact_estimator/core/estimator/estimator_settings.h"

namespace sphere_contact_estimator
{
/// What the models predict for a run: the estimator replayed over every sample with one set of parameters (the node's
/// estimator, so transients, the frame and the turn rate are as the node has them).
struct Prediction
{
  std::vector<Eigen::Vector2d> force;  ///< brush + rolling resistance on the robot, ground frame [N]
  std::vector<double> sliding;         ///< the brush model's sliding share of the patch
  std::vector<Eigen::Vector2d> slip;   ///< (sigma_x, sigma_y), ROS contact frame
  std::vector<double> spin;            ///< phi, ROS contact frame [1/m]
  std::vector<double> tilt_ratio;      ///< chi_gamma
  std::vector<double> speed;           ///< rolling speed V_r [m/s]
  std::vector<double> heading;         ///< of the contact frame in the ground frame [rad]
  std::vector<double> rolling_resistance;  ///< F_R L, against the rolling direction [N]
  std::vector<std::uint32_t> flags;    ///< the estimate's flags (estimate_flags)
  std::vector<std::uint8_t> answered;  ///< the estimator answered (input finite and possible)
};
Prediction predictForces(const std::vector<CalibrationSample>& samples, const EstimatorSettings& settings);

/// Why a sample does not enter the fit, counted in FitResult::rejected.
enum class Rejection : int
{
  NoImu = 0,      ///< no IMU sample paired with the message
  Unanswered,     ///< the estimator refused the input (not finite, impossible)
  Standstill,     ///< slips undefined (V_r below standstill_speed): the brush force is the bristles' history
  Reset,          ///< a gap or a time jump reset the state here
  WithinNoise,    ///< the motion is within the odometry's declared noise (a parked robot)
  Transient,      ///< the rolling speed changes within a patch transit: the steady state lags (FitOptions::max_lag)
  Count
};
const char* toString(Rejection r);

/// The parameters the fit can take: the brush's bristle stiffness k (with a fixed patch radius a the data determine
/// k a^3, through the slip stiffness C_sigma = 8/3 k a^3 of the parabolic pressure), friction mu, and the floor's
/// damping gamma (with its stiffness k_s held: at the speeds a robot rolls, far below the cylinder's v* (eq. 29),
/// the rolling resistance is mu_roll = gamma/k_s v to first order (eq. 27), so the data determine gamma/k_s, the
/// floor's relaxation time, and not gamma, k_s and the floor's density apart).
enum class FitParameter : int
{
  BristleStiffness = 0,
  Friction,
  SurfaceDamping,
  Count
};
const char* parameterName(FitParameter p);  ///< as in the node's parameter file
double parameterValue(const EstimatorSettings& s, FitParameter p);

struct FitOptions
{
  /// k and mu by default. The floor's damping only where asked (and the settings have a rolling-resistance model):
  /// free, it also takes up what a run that is not the model's leaves (a uniform pressure where the fit assumes the
  /// parabolic one: the residuals' streaks, the mismatch flag's evidence, fell from 0.58-0.72 to 0.22), so fit it from
  /// runs the fit of k and mu shows to be the model's.
  std::array<bool, static_cast<int>(FitParameter::Count)> fit{ { true, true, false } };
  /// Huber loss: residuals beyond this many standard deviations of the measured force count linearly (IMU spikes,
  /// bumps), not quadratically.
  double huber = 3.0;
  /// Starts: the parameter file's values and values this factor below and above them (the best fit kept).
  double start_spread = 3.0;
  int max_iterations = 50;
  /// mu is determined only where the fitted model slides over this share of the patch at kMinSlidingSamples samples or
  /// more; otherwise the data give a bound, mu >= max |F| / F_z.
  double sliding_share = 0.5;
  static constexpr int kMinSlidingSamples = 10;
  /// A fitted parameter counts as determined where its standard deviation is below this fraction of its value.
  double determined_sd = 0.2;
  /// The models' accuracy target during the fit (a fraction of mu F_z): their error must sit below the IMU's noise.
  double accuracy_target = 1e-3;
  /// The fit compares each message with the steady state of its slips, which the patch reaches only after rolling its
  /// length 2a. Where the rolling speed changes, the slips at a constant sliding velocity change with it, by a share
  /// 2a |dV_r/dt| / V_r^2 of themselves over a transit: messages where that exceeds max_lag stay out (in a synthetic
  /// run from the node's auto model, keeping them put k 0.45 sd high on average over 40 seeds).
  double max_lag = 0.02;
  double lag_window = 0.05;  ///< half-width of the window dV_r/dt is fitted over [s]
  /// Threads evaluating the messages' residuals (Ceres Solver's num_threads): the fitted values agree to rounding
  /// across thread counts, not bit for bit (the sums' order changes).
  int threads = 1;
};

struct FittedValue
{
  FitParameter parameter = FitParameter::BristleStiffness;
  double start = 0.0;       ///< the parameter file's value
  double value = 0.0;       ///< fitted (or, not fitted, the file's)
  double sd = 0.0;          ///< standard deviation [the parameter's unit]
  /// The 95 % interval: value -+ 1.96 sd, or, for the stiffness where friction is only a bound, the span of its fits
  /// over every mu the forces allow (wider); for friction without sliding, [lower_bound, infinity).
  double low = 0.0, high = 0.0;
  bool fitted = false;      ///< asked for
  bool determined = false;  ///< the data determine it (sd below FitOptions::determined_sd of it; mu: sliding seen)
  double lower_bound = 0.0; ///< mu without sliding: the bound the data give (0: none)
  std::string note;         ///< why not determined, in a few words
};

struct FitResult
{
  EstimatorSettings settings;  ///< the parameter file's, with the determined values
  std::vector<FittedValue> values;
  Eigen::MatrixXd correlation;  ///< of the parameters of the final solve, in the order of `correlated`
  std::vector<FitParameter> correlated;
  int samples = 0;              ///< all messages
  int used = 0;                 ///< entering the fit
  std::array<int, static_cast<int>(Rejection::Count)> rejected{};
  double reduced_chi2 = 0.0;    ///< sum of squared residuals / (used residuals - fitted parameters)
  /// The force residuals' lag-1 autocorrelation on each ground axis, over the used messages in order. A run that is
  /// not the model's (another pressure distribution, an IMU bias, a floor that gives) leaves streaks of one sign: 0.58-
  /// 0.84 in synthetic runs with a uniform pressure or a 0.2 m/s^2 bias, against at most 0.19 (median 0.03) in 100 runs
  /// of the model. mismatch() tells.
  Eigen::Vector2d residual_autocorrelation = Eigen::Vector2d::Zero();
  /// The residuals run in streaks: the autocorrelation above mismatchThreshold(used) on an axis.
  bool mismatch() const;
  static constexpr double kMismatchAutocorrelation = 0.3;
  /// max(4 / sqrt(used), kMismatchAutocorrelation).
  static double mismatchThreshold(int used);
  bool converged = false;
  int iterations = 0;
  // what the used samples covered
  double speed_min = 0.0, speed_max = 0.0, slip_max = 0.0, sliding_max = 0.0;
  /// The largest horizontal force the run shows beyond its noise [N]: max |F| less (sqrt(2 ln N) + 2) sqrt(2) sd, what N
  /// noisy readings of two axes can add by chance. Friction's bound without sliding is this over F_z.
  double force_max = 0.0;
  Prediction fitted;            ///< the models at the fitted values (the node's prediction, the configured model)
  std::vector<std::uint8_t> used_mask;
  /// Each message's force residual at the fit (measured - model at its latent slips) in standard deviations of the
  /// measured force; NaN where not used.
  std::vector<Eigen::Vector2d> residuals;
  std::vector<Rejection> rejection;  ///< why each message was not used (Rejection::Count where used)
};

/// Fits the chosen parameters to the measured forces by nonlinear least squares with errors in the inputs (Ceres
/// Solver, Levenberg-Marquardt, Huber loss on the forces, several starts). Each message that enters (rolling, not
/// parked, an IMU sample paired) has latent true slips (sigma_x, sigma_y, phi), tied to the measured ones by the
/// covariance the odometry declares (EstimatorInput::twist_covariance, through the slips' Jacobian), and the measured
/// force is compared with the steady brush model at those slips plus the rolling resistance, in units of the force's
/// noise; the parameters are found with all the latent slips at once (the Schur complement eliminates them). The
/// models' accuracy is raised to FitOptions::accuracy_target. Standard deviations from the fit's covariance (the
/// latent slips marginalised), scaled by the reduced chi-square where that exceeds 1. Throws std::invalid_argument
/// when no sample can enter the fit.
FitResult fitContact(const std::vector<CalibrationSample>& samples, const EstimatorSettings& settings,
                     const FitOptions& options = FitOptions());

}  // namespace sphere_contact_estimator
