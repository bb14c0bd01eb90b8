#include "sphere_contact_estimator/core/calibration/contact_fit.h"

// STL
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>

// Eigen
#include <Eigen/Cholesky>
#include <Eigen/LU>

// Ceres
#include <ceres/ceres.h>

// Package
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/estimator/estimate_covariance.h"
#include "sphere_contact_estimator/core/estimator/paper_frame.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"

namespace sphere_contact_estimator
{
namespace
{
constexpr int kParameters = static_cast<int>(FitParameter::Count);
constexpr int kMaxFitted = kParameters;
// differences in each latent slip over a fraction of its noise: wide enough that the models' own error (the accuracy
// target of mu F_z) stays a small part of the difference
constexpr double kSlipStep = 0.1;  // of the slip's standard deviation
constexpr std::size_t kSubsetMessages = 400;  // a long run's first solve
constexpr double kInterval95 = 1.96;          // a 95 % interval's half-width in standard deviations
// the parameters' ranges in the fit: the brush's validity (BrushParameters), friction's in the parameter file
constexpr double kStiffnessMin = 1e3, kStiffnessMax = 1e18;  // [N/m^3]
constexpr double kFrictionMin = 1e-3, kFrictionMax = 100.0;
// the floor's relaxation time tau = gamma/k_s [s]: a floor whose rolling resistance at 1 m/s would exceed a tenth of
// the load on a 10-cm sphere (mu_roll = tau v, F_R = mu_roll F_N / R) is no floor a robot rolls on; a model that does
// not fit (an IMU bias) would otherwise put its misfit into gamma without end
constexpr double kTauMin = 1e-7, kTauMax = 1e-2;
constexpr double kDampingStep = 1e-4;  // the log step of the rolling resistance's forward difference in gamma

// The range of a fitted parameter.
std::pair<double, double> rangeOf(FitParameter p, const EstimatorSettings& s)
{
  switch (p)
  {
    case FitParameter::BristleStiffness:
      return { kStiffnessMin, kStiffnessMax };
    case FitParameter::Friction:
      return { kFrictionMin, kFrictionMax };
    case FitParameter::SurfaceDamping:
    case FitParameter::Count:
      break;
  }
  return { kTauMin * s.surface_stiffness, kTauMax * s.surface_stiffness };
}

std::string formatValue(double v)
{
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

double& field(EstimatorSettings& s, FitParameter p)
{
  switch (p)
  {
    case FitParameter::BristleStiffness:
      return s.bristle_stiffness;
    case FitParameter::Friction:
      return s.friction;
    case FitParameter::SurfaceDamping:
    case FitParameter::Count:
      break;
  }
  return s.surface_damping;
}
double field(const EstimatorSettings& s, FitParameter p)
{
  return field(const_cast<EstimatorSettings&>(s), p);
}

// What the fit keeps of one message: the measured slips (paper frame, rolling along +x) and their covariance from the
// odometry's declared noise, the rolling speed, the frame's heading, the rolling resistance, the measured force.
struct Message
{
  int index = 0;
  Eigen::Vector3d slips = Eigen::Vector3d::Zero();  // sigma_x, sigma_y, phi (paper frame)
  Eigen::Matrix3d prior = Eigen::Matrix3d::Identity();  // inverse Cholesky factor of their covariance (whitening)
  Eigen::Vector3d sd = Eigen::Vector3d::Zero();
  double chi_gamma = 1.0, speed = 0.0, heading = 0.0, rolling_resistance = 0.0;
  Eigen::Vector2d force = Eigen::Vector2d::Zero();
  double force_sd = 1.0;
};

// The parameters of one evaluation: the file's, with the fitted ones at exp(x) times the file's.
class Parameters
{
public:
  Parameters(const EstimatorSettings& base, std::vector<FitParameter> fitted)
    : base_(base)
    , fitted_(std::move(fitted))
    , floor_(std::find(fitted_.begin(), fitted_.end(), FitParameter::SurfaceDamping) != fitted_.end())
  {
  }
  int size() const { return static_cast<int>(fitted_.size()); }
  EstimatorSettings at(const double* x) const
  {
    EstimatorSettings s = base_;
    for (int j = 0; j < size(); ++j)
      field(s, fitted_[j]) = field(s, fitted_[j]) * std::exp(x[j]);
    return s;
  }
  FitParameter parameter(int j) const { return fitted_[j]; }
  /// The floor's damping is fitted: the rolling resistance then comes from the trial parameters, not the message.
  bool floorFitted() const { return floor_; }
  const EstimatorSettings& base() const { return base_; }

private:
  EstimatorSettings base_;
  std::vector<FitParameter> fitted_;
  bool floor_;
};

// The brush force (paper frame, rolling along +x) of the steady model (Sects. 3, 6: the state a message's slips settle
// to within a patch transit, a few messages) at slips z (paper frame).
Eigen::Vector2d brushForce(const EstimatorSettings& s, const Message& m, const double* z, double* sliding = nullptr)
{
  BrushSteady steady(s.brushParameters());
  const ContactKinematics kin = ContactKinematics::fromSlips(Eigen::Vector2d(z[0], z[1]), z[2], m.chi_gamma, m.speed);
  const BrushForces f = steady.update(kin, 0.0);
  if (sliding)
    *sliding = f.sliding_fraction;
  return { f.F_x, f.F_y };
}

// The horizontal force on the robot in the ground frame: the brush force turned from the paper's contact frame, and
// the rolling resistance F_R L against the rolling direction.
Eigen::Vector2d groundForce(const Message& m, const Eigen::Vector2d& brush, double rolling_resistance)
{
  return contactToGround(m.heading, paper_frame::toRos(brush) - Eigen::Vector2d(rolling_resistance, 0.0));
}

// The rolling resistance F_R L at the message's speed with the settings' floor (Poeschel et al., eq. 18 solved
// exactly: the node's table interpolates this solution).
double rollingResistance(const EstimatorSettings& s, const Message& m)
{
  const CylinderExact cylinder(s.cylinderParameters());
  return cylinder.solve(m.speed).F_R * s.effective_length;
}

// The measured force against the model's at the message's latent (true) slips, in units of the force's noise.
//
// The brush's field depends on k and mu only through the slips scaled by k / mu, and its stresses scale with mu
// (the deflections are in units of mu q_z / k: BristleField), so F(k, mu; z) = mu G(z k / mu): the derivatives in
// log k and log mu are D = z . dF/dz and F - D, from the slips' derivatives at no further cost.
class ForceResidual : public ceres::CostFunction
{
public:
  ForceResidual(const Parameters& p, const Message& m) : p_(p), m_(m)
  {
    set_num_residuals(2);
    mutable_parameter_block_sizes()->push_back(p.size());
    mutable_parameter_block_sizes()->push_back(3);
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override
  {
    // a step outside the models' range (the solver's trial point) is refused: Ceres then takes a shorter one
    try
    {
      return evaluate(x, residuals, jacobians);
    }
    catch (const std::invalid_argument&)
    {
      return false;
    }
  }

private:
  bool evaluate(double const* const* x, double* residuals, double** jacobians) const
  {
    const EstimatorSettings s = p_.at(x[0]);
    const Eigen::Vector2d B = brushForce(s, m_, x[1]);
    const double rr = p_.floorFitted() ? rollingResistance(s, m_) : m_.rolling_resistance;
    const Eigen::Vector2d F = groundForce(m_, B, rr);
    residuals[0] = (m_.force.x() - F.x()) / m_.force_sd;
    residuals[1] = (m_.force.y() - F.y()) / m_.force_sd;
    if (!(std::isfinite(residuals[0]) && std::isfinite(residuals[1])))
      return false;
    if (!jacobians || (!jacobians[0] && !jacobians[1]))
      return true;
    Eigen::Matrix<double, 2, 3> dB;  // paper frame
    double z[3] = { x[1][0], x[1][1], x[1][2] };
    for (int j = 0; j < 3; ++j)
    {
      // forward differences over a tenth of the slip's noise: the derivative's own error then stays near a twentieth
      // of the force's curvature over that noise, and the steps cost three evaluations, not six
      const double h = std::max(kSlipStep * m_.sd[j], 1e-7);
      z[j] = x[1][j] + h;
      const Eigen::Vector2d up = brushForce(s, m_, z);
      z[j] = x[1][j];
      dB.col(j) = (up - B) / h;
    }
    const double inv = -1.0 / m_.force_sd;  // residual = (measured - model) / sd
    if (jacobians[1])
      for (int j = 0; j < 3; ++j)
      {
        const Eigen::Vector2d d = groundForce(m_, dB.col(j), 0.0) * inv;
        jacobians[1][j] = d.x();
        jacobians[1][3 + j] = d.y();
      }
    if (jacobians[0])
    {
      const int n = p_.size();
      const Eigen::Vector2d D = dB * Eigen::Vector3d(z[0], z[1], z[2]);
      for (int j = 0; j < n; ++j)
      {
        Eigen::Vector2d d;
        if (p_.parameter(j) == FitParameter::SurfaceDamping)
        {
          // the floor moves the rolling resistance only: a forward difference in log gamma (the exact solution costs
          // a few hundred ns)
          double xs[kMaxFitted];
          std::copy(x[0], x[0] + n, xs);
          xs[j] += kDampingStep;
          const double up = rollingResistance(p_.at(xs), m_);
          d = groundForce(m_, Eigen::Vector2d::Zero(), (up - rr) / kDampingStep) * inv;
        }
        else
        {
          const bool k = p_.parameter(j) == FitParameter::BristleStiffness;
          d = groundForce(m_, k ? D : Eigen::Vector2d(B - D), 0.0) * inv;
        }
        jacobians[0][j] = d.x();
        jacobians[0][n + j] = d.y();
      }
    }
    return true;
  }

  const Parameters& p_;
  const Message& m_;
};

// The latent slips against the measured ones, whitened by their covariance (errors in the inputs: without them a fit
// of noisy small slips finds the slip stiffness far too low, the noise diluting the slope).
class SlipPrior : public ceres::SizedCostFunction<3, 3>
{
public:
  explicit SlipPrior(const Message& m) : m_(m) {}
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override
  {
    const Eigen::Vector3d r = m_.prior * (Eigen::Map<const Eigen::Vector3d>(x[0]) - m_.slips);
    Eigen::Map<Eigen::Vector3d> out(residuals);
    out = r;
    if (jacobians && jacobians[0])
    {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(jacobians[0]);
      J = m_.prior;
    }
    return true;
  }

private:
  const Message& m_;
};

// One solve's outcome: the fitted parameters (log of their ratio to the settings') and each message's latent slips.
struct Solution
{
  std::vector<double> x;
  std::vector<Eigen::Vector3d> latent;
  ceres::Solver::Summary summary;
};

// One Levenberg-Marquardt solve from x over every stride-th message (the latent slips of the others stay at the
// measured ones), the latent slips starting at `latent` where given, else at the measured ones.
Solution solve(const std::vector<Message>& messages, const Parameters& params, const FitOptions& options,
               const std::vector<double>& x, const std::vector<Eigen::Vector3d>* latent, std::size_t stride,
               int& iterations)
{
  Solution out;
  out.x = x;
  out.latent.resize(messages.size());
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (std::size_t i = 0; i < messages.size(); ++i)
  {
    out.latent[i] = latent && latent->size() == messages.size() ? (*latent)[i] : messages[i].slips;
    if (i % stride != 0)
      continue;
    problem.AddResidualBlock(new ForceResidual(params, messages[i]), new ceres::HuberLoss(options.huber),
                             out.x.data(), out.latent[i].data());
    problem.AddResidualBlock(new SlipPrior(messages[i]), nullptr, out.latent[i].data());
  }
  for (int j = 0; j < params.size() && problem.NumResidualBlocks() > 0; ++j)
  {
    // the parameters within their ranges (x is the log of the ratio to the settings' value)
    const auto range = rangeOf(params.parameter(j), params.base());
    const double base = field(params.base(), params.parameter(j));
    problem.SetParameterLowerBound(out.x.data(), j, std::log(range.first / base));
    problem.SetParameterUpperBound(out.x.data(), j, std::log(range.second / base));
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_SCHUR;  // the latent slips eliminated: a system of the parameters alone
  so.max_num_iterations = options.max_iterations;
  so.num_threads = std::max(1, options.threads);  // the residuals are independent: each builds its own model
  so.logging_type = ceres::SILENT;
  so.function_tolerance = 1e-6;  // of the cost: the models' own error keeps it from settling much finer
  so.parameter_tolerance = 1e-8;
  ceres::Solve(so, &problem, &out.summary);
  iterations += static_cast<int>(out.summary.iterations.size());
  return out;
}

// One message's share of the parameters' information with its latent slips marginalised (the Schur complement of
// J^T J: A^T A - A^T B (B^T B + P^T P)^-1 B^T A, A and B the force residuals' derivatives in the parameters and the
// slips, P the prior's whitening) and of the chi-square (the force's residuals and the latent slips'). False where the
// model cannot be evaluated.
bool addInformation(const Parameters& params, const Message& m, const double* x, const Eigen::Vector3d& latent,
                    Eigen::MatrixXd& info, double& chi2, Eigen::Vector2d* residual = nullptr)
{
  const int n = params.size();
  ForceResidual f(params, m);
  const double* xs[2] = { x, latent.data() };
  double r[2];
  std::vector<double> A(2 * std::max(n, 1), 0.0);
  double B[6];
  double* jac[2] = { n > 0 ? A.data() : nullptr, B };
  if (!f.Evaluate(xs, r, jac))
    return false;
  chi2 += r[0] * r[0] + r[1] * r[1] + (m.prior * (latent - m.slips)).squaredNorm();
  if (residual)
    *residual = Eigen::Vector2d(r[0], r[1]);
  if (n > 0)
  {
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Am(A.data(), 2, n);
    const Eigen::Map<const Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> Bm(B);
    const Eigen::Matrix3d BB = Bm.transpose() * Bm + m.prior.transpose() * m.prior;
    const Eigen::MatrixXd BA = Bm.transpose() * Am;
    info += Am.transpose() * Am - BA.transpose() * BB.ldlt().solve(BA);
  }
  return true;
}

// The covariance of the parameters' logs from their information, widened by the reduced chi-square where that
// exceeds 1 (the IMU noisier than it said); infinite where the information is singular.
Eigen::MatrixXd covarianceOf(const Eigen::MatrixXd& info, double reduced_chi2)
{
  const int n = static_cast<int>(info.rows());
  Eigen::MatrixXd cov = Eigen::MatrixXd::Constant(n, n, std::numeric_limits<double>::infinity());
  if (n > 0)
  {
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(info);
    if (ldlt.info() == Eigen::Success && ldlt.isPositive() && info.diagonal().minCoeff() > 0.0)
      cov = ldlt.solve(Eigen::MatrixXd::Identity(n, n)) * std::max(1.0, reduced_chi2);
  }
  return cov;
}

// The stiffness fitted with friction held at mu, over every stride-th message: a point of the profile of the fit's
// cost over mu, where the data give mu only a bound.
struct ProfilePoint
{
  double mu = 0.0, k = 0.0;
  double damping = 0.0;  // the floor's, fitted with k where asked, else the start's
  double sd = std::numeric_limits<double>::infinity();  // of k, widened by the reduced chi-square
  double cost = std::numeric_limits<double>::infinity();  // Ceres' (half the robust sum of squares)
  double reduced_chi2 = 0.0;
  double sliding = 0.0;  // the largest sliding share of the patch over the messages, at the fit
  bool usable = false;
  std::vector<Eigen::Vector3d> latent;  // the messages' latent slips at the fit (a neighbouring point's start)
};

// start: the settings with the other parameters' starting values (k first, the floor's damping where with_floor).
ProfilePoint profileAt(const std::vector<Message>& messages, const EstimatorSettings& start, double mu, bool with_floor,
                       const FitOptions& options, std::size_t stride, int& iterations,
                       const std::vector<Eigen::Vector3d>* latent = nullptr)
{
  ProfilePoint p;
  p.mu = mu;
  EstimatorSettings s = start;
  s.friction = mu;
  const double k_start = s.bristle_stiffness;
  std::vector<FitParameter> others{ FitParameter::BristleStiffness };
  if (with_floor)
    others.push_back(FitParameter::SurfaceDamping);
  const Parameters params(s, others);
  const int n = params.size();
  Solution sol = solve(messages, params, options, std::vector<double>(n, 0.0), latent, stride, iterations);
  if (!sol.summary.IsSolutionUsable())
    return p;
  p.usable = true;
  p.cost = sol.summary.final_cost;
  p.k = k_start * std::exp(sol.x[0]);
  const EstimatorSettings at = params.at(sol.x.data());
  p.damping = at.surface_damping;
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(n, n);
  double chi2 = 0.0;
  int used = 0;
  for (std::size_t i = 0; i < messages.size(); i += stride)
  {
    if (!addInformation(params, messages[i], sol.x.data(), sol.latent[i], info, chi2))
      continue;
    ++used;
    double sliding = 0.0;
    brushForce(at, messages[i], sol.latent[i].data(), &sliding);
    p.sliding = std::max(p.sliding, sliding);
  }
  p.reduced_chi2 = chi2 / std::max(1, 2 * used - n);
  p.latent = std::move(sol.latent);
  p.sd = p.k * std::sqrt(covarianceOf(info, p.reduced_chi2)(0, 0));
  return p;
}

// Why message i stays out of the fit; Rejection::Count where it enters.
Rejection rejectionOf(const CalibrationSample& s, const Prediction& p, std::size_t i)
{
  if (!s.has_force || !(s.force_sd > 0.0))
    return Rejection::NoImu;
  if (!p.answered[i])
    return Rejection::Unanswered;
  if (p.flags[i] & (estimate_flags::kGapReset | estimate_flags::kTimeJumpReset))
    return Rejection::Reset;
  if (p.flags[i] & estimate_flags::kStandstill)
    return Rejection::Standstill;
  if (p.flags[i] & estimate_flags::kMotionWithinNoise)
    return Rejection::WithinNoise;
  return Rejection::Count;
}
}  // namespace

const char* toString(Rejection r)
{
  switch (r)
  {
    case Rejection::NoImu:
      return "no IMU sample paired";
    case Rejection::Unanswered:
      return "input refused by the estimator";
    case Rejection::Standstill:
      return "standstill (slips undefined)";
    case Rejection::Reset:
      return "state reset (gap or time jump)";
    case Rejection::WithinNoise:
      return "motion within the odometry's noise (parked)";
    case Rejection::Transient:
      return "speed changing within a patch transit";
    case Rejection::Count:
      break;
  }
  return "?";
}

double parameterValue(const EstimatorSettings& s, FitParameter p)
{
  return field(s, p);
}

const char* parameterName(FitParameter p)
{
  switch (p)
  {
    case FitParameter::BristleStiffness:
      return "bristle_stiffness";
    case FitParameter::Friction:
      return "friction";
    case FitParameter::SurfaceDamping:
      return "surface_damping";
    case FitParameter::Count:
      break;
  }
  return "?";
}

bool FitResult::mismatch() const
{
  return used > 0 && residual_autocorrelation.maxCoeff() > mismatchThreshold(used);
}

double FitResult::mismatchThreshold(int used)
{
  // Independent residuals would stay within 4 / sqrt(n); the fit's are not quite: their spread is far larger where the
  // patch slides than where the latent slips absorb the noise, and runs of the model showed up to 0.19 (100 seeds,
  // median 0.03), runs with an IMU bias or another pressure distribution at least 0.58 (10 runs)
  return std::max(4.0 / std::sqrt(static_cast<double>(std::max(used, 1))), kMismatchAutocorrelation);
}

Prediction predictForces(const std::vector<CalibrationSample>& samples, const EstimatorSettings& settings)
{
  ContactEstimator estimator(settings);
  Prediction p;
  const std::size_t n = samples.size();
  p.force.assign(n, Eigen::Vector2d::Zero());
  p.sliding.assign(n, 0.0);
  p.slip.assign(n, Eigen::Vector2d::Zero());
  p.spin.assign(n, 0.0);
  p.tilt_ratio.assign(n, 1.0);
  p.speed.assign(n, 0.0);
  p.heading.assign(n, 0.0);
  p.rolling_resistance.assign(n, 0.0);
  p.flags.assign(n, 0u);
  p.answered.assign(n, 0u);
  for (std::size_t i = 0; i < n; ++i)
  {
    const ContactEstimateData* e = estimator.update(samples[i].input);
    if (!e)
      continue;
    p.answered[i] = 1;
    p.force[i] = robotForce(*e);
    p.sliding[i] = e->brush.sliding_fraction;
    p.slip[i] = e->slip;
    p.spin[i] = e->spin;
    p.tilt_ratio[i] = e->tilt_ratio;
    p.speed[i] = e->rolling_speed;
    p.heading[i] = e->heading;
    p.rolling_resistance[i] = e->rolling_resistance_force;
    p.flags[i] = e->flags;
  }
  return p;
}

namespace
{
// Where the run gives friction only a bound, the stiffness depends on the friction it is fitted with (the patch's
// partial sliding bends the force-slip curve the more, the lower mu), and a stiffness fitted at one held mu misses the
// truth by many of its standard deviations where that mu is off. The profile of the fit's cost over mu >= the bound
// tells which mu the forces' shape allows: a likelihood-ratio set, twice the cost within 3.84 (chi-square, one degree,
// 95 %) times the reduced chi-square of its minimum.
//
// The profile is taken over a subset of a long run's messages (as the first solve: fewer messages, a wider set): at the
// free fit's mu (in the set: its cost is the lowest), at the bound and at friction's largest value, then halved (in log
// mu) across the set's edges. The cost is taken to have one minimum over mu (the set an interval), the stiffness to
// change monotonically between neighbouring points (its fits decrease with mu: the less the patch slides, the less
// stiffness the same forces need).
class FrictionProfile
{
public:
  static constexpr double kMuMax = kFrictionMax;

  /// result: the free fit's settings (the points' first starts); iterations: the solves' count, added to
  FrictionProfile(const std::vector<Message>& messages, const EstimatorSettings& base, const EstimatorSettings& result,
                  const FitOptions& options, bool with_floor, int& iterations)
    : messages_(messages)
    , base_(base)
    , result_(result)
    , options_(options)
    , with_floor_(with_floor)
    , stride_(std::max<std::size_t>(1, messages.size() / kSubsetMessages))
    , iterations_(iterations)
  {
  }

  /// The first points: at the free fit's mu, at the bound and at friction's largest value.
  void start(double bound)
  {
    const double mu_low = std::min(kMuMax, std::max(bound, kFrictionMin));  // friction's range: 1e-3 to 100
    const double mu_free = std::min(kMuMax, std::max(mu_low, result_.friction));
    profile_.push_back(fit(mu_free, nullptr));
    if (mu_low < mu_free)
      profile_.insert(profile_.begin(), fit(mu_low, &profile_.front()));
    if (mu_free < kMuMax)
      profile_.push_back(fit(kMuMax, &profile_[profile_.size() - 1]));
    findBest();
  }

  /// The cost's least point was fitted.
  bool usable() const { return profile_[best_].usable; }

  /// Between points the set's edge, and the stiffness with it, may lie anywhere: each step across the edge halved until
  /// the stiffness changes by less than kStepInSd of its sd across it; past kMaxProfile points the step's far end is
  /// taken in whole (coarse_: wider, not narrower).
  void refine()
  {
    constexpr double kStepInSd = 0.5;
    constexpr std::size_t kMaxProfile = 40;
    for (bool refined = true; refined;)
    {
      refined = false;
      for (std::size_t i = 0; i + 1 < profile_.size(); ++i)
      {
        const ProfilePoint &p = profile_[i], &q = profile_[i + 1];
        if (inSet(p) == inSet(q) || !p.usable || !q.usable ||
            std::abs(p.k - q.k) <= kStepInSd * std::min(p.sd, q.sd) || q.mu <= p.mu * (1.0 + 1e-6))
          continue;
        if (profile_.size() >= kMaxProfile)
        {
          coarse_.emplace_back(p.k, q.k);
          continue;
        }
        ProfilePoint mid = fit(std::sqrt(p.mu * q.mu), inSet(p) ? &p : &q);
        profile_.insert(profile_.begin() + static_cast<std::ptrdiff_t>(i) + 1, std::move(mid));
        findBest();
        refined = true;
        break;
      }
    }
  }

  /// The set's ends over mu; open: it reaches friction's largest value (any mu above its lower end fits).
  void muRange(double& lo, double& hi, bool& open) const
  {
    open = profile_.back().mu >= kMuMax && inSet(profile_.back());
    lo = std::numeric_limits<double>::infinity();
    hi = 0.0;
    for (const ProfilePoint& p : profile_)
      if (inSet(p))
      {
        lo = std::min(lo, p.mu);
        hi = std::max(hi, p.mu);
      }
  }

  /// The point at mu: the profile's own where it has one there, else fitted from the nearest (not added to it);
  /// k_nearest: that nearest point's stiffness.
  ProfilePoint at(double mu, double& k_nearest)
  {
    std::size_t nearest = best_;
    for (std::size_t j = 0; j < profile_.size(); ++j)
      if (profile_[j].usable &&
          std::abs(std::log(profile_[j].mu / mu)) < std::abs(std::log(profile_[nearest].mu / mu)))
        nearest = j;
    k_nearest = profile_[nearest].k;
    return profile_[nearest].mu == mu ? profile_[nearest] : fit(mu, &profile_[nearest]);
  }

  /// The stiffness's span over the set, its fits carried to the whole run (times shift, their sd times narrow and
  /// shift), each within its 95 % interval; the coarse steps' ends count whole. Widens [lo, hi].
  void stiffnessSpan(double shift, double narrow, double& lo, double& hi) const
  {
    for (const ProfilePoint& p : profile_)
      if (inSet(p))
      {
        const double sd = std::isfinite(p.sd) ? p.sd * narrow * shift : std::numeric_limits<double>::infinity();
        lo = std::min(lo, p.k * shift - kInterval95 * sd);
        hi = std::max(hi, p.k * shift + kInterval95 * sd);
      }
    for (const auto& step : coarse_)
    {
      lo = std::min({ lo, step.first * shift, step.second * shift });
      hi = std::max({ hi, step.first * shift, step.second * shift });
    }
  }

private:
  static constexpr double kChi2One95 = 3.841;  // chi-square with one degree of freedom, 95 % quantile

  void findBest()
  {
    best_ = 0;
    for (std::size_t j = 1; j < profile_.size(); ++j)
      if (profile_[j].usable && (!profile_[best_].usable || profile_[j].cost < profile_[best_].cost))
        best_ = j;
  }
  bool inSet(const ProfilePoint& p) const
  {
    return p.usable &&
           p.cost <= profile_[best_].cost + 0.5 * kChi2One95 * std::max(1.0, profile_[best_].reduced_chi2);
  }
  // a point fitted at mu, starting from a neighbouring point's fit where it has one, else the free fit's
  ProfilePoint fit(double mu, const ProfilePoint* near)
  {
    EstimatorSettings start = base_;
    start.bristle_stiffness = near && near->usable ? near->k : result_.bristle_stiffness;
    start.surface_damping = near && near->usable ? near->damping : result_.surface_damping;
    return profileAt(messages_, start, mu, with_floor_, options_, stride_, iterations_,
                     near && near->usable ? &near->latent : nullptr);
  }

  const std::vector<Message>& messages_;
  const EstimatorSettings& base_;
  const EstimatorSettings& result_;
  const FitOptions& options_;
  const bool with_floor_;
  const std::size_t stride_;
  int& iterations_;
  std::vector<ProfilePoint> profile_;  // in increasing mu
  std::size_t best_ = 0;               // the least cost's point
  std::vector<std::pair<double, double>> coarse_;  // steps left unresolved: their ends' stiffness both count
};

// The settings hold mu at the file's value or the nearest the data allow, with the stiffness fitted at it; the
// stiffness's interval spans its fits over the set FrictionProfile finds.
FitResult fitWithFrictionBounded(const std::vector<CalibrationSample>& samples, const EstimatorSettings& settings,
                                 const FitOptions& options, const std::vector<Message>& messages,
                                 const EstimatorSettings& base, const EstimatorSettings& result, const FitResult& free)
{
  const FittedValue& mu = free.values[static_cast<int>(FitParameter::Friction)];
  const bool with_floor = free.values[static_cast<int>(FitParameter::SurfaceDamping)].fitted;
  const double bound = mu.lower_bound;
  int iterations = free.iterations;
  FrictionProfile profile(messages, base, result, options, with_floor, iterations);
  profile.start(bound);
  FitOptions again = options;
  again.fit[static_cast<int>(FitParameter::Friction)] = false;
  EstimatorSettings held = settings;
  held.friction = std::max(settings.friction, bound);
  // the result's friction: the free fit's bound, at the value the others were fitted with
  const auto holdFriction = [&](FitResult& second, const std::string& note) {
    FittedValue& m = second.values[static_cast<int>(FitParameter::Friction)];
    m = mu;
    m.value = held.friction;
    m.sd = 0.0;
    m.low = bound;
    m.high = std::numeric_limits<double>::infinity();
    m.note = note;
    second.settings.friction = held.friction;  // the file's, or the nearest value the run allows
    second.iterations += iterations;
  };
  if (!profile.usable())
  {
    FitResult second = fitContact(samples, held, again);
    FittedValue& k = second.values[static_cast<int>(FitParameter::BristleStiffness)];
    k.determined = false;
    k.note = "fitted with mu held at " + std::to_string(held.friction) + ", which the data give only as a bound";
    k.low = 0.0;
    k.high = std::numeric_limits<double>::infinity();
    holdFriction(second, mu.note);
    return second;
  }
  profile.refine();
  double mu_lo, mu_hi;
  bool open;
  profile.muRange(mu_lo, mu_hi, open);
  // mu for the node: the file's (or the bound), moved to the nearest the forces allow
  held.friction = std::max(held.friction, mu_lo);
  if (!open)
    held.friction = std::min(held.friction, mu_hi);
  double k_nearest;
  const ProfilePoint h = profile.at(held.friction, k_nearest);
  // the stiffness with mu held, every message (the profile's value there a start close to the answer)
  held.bristle_stiffness = h.usable ? h.k : k_nearest;
  FitResult second = fitContact(samples, held, again);
  FittedValue& k = second.values[static_cast<int>(FitParameter::BristleStiffness)];
  k.start = settings.bristle_stiffness;
  if (!k.determined)
    second.settings.bristle_stiffness = settings.bristle_stiffness;  // the file's, not the profile's start
  // k's interval spans its fits over the set: the subset's, carried to the whole run by the ratios of the whole run's
  // fit at the held mu to the subset's there (the value's, and the sd's: a subset of n / stride messages has one
  // about sqrt(stride) wider), so that no further solve over every message is needed
  const double shift = h.usable ? k.value / h.k : 1.0;
  const double narrow = h.usable && std::isfinite(h.sd) && h.sd > 0.0 ? std::min(1.0, k.sd / h.sd) : 1.0;
  double k_lo = k.low, k_hi = k.high;
  profile.stiffnessSpan(shift, narrow, k_lo, k_hi);
  k.low = std::max(0.0, k_lo);
  k.high = k_hi;
  const std::string range = open ? "mu >= " + formatValue(mu_lo) : "mu from " + formatValue(mu_lo) + " to " +
                                                                         formatValue(mu_hi);
  if (k.determined && 0.5 * (k.high - k.low) > kInterval95 * options.determined_sd * k.value)
  {
    k.determined = false;
    k.note = "it depends on mu, which the run gives only as a bound: k from " + formatValue(k.low) + " to " +
             formatValue(k.high) + " over " + range + " (what the forces allow)";
    second.settings.bristle_stiffness = settings.bristle_stiffness;
  }
  else if (k.determined)
    k.note = "over " + range + " (what the forces allow; mu only a bound)";
  holdFriction(second, mu.note + "; the forces' shape allows " + range + "; held at " + formatValue(held.friction) +
                           " for the others");
  return second;
}
// Each message's lag of the steady state: 2a |dV_r/dt| / V_r^2, the rolling speed's rate by a least-squares line over
// the window around it (infinite where the sphere does not roll).
std::vector<double> steadyLag(const std::vector<CalibrationSample>& samples, const Prediction& first, double a,
                              const FitOptions& options)
{
  std::vector<double> lag(samples.size(), 0.0);
  for (std::size_t i = 0, lo = 0, hi = 0; i < samples.size(); ++i)
  {
    const double t = samples[i].input.stamp;
    while (lo < i && samples[lo].input.stamp < t - options.lag_window)
      ++lo;
    hi = std::max(hi, i);
    while (hi + 1 < samples.size() && samples[hi + 1].input.stamp <= t + options.lag_window)
      ++hi;
    double st = 0.0, sv = 0.0, stt = 0.0, stv = 0.0;
    int n_window = 0;
    for (std::size_t j = lo; j <= hi; ++j)
      if (first.answered[j])
      {
        const double dt = samples[j].input.stamp - t, v = first.speed[j];
        st += dt, sv += v, stt += dt * dt, stv += dt * v;
        ++n_window;
      }
    const double det = n_window * stt - st * st;
    const double rate = n_window >= 3 && det > 0.0 ? (n_window * stv - st * sv) / det : 0.0;
    const double v = first.speed[i];
    lag[i] = v > 0.0 ? 2.0 * a * std::abs(rate) / (v * v) : std::numeric_limits<double>::infinity();
  }
  return lag;
}

// The messages that enter the fit, each with its measured slips and their whitening prior; why the others stay out
// (out.rejected, out.rejection) and which entered (out.used_mask, out.used).
std::vector<Message> selectMessages(const std::vector<CalibrationSample>& samples, const Prediction& first,
                                    const std::vector<double>& lag, const EstimatorSettings& base,
                                    const FitOptions& options, FitResult& out)
{
  out.used_mask.assign(samples.size(), 0u);
  out.rejection.assign(samples.size(), Rejection::Count);
  out.residuals.assign(samples.size(), Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
  std::vector<Message> messages;
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    Rejection r = rejectionOf(samples[i], first, i);
    if (r == Rejection::Count && lag[i] > options.max_lag)
      r = Rejection::Transient;
    if (r != Rejection::Count)
    {
      ++out.rejected[static_cast<int>(r)];
      out.rejection[i] = r;
      continue;
    }
    const CalibrationSample& cs = samples[i];
    Message m;
    m.index = static_cast<int>(i);
    const Eigen::Vector2d sigma = paper_frame::fromRos(first.slip[i]);
    m.slips = Eigen::Vector3d(sigma.x(), sigma.y(), paper_frame::zFromRos(first.spin[i]));
    m.chi_gamma = first.tilt_ratio[i];
    m.speed = first.speed[i];
    m.heading = first.heading[i];
    m.rolling_resistance = first.rolling_resistance[i];
    m.force = cs.force;
    m.force_sd = cs.force_sd;
    // the slips' covariance from the odometry's (the slips' Jacobian at the measured twist)
    const Eigen::Matrix<double, 4, 5> J =
        slipJacobian(cs.input.omega, cs.input.v_contact.head<2>(), base.rolling_radius, m.heading);
    Eigen::Matrix3d C = J.topRows<3>() * usedTwistCovariance(cs.input.twist_covariance) * J.topRows<3>().transpose();
    // exact inputs (no covariance declared) hold the slips: a floor far below any noise keeps the prior invertible
    for (int k = 0; k < 3; ++k)
      C(k, k) += 1e-16 + 1e-12 * C(k, k);
    const Eigen::LLT<Eigen::Matrix3d> llt(C);
    if (llt.info() != Eigen::Success)
      continue;
    const Eigen::Matrix3d L = llt.matrixL();
    m.prior = L.inverse();
    m.sd = C.diagonal().cwiseSqrt();
    messages.push_back(m);
    out.used_mask[i] = 1;
    ++out.used;
  }
  return messages;
}

// The best of the solves from several starts: the file's values, and below and above them (exp(x) times the file's).
// A long run is solved first on a subset of its messages (what the parameters need comes from a few hundred), then
// whole from there: the whole run's solve then starts close and takes a few iterations.
Solution solveFromStarts(const std::vector<Message>& messages, const Parameters& params, const FitOptions& options,
                         int& iterations)
{
  const int n = params.size();
  Solution best;
  best.x.assign(n, 0.0);
  double best_cost = std::numeric_limits<double>::infinity();
  const std::size_t stride = std::max<std::size_t>(1, messages.size() / kSubsetMessages);
  for (double factor : { 1.0, 1.0 / options.start_spread, options.start_spread })
  {
    if (n == 0)
      break;
    std::vector<double> x(n, std::log(factor));
    if (stride > 1)
    {
      const Solution subset = solve(messages, params, options, x, nullptr, stride, iterations);
      if (subset.summary.IsSolutionUsable())
        x = subset.x;
    }
    Solution whole = solve(messages, params, options, x, nullptr, 1, iterations);
    if (whole.summary.IsSolutionUsable() && whole.summary.final_cost < best_cost)
    {
      best_cost = whole.summary.final_cost;
      best = std::move(whole);
    }
    // the file's values converged to a minimum no other start improves on: enough where the fit is well posed
    if (factor == 1.0 && best.summary.termination_type == ceres::CONVERGENCE)
    {
      bool inside = true;
      for (int j = 0; j < n; ++j)
        inside = inside && std::abs(best.x[j]) < std::log(options.start_spread);
      if (inside)
        break;
    }
  }
  return best;
}

// At the fit: each used message's information on the parameters (the latent slips marginalised) and its residual
// (out.residuals), and what the used messages covered (speeds, slips, sliding, the largest force for sure). Returns
// how many slide over options.sliding_share of the patch.
int gatherInformation(const std::vector<Message>& messages, const Parameters& params, const Solution& best,
                      const FitOptions& options, FitResult& out, Eigen::MatrixXd& info, double& chi2)
{
  int sliding_samples = 0;
  bool first_used = true;
  // the largest force the run shows for sure: less than the largest of N noisy readings can reach by noise alone
  // (the maximum of N standard normals stays below sqrt(2 ln N) + 2 but for a share far below a percent)
  const double margin = std::sqrt(2.0 * std::log(std::max<double>(2.0, static_cast<double>(messages.size())))) + 2.0;
  for (std::size_t i = 0; i < messages.size(); ++i)
  {
    const Message& m = messages[i];
    const Eigen::Vector3d& latent = best.latent.empty() ? m.slips : best.latent[i];
    Eigen::Vector2d& residual = out.residuals[static_cast<std::size_t>(m.index)];
    if (!addInformation(params, m, best.x.data(), latent, info, chi2, &residual))
      continue;
    const std::size_t k = static_cast<std::size_t>(m.index);
    const double v = out.fitted.speed[k];
    out.speed_min = first_used ? v : std::min(out.speed_min, v);
    out.speed_max = first_used ? v : std::max(out.speed_max, v);
    first_used = false;
    out.slip_max = std::max(out.slip_max, out.fitted.slip[k].norm());
    out.sliding_max = std::max(out.sliding_max, out.fitted.sliding[k]);
    out.force_max = std::max(out.force_max, m.force.norm() - margin * std::sqrt(2.0) * m.force_sd);
    if (out.fitted.sliding[k] >= options.sliding_share)
      ++sliding_samples;
  }
  return sliding_samples;
}

// The residuals' streaks: lag-1 autocorrelation on each axis over the used messages in order.
Eigen::Vector2d residualAutocorrelation(const std::vector<Eigen::Vector2d>& residuals)
{
  Eigen::Vector2d out = Eigen::Vector2d::Zero();
  for (int axis = 0; axis < 2; ++axis)
  {
    std::vector<double> v;
    for (const Eigen::Vector2d& r : residuals)
      if (r.allFinite())
        v.push_back(r[axis]);
    if (v.size() < 3)
      continue;
    double mean = 0.0;
    for (double x : v)
      mean += x;
    mean /= static_cast<double>(v.size());
    double num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i)
    {
      den += (v[i] - mean) * (v[i] - mean);
      if (i + 1 < v.size())
        num += (v[i] - mean) * (v[i + 1] - mean);
    }
    out[axis] = den > 0.0 ? num / den : 0.0;
  }
  return out;
}

// One fitted parameter (the k-th of the solve) at the fit: its value, sd and interval from the covariance, and whether
// the data determine it, or why not (no convergence, too wide, mu without sliding, pressed against its range).
FittedValue fittedValue(FitParameter parameter, int k, const EstimatorSettings& base, const EstimatorSettings& result,
                        const Eigen::MatrixXd& cov, const FitResult& out, const FitOptions& options,
                        int sliding_samples)
{
  FittedValue v;
  v.parameter = parameter;
  v.start = field(base, parameter);
  v.fitted = true;
  v.value = field(result, parameter);
  v.sd = v.value * std::sqrt(std::max(0.0, cov(k, k)));  // sd of the log times the value
  v.low = v.value - kInterval95 * v.sd;
  v.high = v.value + kInterval95 * v.sd;
  v.determined = out.converged && std::isfinite(v.sd) && v.sd <= options.determined_sd * v.value;
  if (!out.converged)
    v.note = "the fit did not converge";
  else if (!v.determined)
    v.note = "the data do not determine it (sd above " + std::to_string(static_cast<int>(100 * options.determined_sd)) +
             " % of the value)";
  if (parameter == FitParameter::Friction && sliding_samples < FitOptions::kMinSlidingSamples)
  {
    // without sliding, friction only bounds the forces seen: mu F_z >= |F_t| wherever the patch sticks
    v.determined = false;
    v.lower_bound = out.force_max / base.verticalLoad();
    v.note = "the run never slides (at most " + std::to_string(static_cast<int>(100 * out.sliding_max + 0.5)) +
             " % of the patch): mu is only bounded below";
  }
  const auto range = rangeOf(parameter, result);
  if (v.value <= range.first * (1.0 + 1e-6) || v.value >= range.second * (1.0 - 1e-6))
  {
    // pressed against its range: the data push it beyond what the parameter can be (a run that is not the model's)
    v.determined = false;
    v.note = "at the edge of its range [" + formatValue(range.first) + ", " + formatValue(range.second) +
             "]: the data push it beyond (a run that is not the model's?)";
  }
  if (parameter == FitParameter::SurfaceDamping && v.determined)
    v.note = "with surface_stiffness held: the floor's relaxation time gamma/k_s = " +
             formatValue(v.value / base.surface_stiffness) + " s";
  return v;
}
}  // namespace

FitResult fitContact(const std::vector<CalibrationSample>& samples, const EstimatorSettings& settings,
                     const FitOptions& options)
{
  FitResult out;
  out.samples = static_cast<int>(samples.size());
  EstimatorSettings base = settings;
  base.accuracy_target = std::min(settings.accuracy_target, options.accuracy_target);
  base.auto_noise_fraction = 0.0;    // the models' accuracy is the fit's, not the noise's
  // (the flag of a parked robot, kMotionWithinNoise, no longer needs it; kept, so that the covariance's share of the work
  // budget, and with it the brush answers the fit is made of, stays as it was)
  base.propagate_covariance = true;
  // each message's forces are held against its IMU sample: every motion moves the bristles as measured (those within
  // the noise stay out of the fit anyway, kMotionWithinNoise)
  base.hold_within_noise = false;
  std::vector<FitParameter> fitted;
  for (int j = 0; j < kParameters; ++j)
    if (options.fit[j] && !(static_cast<FitParameter>(j) == FitParameter::SurfaceDamping &&
                            settings.rolling_resistance_model == CylinderModelKind::Off))
      fitted.push_back(static_cast<FitParameter>(j));

  // which messages enter, and what the fit keeps of them: the flags and the frame do not depend on the parameters
  EstimatorSettings kinematic = base;
  kinematic.brush_model = BrushModelKind::Off;  // the flags and the frame are the kinematics': no brush needed here
  const Prediction first = predictForces(samples, kinematic);
  const std::vector<double> lag = steadyLag(samples, first, base.brushParameters().a, options);
  const std::vector<Message> messages = selectMessages(samples, first, lag, base, options, out);
  if (out.used == 0)
    throw std::invalid_argument("calibration: no sample can enter the fit (each was rejected; see the counts)");

  const Parameters params(base, fitted);
  const int n = params.size();
  const Solution best = solveFromStarts(messages, params, options, out.iterations);

  // the parameters' covariance with the latent slips marginalised, and what the used messages covered
  EstimatorSettings result = params.at(best.x.data());
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(n, n);
  double chi2 = 0.0;
  out.fitted = predictForces(samples, result);
  const int sliding_samples = gatherInformation(messages, params, best, options, out, info, chi2);
  out.residual_autocorrelation = residualAutocorrelation(out.residuals);
  out.converged = n == 0 || best.summary.termination_type == ceres::CONVERGENCE;
  // five residuals and three latent slips a message: two degrees of freedom each, less the parameters
  const int dof = std::max(1, 2 * out.used - n);
  out.reduced_chi2 = chi2 / dof;
  const Eigen::MatrixXd cov = covarianceOf(info, out.reduced_chi2);
  out.correlation = Eigen::MatrixXd::Identity(n, n);
  out.correlated = fitted;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (a != b && std::isfinite(cov(a, b)) && cov(a, a) > 0.0 && cov(b, b) > 0.0)
        out.correlation(a, b) = cov(a, b) / std::sqrt(cov(a, a) * cov(b, b));

  for (int j = 0; j < kParameters; ++j)
  {
    const FitParameter parameter = static_cast<FitParameter>(j);
    const auto it = std::find(fitted.begin(), fitted.end(), parameter);
    if (it != fitted.end())
    {
      out.values.push_back(fittedValue(parameter, static_cast<int>(it - fitted.begin()), base, result, cov, out,
                                       options, sliding_samples));
      continue;
    }
    FittedValue v;
    v.parameter = parameter;
    v.start = field(base, parameter);
    v.value = v.start;
    if (parameter == FitParameter::SurfaceDamping && options.fit[j])
      v.note = "not fitted: rolling_resistance_model is off";
    out.values.push_back(v);
  }
  // the settings: the file's, with the determined values
  out.settings = settings;
  for (const FittedValue& v : out.values)
    if (v.fitted && v.determined)
      field(out.settings, v.parameter) = v.value;

  // friction only a bound: k's interval over every mu the forces allow (the profile fits k, so only where k is asked
  // for; with friction and the floor alone, the floor's sd from the free fit already marginalises mu)
  const FittedValue& mu = out.values[static_cast<int>(FitParameter::Friction)];
  if (mu.fitted && mu.lower_bound > 0.0 && out.values[static_cast<int>(FitParameter::BristleStiffness)].fitted)
    return fitWithFrictionBounded(samples, settings, options, messages, base, result, out);
  return out;
}

}  // namespace sphere_contact_estimator
