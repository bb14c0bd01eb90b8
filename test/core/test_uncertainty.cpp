// Uncertainty (issue 13): the unscented transform and the covariance checks; the brush forces' covariance from the
// slips' (the linear model's J Sigma J^T to rounding, the steady model's unscented transform against Monte Carlo);
// the cylinder's spread in the speed; the twist covariance through the estimator against Monte Carlo in the twist,
// with every kind of bad covariance; auto below the noise.

// STL
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <vector>

// Eigen
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

// GTest
#include <gtest/gtest.h>

// Package
#include "brush_test_support.h"
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "sphere_contact_estimator/core/brush/force_covariance.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"
#include "sphere_contact_estimator/core/estimator/standstill_covariance.h"
#include "sphere_contact_estimator/core/numerics/covariance.h"
#include "sphere_contact_estimator/core/numerics/unscented_transform.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_spread.h"
#include "sample_covariance.h"

namespace sphere_contact_estimator
{
namespace
{
// The sample covariance of f(x) for x ~ N(mean, P), n draws from rng.
template <int N, int M>
Eigen::Matrix<double, M, M> monteCarlo(const Eigen::Matrix<double, N, 1>& mean, const Eigen::Matrix<double, N, N>& P,
                                       const std::function<Eigen::Matrix<double, M, 1>(const Eigen::Matrix<double, N, 1>&)>& f,
                                       int n, std::mt19937_64& rng)
{
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(P);
  const Eigen::Matrix<double, N, N> root =
      eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Eigen::Matrix<double, M, 1>> y;
  for (int i = 0; i < n; ++i)
  {
    Eigen::Matrix<double, N, 1> z;
    for (int k = 0; k < N; ++k)
      z(k) = g(rng);
    y.push_back(f(mean + root * z));
  }
  return sampleCovariance(y);
}

// Standard deviations within `sd_tolerance` (relative) and correlations within `corr_tolerance` where the
// reference's standard deviation is above `floor` (the scale of each output).
template <int M>
void expectClose(const Eigen::Matrix<double, M, M>& got, const Eigen::Matrix<double, M, M>& ref,
                 const Eigen::Matrix<double, M, 1>& floor, double sd_tolerance, double corr_tolerance,
                 const std::string& where)
{
  const Eigen::Matrix<double, M, 1> a = got.diagonal().cwiseMax(0.0).cwiseSqrt(), b = ref.diagonal().cwiseSqrt();
  for (int i = 0; i < M; ++i)
  {
    if (!(b(i) > floor(i)))
      continue;
    EXPECT_NEAR(a(i) / b(i), 1.0, sd_tolerance) << where << ": sd of output " << i;
    for (int j = i + 1; j < M; ++j)
    {
      if (b(j) > floor(j) && a(i) > 0.0 && a(j) > 0.0)
      {
        EXPECT_NEAR(got(i, j) / (a(i) * a(j)), ref(i, j) / (b(i) * b(j)), corr_tolerance)
            << where << ": correlation " << i << "-" << j;
      }
    }
  }
}

TEST(UnscentedTransform, ExactForLinearMapsAndTheMeanOfQuadraticOnes)
{
  Eigen::Matrix3d L;
  L << 1.0, 0.0, 0.0, 0.3, 2.0, 0.0, -0.5, 0.1, 0.7;
  const Eigen::Matrix3d P = L * L.transpose();
  const Eigen::Vector3d m(0.2, -1.0, 3.0);
  Eigen::Matrix<double, 2, 3> A;
  A << 1.0, -2.0, 0.5, 0.0, 3.0, 1.0;
  const auto linear = unscentedTransform<3, 2>(m, P, [&](const Eigen::Vector3d& x) { return Eigen::Vector2d(A * x); });
  EXPECT_LT((linear.mean - A * m).norm(), 1e-12);
  EXPECT_LT((linear.covariance - A * P * A.transpose()).norm(), 1e-11);
  EXPECT_EQ(linear.evaluations, 6);  // kappa = 0: the mean is not evaluated
  // E[x^T x] = m^T m + tr P
  const auto quadratic = unscentedTransform<3, 1>(
      m, P, [](const Eigen::Vector3d& x) { return Eigen::Matrix<double, 1, 1>(x.squaredNorm()); });
  EXPECT_NEAR(quadratic.mean(0), m.squaredNorm() + P.trace(), 1e-11);
}

TEST(UnscentedTransform, SemiDefiniteAndZeroCovariances)
{
  // a variable known exactly and a perfectly correlated pair: sigma points only along the spread, f at the mean
  // once for the rest
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  P(0, 0) = P(1, 1) = P(0, 1) = P(1, 0) = 4.0;
  int calls = 0;
  const auto u = unscentedTransform<3, 1>(Eigen::Vector3d::Zero(), P, [&](const Eigen::Vector3d& x) {
    ++calls;
    return Eigen::Matrix<double, 1, 1>(x(0) + x(1) + 10.0 * x(2));
  });
  EXPECT_EQ(calls, u.evaluations);
  EXPECT_EQ(u.evaluations, 3);
  EXPECT_NEAR(u.covariance(0, 0), 16.0, 1e-12);  // var(x0 + x1) = 4 + 4 + 2 * 4
  const auto zero = unscentedTransform<3, 1>(Eigen::Vector3d(1.0, 2.0, 3.0), Eigen::Matrix3d::Zero(),
                                             [](const Eigen::Vector3d& x) { return Eigen::Matrix<double, 1, 1>(x.sum()); });
  EXPECT_EQ(zero.covariance(0, 0), 0.0);
  EXPECT_EQ(zero.mean(0), 6.0);
}

TEST(CovarianceCheck, NamesWhatIsWrong)
{
  Eigen::Matrix2d P;
  P << 1.0, 0.5, 0.5, 1.0;
  EXPECT_EQ(covarianceProblem<2>(P), nullptr);
  EXPECT_EQ(covarianceProblem<2>(Eigen::Matrix2d::Zero()), nullptr);
  Eigen::Matrix2d bad = P;
  bad(0, 1) = NAN;
  EXPECT_STREQ(covarianceProblem<2>(bad), "not finite");
  bad = P;
  bad(0, 1) = 0.7;
  EXPECT_STREQ(covarianceProblem<2>(bad), "not symmetric");
  bad = P;
  bad(1, 1) = -1.0;
  EXPECT_STREQ(covarianceProblem<2>(bad), "a negative variance");
  bad << 1.0, 2.0, 2.0, 1.0;  // a correlation of 2
  EXPECT_NE(covarianceProblem<2>(bad), nullptr);
}

TEST(ForceCovariance, LinearModelIsJSigmaJTransposed)
{
  // eqs. 61-62 (and the spin term of M_z) written out here: the covariance is exactly J Sigma J^T
  const BrushParameters p = test::figure4Parameters();
  const double a = p.a, k = p.k;
  const double C_sigma = 8.0 / 3.0 * k * a * a * a, C_phi = 3.0 * M_PI * a / 32.0 * C_sigma;
  const double C_Mphi = 8.0 / 15.0 * k * a * a * a * a * a;
  Eigen::Matrix3d J;
  J << C_sigma, 0.0, 0.0, 0.0, C_sigma, C_phi, 0.0, -C_phi, C_Mphi;
  Eigen::Matrix3d S;
  S << 1e-6, 2e-7, 1e-6, 2e-7, 4e-6, -3e-6, 1e-6, -3e-6, 1e-2;
  const ForceCovariance c = propagateSlipCovariance(BrushModelKind::Linear, p, { 0.01, -0.005 }, 0.5, 1.0, S);
  EXPECT_EQ(c.method, CovarianceMethod::Jacobian);
  const Eigen::Matrix3d ref = J * S * J.transpose();
  EXPECT_LT((c.covariance - ref).cwiseAbs().maxCoeff(), 1e-12 * ref.cwiseAbs().maxCoeff());
  // past mu F_z (scaled back onto the friction circle) against central differences of the model itself
  const BrushLinear model(p);
  const Eigen::Vector2d sigma(0.3, 0.1);
  const double phi = 2.0;
  const auto f = [&](const Eigen::Vector3d& x) {
    const BrushForces g = model.evaluate({ x(0), x(1) }, x(2));
    return Eigen::Vector3d(g.F_x, g.F_y, g.M_z);
  };
  Eigen::Matrix3d D;
  for (int i = 0; i < 3; ++i)
  {
    Eigen::Vector3d h = Eigen::Vector3d::Zero();
    h(i) = 1e-7 * (i == 2 ? 10.0 : 1.0);
    const Eigen::Vector3d x(sigma.x(), sigma.y(), phi);
    D.col(i) = (f(x + h) - f(x - h)) / (2.0 * h(i));
  }
  const ForceCovariance saturated = propagateSlipCovariance(BrushModelKind::Linear, p, sigma, phi, 1.0, S);
  const Eigen::Matrix3d expected = D * S * D.transpose();
  EXPECT_LT((saturated.covariance - expected).cwiseAbs().maxCoeff(), 1e-5 * expected.cwiseAbs().maxCoeff());
}

TEST(ForceCovariance, ZeroGivesExactlyZeroAndBadCovariancesAreRefused)
{
  const BrushParameters p = test::figure4Parameters();
  for (BrushModelKind kind : { BrushModelKind::Linear, BrushModelKind::Steady })
  {
    const ForceCovariance c = propagateSlipCovariance(kind, p, { 0.05, 0.02 }, 3.33, 1.0, Eigen::Matrix3d(Eigen::Matrix3d::Zero()));
    EXPECT_EQ(c.method, CovarianceMethod::Zero);
    EXPECT_TRUE(c.covariance.isZero(0.0));
    EXPECT_EQ(c.evaluations, 0);
  }
  Eigen::Matrix3d bad = Eigen::Matrix3d::Identity() * 1e-6;
  bad(1, 1) = -1e-6;
  EXPECT_THROW(propagateSlipCovariance(BrushModelKind::Steady, p, { 0.05, 0.02 }, 3.33, 1.0, bad), std::invalid_argument);
  bad(1, 1) = NAN;
  EXPECT_THROW(propagateSlipCovariance(BrushModelKind::Steady, p, { 0.05, 0.02 }, 3.33, 1.0, bad), std::invalid_argument);
}

TEST(ForceCovariance, SteadyModelAgainstMonteCarlo)
{
  // Seeded random operating points over the envelope, from adhesion to full sliding with spin, tilt and not, the
  // three pressures, under both sliding laws; the slips spread by 5 % of their size with a random correlation (a
  // spread that keeps the model smooth). 4000 draws of the steady model each (the sampling error of a standard
  // deviation is then about 1 %, of a correlation 0.02), each within 2 % of the spread: standard deviations within
  // 10 %, correlations within 0.1.
  for (const SlidingLaw law : { SlidingLaw::Coulomb, SlidingLaw::Rigid })
  {
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int checked = 0;
    double worst_sd = 0.0;
    for (int i = 0; i < 6; ++i)
    {
      const BrushParameters p = test::drawEnvelopeParameters(rng, i, law);
      const double scale = std::pow(10.0, -2.0 * u(rng));
      const Eigen::Vector2d sigma = scale * Eigen::Vector2d(0.3 * (2.0 * u(rng) - 1.0), 0.1 * (2.0 * u(rng) - 1.0));
      const double phi = scale * (2.0 * u(rng) - 1.0) / p.a, chi = 0.3 + 0.6 * u(rng);
      const Eigen::Vector3d sd(0.05 * std::abs(sigma.x()) + 1e-5, 0.05 * std::abs(sigma.y()) + 1e-5,
                               0.05 * std::abs(phi) + 1e-5 / p.a);
      Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
      R(0, 1) = R(1, 0) = 0.6 * (2.0 * u(rng) - 1.0);
      R(1, 2) = R(2, 1) = 0.3 * (2.0 * u(rng) - 1.0);
      const Eigen::Matrix3d S = sd.asDiagonal() * R * sd.asDiagonal();
      const ForceCovariance c = propagateSlipCovariance(BrushModelKind::Steady, p, sigma, phi, chi, S);
      ASSERT_TRUE(c.defined);
      EXPECT_EQ(c.method, CovarianceMethod::Unscented);
      EXPECT_LE(c.evaluations, 12);
      const BrushSteady steady(p);
      const double tolerance = std::max(1e-7, 0.02 * c.spread(p));
      const Eigen::Matrix3d mc = monteCarlo<3, 3>(
          Eigen::Vector3d(sigma.x(), sigma.y(), phi), S,
          [&](const Eigen::Vector3d& x) {
            const BrushForces f = steady.evaluate({ x(0), x(1) }, x(2), chi * x(2), (1.0 - chi) * x(2), tolerance);
            return Eigen::Vector3d(f.F_x, f.F_y, f.M_z);
          },
          4000, rng);
      const double limit = p.mu * p.F_z;
      const BrushForces nominal = steady.evaluate(sigma, phi, chi * phi, (1.0 - chi) * phi, 1e-4);
      const std::string where = std::string(toString(law)) + " point " + std::to_string(i) + " (sliding " +
                                std::to_string(nominal.sliding_fraction) + ", tilt " + std::to_string(p.tilt) + ")";
      expectClose<3>(c.covariance, mc, Eigen::Vector3d(1e-5 * limit, 1e-5 * limit, 1e-5 * limit * p.a), 0.10, 0.1, where);
      for (int k = 0; k < 3; ++k)
        if (mc(k, k) > 0.0)
          worst_sd = std::max(worst_sd, std::abs(std::sqrt(c.covariance(k, k) / mc(k, k)) - 1.0));
      ++checked;
    }
    std::printf("%s law: largest relative error of a standard deviation %.3f over %d points\n", toString(law), worst_sd,
                checked);
    EXPECT_EQ(checked, 6);
  }
}

TEST(ForceCovariance, SaysWhereTheForcesBendOverTheSpread)
{
  // Full sliding with a lateral slip far smaller than the longitudinal slip's spread: F_y = mu F_z sigma_y / |sigma|
  // peaks at sigma_x = 0, an even bend that the transform's moments do not follow. Small slips in adhesion: smooth.
  const BrushParameters p = test::figure4Parameters();
  const Eigen::Matrix3d wide = Eigen::Vector3d(0.1 * 0.1, 1e-8, 1e-8).asDiagonal();
  const ForceCovariance bent = propagateSlipCovariance(BrushModelKind::Steady, p, { 0.0, 0.01 }, 0.0, 1.0, wide);
  EXPECT_FALSE(bent.smooth);
  const Eigen::Matrix3d narrow = Eigen::Vector3d(1e-10, 1e-10, 1e-6).asDiagonal();
  const ForceCovariance smooth = propagateSlipCovariance(BrushModelKind::Steady, p, { 1e-4, 5e-5 }, 0.01, 1.0, narrow);
  EXPECT_TRUE(smooth.smooth);
  EXPECT_EQ(smooth.evaluations, 7);  // the mean too, for the bend
}

TEST(CylinderSpread, AgainstMonteCarloBelowAtAndPastTheCriticalSpeeds)
{
  // The paper's rubber: below, at and past v*, and past v_c (point contact): F_R and mu_roll's sd within 10 %.
  CylinderParameters c;
  c.g = 10.0;
  const CylinderExact model(c);
  const double v_star = *model.scales().v_star, v_c = model.scales().v_critical;
  std::mt19937_64 rng(41);
  for (double v : { 0.3 * v_star, v_star, 3.0 * v_star, 2.0 * v_c })
  {
    const double sd = 0.05 * v;
    const CylinderSpread s = cylinderSpread(model, v, sd);
    EXPECT_EQ(s.method, CovarianceMethod::Unscented);
    const Eigen::Matrix2d mc = monteCarlo<1, 2>(
        Eigen::Matrix<double, 1, 1>(v), Eigen::Matrix<double, 1, 1>(sd * sd),
        [&](const Eigen::Matrix<double, 1, 1>& x) {
          const CylinderState st = model.solve(std::abs(x(0)));
          return Eigen::Vector2d(st.F_R, st.mu_roll);
        },
        10000, rng);
    EXPECT_NEAR(std::sqrt(s.F_R_variance / mc(0, 0)), 1.0, 0.1) << "v = " << v;
    EXPECT_NEAR(std::sqrt(s.mu_roll_variance / mc(1, 1)), 1.0, 0.1) << "v = " << v;
  }
  EXPECT_EQ(cylinderSpread(model, v_star, 0.0).F_R_variance, 0.0);
  EXPECT_THROW(cylinderSpread(model, v_star, -1.0), std::invalid_argument);
  EXPECT_THROW(cylinderSpread(model, v_star, NAN), std::invalid_argument);
}

TEST(TwistCovariance, EveryKindOfBadCovariance)
{
  TwistCovariance C = TwistCovariance::Identity() * 1e-4;
  EXPECT_EQ(checkTwistCovariance(C), CovarianceStatus::Ok);
  EXPECT_EQ(checkTwistCovariance(TwistCovariance::Zero()), CovarianceStatus::Ok);
  TwistCovariance z = C;
  z(2, 2) = -1.0;  // linear z is never used: anything goes there
  z(2, 0) = z(0, 2) = NAN;
  EXPECT_EQ(checkTwistCovariance(z), CovarianceStatus::Ok);
  const char* why = nullptr;
  TwistCovariance unknown = C;
  unknown(5, 5) = -1.0;  // the ROS convention for "no estimate"
  EXPECT_EQ(checkTwistCovariance(unknown, &why), CovarianceStatus::Unknown);
  EXPECT_NE(why, nullptr);
  TwistCovariance negative = C;
  negative(3, 3) = -0.5;
  EXPECT_EQ(checkTwistCovariance(negative, &why), CovarianceStatus::Invalid);
  EXPECT_STREQ(why, "a negative variance");
  TwistCovariance nan = C;
  nan(0, 1) = nan(1, 0) = NAN;
  EXPECT_EQ(checkTwistCovariance(nan), CovarianceStatus::Invalid);
  TwistCovariance asymmetric = C;
  asymmetric(0, 1) = 1e-5;
  EXPECT_EQ(checkTwistCovariance(asymmetric), CovarianceStatus::Invalid);
  TwistCovariance indefinite = C;
  indefinite(3, 4) = indefinite(4, 3) = 5e-4;  // a correlation of 5
  EXPECT_EQ(checkTwistCovariance(indefinite), CovarianceStatus::Invalid);
}

// --- the estimator: the twist's covariance to the outputs ---

EstimatorSettings steadySettings(BrushModelKind kind)
{
  EstimatorSettings s;
  s.brush_model = kind;
  s.accuracy_target = 1e-4;
  s.rolling_resistance_model = CylinderModelKind::Exact;
  // the transform's accuracy is under test, not the work budget (WorkBudget.* test that): all the work it takes
  s.work_budget = EstimatorSettings::kMaxWorkBudget;
  return s;
}

EstimatorInput rolling(double speed, double slip_x, double slip_y, double yaw_rate, double heading)
{
  // the robot rolling at `speed` along `heading` in the ground frame (ROS axes), sliding by slip * speed
  const double c = std::cos(heading), s = std::sin(heading), R = EstimatorSettings{}.rolling_radius;
  EstimatorInput in;
  in.stamp = 1.0;
  const Eigen::Vector2d V_r(speed * c, speed * s);
  in.omega = Eigen::Vector3d(-V_r.y() / R, V_r.x() / R, yaw_rate);  // V_r = R (omega_y, -omega_x)
  const Eigen::Vector2d V_s = speed * (slip_x * Eigen::Vector2d(c, s) + slip_y * Eigen::Vector2d(-s, c));
  in.v_contact = Eigen::Vector3d(V_r.x() - V_s.x(), V_r.y() - V_s.y(), 0.0);  // sigma = -V_s / V_r
  return in;
}

// The estimator's brush forces (ROS contact frame, turned back to the heading of `reference`) and F_R L for one
// message, from a fresh estimator: a stateless map for the Monte Carlo draws.
Eigen::Vector4d outputs(const EstimatorSettings& settings, const EstimatorInput& in, double heading)
{
  ContactEstimator e(settings);
  const ContactEstimateData* d = e.update(in);
  const double t = d->heading - heading;
  const Eigen::Vector2d F(std::cos(t) * d->brush.F_x - std::sin(t) * d->brush.F_y,
                          std::sin(t) * d->brush.F_x + std::cos(t) * d->brush.F_y);
  return { F.x(), F.y(), d->brush.M_z, d->rolling_resistance_force };
}

TEST(EstimateCovariance, TwistCovarianceAgainstMonteCarlo)
{
  // Rolling at 1 m/s along a heading of 0.7 rad with slip and yaw in adhesion, partial and full sliding, the twist
  // noisy by a few per cent with correlations: the brush forces' covariance (steady model; the linear model's) and
  // F_R's variance against 10^4 draws of the twist through fresh estimators.
  std::mt19937_64 rng(53);
  const double heading = 0.7;
  for (const auto& [slip_x, slip_y, yaw, kind] :
       { std::tuple{ 0.002, 0.001, 0.05, BrushModelKind::Linear }, { 0.002, 0.001, 0.05, BrushModelKind::Steady },
         { 0.02, -0.01, 0.5, BrushModelKind::Steady }, { 0.3, 0.1, 2.0, BrushModelKind::Steady } })
  {
    const EstimatorSettings settings = steadySettings(kind);
    EstimatorInput in = rolling(1.0, slip_x, slip_y, yaw, heading);
    Eigen::Matrix<double, 6, 1> sd;
    sd << 0.002, 0.002, 0.0, 0.005, 0.005, 0.01;  // [m/s], [rad/s]
    TwistCovariance R = TwistCovariance::Identity();
    R(0, 4) = R(4, 0) = 0.5;  // the contact centre's and the sphere's velocities from the same wheel encoders
    R(1, 3) = R(3, 1) = -0.5;
    in.twist_covariance = sd.asDiagonal() * R * sd.asDiagonal();
    ContactEstimator estimator(settings);
    const ContactEstimateData* d = estimator.update(in);
    ASSERT_NE(d, nullptr);
    ASSERT_EQ(d->covariance.status, CovarianceStatus::Ok);
    EXPECT_EQ(d->covariance.brush_method,
              kind == BrushModelKind::Linear ? CovarianceMethod::Jacobian : CovarianceMethod::Unscented);
    // the draws over the twist's five used components (V_Cx, V_Cy, omega_x, omega_y, omega_z)
    Eigen::Matrix<double, 5, 1> mean;
    mean << in.v_contact.x(), in.v_contact.y(), in.omega.x(), in.omega.y(), in.omega.z();
    const Eigen::Matrix<double, 5, 5> S = usedTwistCovariance(in.twist_covariance);
    const Eigen::Matrix4d mc = monteCarlo<5, 4>(
        mean, S,
        [&](const Eigen::Matrix<double, 5, 1>& x) {
          EstimatorInput draw = in;
          draw.v_contact = Eigen::Vector3d(x(0), x(1), 0.0);
          draw.omega = Eigen::Vector3d(x(2), x(3), x(4));
          draw.twist_covariance.setZero();
          return outputs(settings, draw, d->heading);
        },
        10000, rng);
    // the brush forces' covariance and F_R's variance (their cross terms are not published)
    const double limit = settings.friction * settings.verticalLoad();
    const std::string where = "slip (" + std::to_string(slip_x) + ", " + std::to_string(slip_y) + ") " + toString(kind);
    expectClose<3>(d->covariance.brush, Eigen::Matrix3d(mc.topLeftCorner<3, 3>()),
                   Eigen::Vector3d(1e-4 * limit, 1e-4 * limit, 1e-4 * limit * 0.01), 0.10, 0.1, where);
    EXPECT_NEAR(std::sqrt(d->covariance.rolling_resistance_force_variance / mc(3, 3)), 1.0, 0.1) << where;
  }
}

TEST(EstimateCovariance, HeldForCovariancePeriodThenPropagatedAgain)
{
  // A 1 kHz stream with a noisy slip: within covariance_period of the last propagation a message carries that
  // covariance (its age on it), at the period's end it is propagated again; a changed twist covariance, a reset, an
  // out-of-order stamp or a period of 0 propagate at once.
  for (const double period : { 0.005, 0.0 })
  {
    EstimatorSettings settings = steadySettings(BrushModelKind::Steady);
    settings.accuracy_target = 1e-3;
    settings.covariance_period = period;
    ContactEstimator estimator(settings);
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 0.002);
    Eigen::Matrix<double, 6, 1> sd;
    sd << 0.002, 0.002, 0.0, 0.005, 0.005, 0.01;
    const TwistCovariance twist = sd.cwiseAbs2().asDiagonal();
    Eigen::Matrix3d last_fresh = Eigen::Matrix3d::Constant(NAN);
    double last_fresh_stamp = NAN;
    int fresh = 0;
    for (int k = 0; k < 40; ++k)
    {
      EstimatorInput in = rolling(1.0, 0.02 + noise(rng), -0.01 + noise(rng), 0.5, 0.3);
      in.stamp = 1.0 + 1e-3 * k;
      in.twist_covariance = twist;
      if (k == 17)
        in.twist_covariance(5, 5) *= 1.5;  // the source's covariance changes: propagated at once
      if (k == 18)
        in.twist_covariance = twist;
      if (k == 29)
        in.stamp = last_fresh_stamp - 5e-4;  // out of order within stamp_tolerance, before the last propagation
      const ContactEstimateData* d = estimator.update(in);
      ASSERT_NE(d, nullptr);
      const CovarianceStatus status = d->covariance.status;
      ASSERT_TRUE(status == CovarianceStatus::Ok || status == CovarianceStatus::Approximate) << k;
      ASSERT_EQ(d->covariance.brush_method, CovarianceMethod::Unscented) << k;
      const bool expect_fresh = period == 0.0 || k == 0 || k == 17 || k == 18 || k == 29 ||
                                !(in.stamp - last_fresh_stamp < period);
      if (expect_fresh)
      {
        EXPECT_EQ(d->covariance.brush_age, 0.0) << k;
        if (k > 0)
        {
          EXPECT_NE(d->covariance.brush, last_fresh) << k;  // of this message's slips
        }
        last_fresh = d->covariance.brush;
        last_fresh_stamp = in.stamp;
        ++fresh;
      }
      else
      {
        EXPECT_NEAR(d->covariance.brush_age, in.stamp - last_fresh_stamp, 1e-12) << k;
        EXPECT_EQ(d->covariance.brush, last_fresh) << k;
      }
    }
    if (period == 0.0)
    {
      EXPECT_EQ(fresh, 40);
    }
    else
    {
      EXPECT_LE(fresh, 12);  // about every fifth, and the four that had to be
    }
  }
  // a reset forgets it: a stamp that goes back beyond the tolerance propagates again
  EstimatorSettings settings = steadySettings(BrushModelKind::Steady);
  settings.accuracy_target = 1e-3;
  ContactEstimator estimator(settings);
  EstimatorInput in = rolling(1.0, 0.02, -0.01, 0.5, 0.3);
  Eigen::Matrix<double, 6, 1> sd;
  sd << 0.002, 0.002, 0.0, 0.005, 0.005, 0.01;
  in.twist_covariance = sd.cwiseAbs2().asDiagonal();
  in.stamp = 2.0;
  ASSERT_NE(estimator.update(in), nullptr);
  in.stamp = 2.001;
  EXPECT_GT(estimator.update(in)->covariance.brush_age, 0.0);
  in.stamp = 1.0;
  const ContactEstimateData* d = estimator.update(in);
  EXPECT_TRUE(d->flags & estimate_flags::kTimeJumpReset);
  EXPECT_EQ(d->covariance.brush_age, 0.0);
}

TEST(EstimateCovariance, HostileCovariancesAndStandstill)
{
  const EstimatorSettings settings = steadySettings(BrushModelKind::Steady);
  const auto run = [&](const TwistCovariance& C, CovarianceStatus status, double speed = 1.0) {
    ContactEstimator e(settings);
    EstimatorInput in = rolling(speed, 0.01, 0.0, 0.1, 0.0);
    in.twist_covariance = C;
    in.twist_covariance_status = status;
    return *e.update(in);
  };
  // exact odometry: exactly zero
  const ContactEstimateData zero = run(TwistCovariance::Zero(), CovarianceStatus::Ok);
  EXPECT_EQ(zero.covariance.status, CovarianceStatus::Ok);
  EXPECT_EQ(zero.covariance.brush_method, CovarianceMethod::Zero);
  EXPECT_TRUE(zero.covariance.brush.isZero(0.0));
  EXPECT_EQ(zero.covariance.rolling_resistance_force_variance, 0.0);
  // refused where it entered (the ROS layer checks the message): nothing carried, said so
  for (CovarianceStatus s : { CovarianceStatus::Unknown, CovarianceStatus::Invalid })
  {
    const ContactEstimateData d = run(TwistCovariance::Identity() * 1e-4, s);
    EXPECT_EQ(d.covariance.status, s);
    EXPECT_EQ(d.covariance.brush_method, CovarianceMethod::None);
    EXPECT_EQ(d.covariance.rolling_resistance_method, CovarianceMethod::None);
    EXPECT_TRUE(std::isfinite(d.brush.F_x));  // the estimate itself goes on
  }
  // finite but absurd: carried where it stays representable (the forces are bounded by friction, so is their
  // spread), flagged approximate; refused where it overflows; never garbage
  const double limit = settings.friction * settings.verticalLoad();
  const ContactEstimateData wide = run(TwistCovariance::Identity() * 1e300, CovarianceStatus::Ok);
  EXPECT_EQ(wide.covariance.status, CovarianceStatus::Approximate);
  EXPECT_TRUE(wide.covariance.brush.allFinite());
  EXPECT_LE(wide.covariance.brush(0, 0), 4.0 * limit * limit);
  const ContactEstimateData huge =
      run(TwistCovariance::Identity() * std::numeric_limits<double>::max(), CovarianceStatus::Ok);
  EXPECT_EQ(huge.covariance.status, CovarianceStatus::Invalid);
  EXPECT_TRUE(huge.covariance.brush.allFinite());
  EXPECT_EQ(huge.covariance.brush_method, CovarianceMethod::None);
  // standstill: no slips, so no brush covariance; the rolling resistance's is still there
  const ContactEstimateData still = run(TwistCovariance::Identity() * 1e-6, CovarianceStatus::Ok, 0.01);
  EXPECT_EQ(still.covariance.status, CovarianceStatus::Undefined);
  EXPECT_EQ(still.covariance.brush_method, CovarianceMethod::None);
  EXPECT_EQ(still.covariance.rolling_resistance_method, CovarianceMethod::Unscented);
  // just above the standstill speed, with a spread that reaches it: carried, flagged approximate
  const ContactEstimateData near = run(TwistCovariance::Identity(), CovarianceStatus::Ok, 0.2);
  EXPECT_EQ(near.covariance.status, CovarianceStatus::Approximate);
  // switched off
  EstimatorSettings off = settings;
  off.propagate_covariance = false;
  ContactEstimator e(off);
  EstimatorInput in = rolling(1.0, 0.01, 0.0, 0.1, 0.0);
  in.twist_covariance = TwistCovariance::Identity() * 1e-4;
  EXPECT_EQ(e.update(in)->covariance.status, CovarianceStatus::Disabled);
}

TEST(EstimateCovariance, NearStandstillWithASmallSpreadAgainstMonteCarlo)
{
  // 0.2 m/s, four times the standstill speed, the speed's spread a twentieth of the gap: the slips' 1 / V_r is
  // still near linear over it
  const EstimatorSettings settings = steadySettings(BrushModelKind::Steady);
  std::mt19937_64 rng(59);
  EstimatorInput in = rolling(0.2, 0.05, 0.02, 0.3, 0.0);
  Eigen::Matrix<double, 6, 1> sd;
  sd << 0.001, 0.001, 0.0, 0.02, 0.02, 0.01;
  in.twist_covariance = sd.cwiseAbs2().asDiagonal();
  ContactEstimator estimator(settings);
  const ContactEstimateData* d = estimator.update(in);
  ASSERT_EQ(d->covariance.status, CovarianceStatus::Ok);
  Eigen::Matrix<double, 5, 1> mean;
  mean << in.v_contact.x(), in.v_contact.y(), in.omega.x(), in.omega.y(), in.omega.z();
  const Eigen::Matrix4d mc = monteCarlo<5, 4>(
      mean, usedTwistCovariance(in.twist_covariance),
      [&](const Eigen::Matrix<double, 5, 1>& x) {
        EstimatorInput draw = in;
        draw.v_contact = Eigen::Vector3d(x(0), x(1), 0.0);
        draw.omega = Eigen::Vector3d(x(2), x(3), x(4));
        draw.twist_covariance.setZero();
        return outputs(settings, draw, d->heading);
      },
      10000, rng);
  const double limit = settings.friction * settings.verticalLoad();
  expectClose<3>(d->covariance.brush, Eigen::Matrix3d(mc.topLeftCorner<3, 3>()),
                 Eigen::Vector3d(1e-4 * limit, 1e-4 * limit, 1e-6 * limit), 0.10, 0.1, "0.2 m/s");
  EXPECT_NEAR(std::sqrt(d->covariance.rolling_resistance_force_variance / mc(3, 3)), 1.0, 0.1);
}

TEST(StandstillCovariance, TheRollsMomentsAgainstClosedForms)
{
  // The roll's share of a message, Var(dt R w + L(d)) with d = -V_r dt, against closed forms for the two kinds of
  // table the lattice gives: linear in d (the moment arm, e x F) and one-sided (what leaves at the rim).
  const double dt = 0.01;
  Eigen::Matrix<double, 5, 5> drive;  // (V_s,x, V_s,y, omega_z, V_r,x, V_r,y), V_s sharing V_r's noise
  {
    Eigen::Matrix<double, 5, 5> G = Eigen::Matrix<double, 5, 5>::Identity();
    G(0, 3) = G(1, 4) = -1.0;  // V_s = V_C - V_r
    const Eigen::Matrix<double, 5, 1> sd(0.004, 0.003, 0.05, 0.003, 0.002);
    Eigen::Matrix<double, 5, 5> C = sd.cwiseAbs2().asDiagonal();
    C(3, 4) = C(4, 3) = 0.3 * sd(3) * sd(4);
    drive = G * C * G.transpose();
  }
  const Eigen::Vector3d limits = Eigen::Vector3d::Constant(1e9);
  const Eigen::Matrix3d P2R = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();  // paper <-> ROS
  AdhesionResponse r;
  r.drive << -2e4, 0.0, 3.0, 0.0, -2e4, -1.0, 3.0, -1.0, -40.0;
  const Eigen::Matrix3d A = dt * (P2R * r.drive * P2R);
  // linear: L(e) = M e (paper), so the increment is dt [A_w, -M_ros] (w, V_r): Var exactly G Sigma G^T
  Eigen::Matrix<double, 3, 2> M;
  M << 300.0, -200.0, 50.0, 400.0, 2.0, -3.0;
  for (int j = 0; j < AdhesionResponse::kDirections; ++j)
    r.roll.col(j) = M * AdhesionResponse::directions()[j];
  Eigen::Matrix<double, 3, 2> M_ros = P2R * M;
  M_ros.col(1) *= -1.0;  // a displacement's y turns sign too
  Eigen::Matrix<double, 3, 5> G;
  G << A, -dt * M_ros;
  const Eigen::Matrix3d linear = G * drive * G.transpose();
  StandstillCovariance walk;
  walk.restart(Eigen::Matrix3d::Zero());
  walk.advance(r, drive, dt, limits, 0.01);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(walk.covariance()(i, j), linear(i, j), 5e-3 * std::sqrt(linear(i, i) * linear(j, j))) << i << j;
  // one-sided: L(e) = -c (e . n)+ (paper), nothing else moving: L(d) = -c (d . n)+ with d . n ~ N(0, s^2):
  // E = -c s / sqrt(2 pi), Var = c^2 s^2 (1/2 - 1/(2 pi)) (measured 1.2 % low: the table's kink, linear between its
  // 32 directions)
  const Eigen::Vector2d n(std::cos(0.7), std::sin(0.7));
  const Eigen::Vector3d c(5.0, -2.0, 0.1);
  r.drive.setZero();
  for (int j = 0; j < AdhesionResponse::kDirections; ++j)
    r.roll.col(j) = -c * std::max(0.0, n.dot(AdhesionResponse::directions()[j]));
  const Eigen::Vector2d n_ros(n.x(), -n.y());
  const double s2 = dt * dt * n_ros.dot(drive.bottomRightCorner<2, 2>() * n_ros);
  const Eigen::Vector3d c_ros = P2R * c;
  const Eigen::Matrix3d one_sided = c_ros * c_ros.transpose() * s2 * (0.5 - 0.5 / M_PI);
  walk.restart(Eigen::Matrix3d::Zero());
  walk.advance(r, drive, dt, limits, 0.01);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(walk.covariance()(i, j), one_sided(i, j), 2e-2 * std::sqrt(one_sided(i, i) * one_sided(j, j)))
          << i << j;
  // without roll noise the roll has no share
  Eigen::Matrix<double, 5, 5> still = drive;
  still.bottomRows<2>().setZero();
  still.rightCols<2>().setZero();
  walk.restart(Eigen::Matrix3d::Zero());
  walk.advance(r, still, dt, limits, 0.01);
  EXPECT_EQ(walk.covariance(), Eigen::Matrix3d::Zero());
}

TEST(EstimateCovariance, StandstillRandomWalkAgainstMonteCarlo)
{
  // Parked, the slips are undefined and the forces are what the adhering bristles integrated: each message's odometry
  // error stays in the state, and the noise in omega_x, omega_y rolls the roots under it. The covariance the estimator
  // walks (StandstillCovariance) against the spread of the forces over independent noise realisations of the same
  // history, at three messages of it, at the default robot and at the envelope's robot where the walk without the
  // roll was furthest off (over random robots: model_accuracy --parked-walk).
  struct Case
  {
    const char* name;
    BrushModelKind model;
    double rate;          // [Hz]
    double spin;          // omega_z while standing [rad/s]
    double skid;          // before standing: rolled 0.1 s at 0.5 m/s with this lateral slip, noise-free (0: none)
    int messages;         // standing, with noise
    double body_heading;  // [rad]
    double tolerance;     // on the ratio of the standard deviations (400 draws: sampling error about 3.5 %), and from
                          // a model's own start on the correlations
    bool uniform_robot = false;  // model_accuracy --parked-walk 7 60's robot 39: a = 5.6 mm, k 2.3e8, 7.8 kg, mu
                                 // 0.68, the uniform pressure (its rim holds deflection: the roll's loss there), and
                                 // its noise: independent, 1.2 times the demo's
    double spun = 0.0;  // before standing: spinning in place at 5 rad/s this long [s], noise-free (0: none)
    double above = 0.0;  // the standard deviations' ratio may pass 1 by this much instead of `tolerance` (0: the same)
  };
  const Case cases[] = {
    // (measured: 1.11 and 1.18 at worst, the walk above the spread: the rim's bristles, with little bound, slide and
    // forget; 1.14 and 1.16 with the sliding ones left out of the response)
    { "parked, auto, 1 kHz", BrushModelKind::Auto, 1000.0, 0.0, 0.0, 300, 0.7, 0.2 },
    { "parked, transient, 100 Hz", BrushModelKind::Transient, 100.0, 0.0, 0.0, 12, -2.0, 0.2 },
    // the roll's share leads M_z here (measured 1.23 at worst, over the spread in the first messages, where the roots
    // rolled less than a lattice spacing; 0.60 without the roll; over the envelope the moment arm alone, without what
    // the roll carries out at the rim, overstated M_z's up to 3.1 times)
    { "parked, uniform pressure, auto, 100 Hz", BrushModelKind::Auto, 100.0, 0.0, 0.0, 52, 0.3, 0.3, true },
    // from a rolled field, whose rear bristles lie on their bounds (measured 1.03 and 1.17 at worst, the correlation of
    // F_y and M_z 0.45-0.49 against 0.59-0.65; without the band of the bound, StandstillCovariance::band, 0.80 and 1.22
    // and 0.08-0.18, which fails)
    { "parked after a skid, auto, 1 kHz", BrushModelKind::Auto, 1000.0, 0.0, 0.05, 300, 0.0, 0.2 },
    // most bristles slide: not followed
    { "spinning in place, auto, 1 kHz", BrushModelKind::Auto, 1000.0, 4.0, 0.0, 300, 1.2, 0.0 },
    // parked after spinning in place (the recorded manoeuvre's park), the bristles on their bounds about the spin
    // pole: the noise pushes them off their bounds and never back on, a ratchet that the walk's per-message shares do
    // not see; measured 1.03-1.19 for F, and M_z's overstated, 1.55-1.75 (with the sliding bristles left out of the
    // response and no band, StandstillCovariance::band, 1.17-1.44 for F and 0.81-0.93 for M_z)
    { "parked after spinning in place, auto, 1 kHz", BrushModelKind::Auto, 1000.0, 0.0, 0.0, 300, 0.4, 0.2, false, 0.5,
      0.8 },
  };
  const auto noise = [](bool uniform_robot) {
    Eigen::Matrix<double, 6, 1> sd;
    sd << 0.004, 0.004, 0.0, 0.03, 0.03, 0.05;  // [m/s], [rad/s]: R_r sd(omega_x,y) = 3 mm/s, far below standstill
    TwistCovariance C = TwistCovariance::Identity();
    C(0, 4) = C(4, 0) = 0.5;  // the contact centre's and the sphere's velocities from the same encoders
    C(1, 3) = C(3, 1) = -0.5;
    if (uniform_robot)
    {
      sd << 0.006, 0.006, 0.0, 0.024, 0.024, 0.024;
      C = TwistCovariance::Identity();  // (V_C and omega independent: the roll's share is largest)
    }
    return TwistCovariance(sd.asDiagonal() * C * sd.asDiagonal());
  };
  constexpr int kDraws = 400;
  for (const Case& c : cases)
  {
    EstimatorSettings settings;
    settings.brush_model = c.model;
    // the spread of the state the noise moves, against the walk's account of it: the noise let through (by default it
    // is held, and the realisations would not spread: test_motion_hold holds the walk's band against the truth there)
    settings.hold_within_noise = false;
    if (c.uniform_robot)
    {
      settings.patch_radius = 0.00557;
      settings.bristle_stiffness = 2.3e8;
      settings.robot_mass = 7.78;
      settings.friction = 0.678;
      settings.pressure = PressureDistribution::Uniform;
    }
    const TwistCovariance twist = noise(c.uniform_robot);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 5, 5>> eig(usedTwistCovariance(twist));
    const Eigen::Matrix<double, 5, 5> root =
        eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
    const double dt = 1.0 / c.rate;
    const int checks[3] = { c.messages / 6, c.messages / 2, c.messages - 1 };
    std::vector<Eigen::Vector3d> F[3];
    Eigen::Matrix3d walked[3] = { Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero() };
    std::mt19937_64 rng(4242);
    std::normal_distribution<double> g(0.0, 1.0);
    int approximate = 0, undefined = 0, walks = 0;
    for (int draw = 0; draw < kDraws; ++draw)
    {
      ContactEstimator e(settings);
      double t = 0.0;
      if (c.skid != 0.0)
        for (int k = 0; k < static_cast<int>(0.1 * c.rate); ++k, t += dt)
        {
          EstimatorInput in = rolling(0.5, 0.0, c.skid, 0.0, 0.0);
          in.stamp = t;
          in.twist_covariance = TwistCovariance::Zero();  // exact: the state at the stop is known
          ASSERT_NE(e.update(in), nullptr);
        }
      for (int k = 0; k < static_cast<int>(c.spun * c.rate); ++k, t += dt)
      {
        EstimatorInput in;
        in.stamp = t;
        in.omega = Eigen::Vector3d(0.0, 0.0, 5.0);
        in.body_heading = c.body_heading;
        in.twist_covariance = TwistCovariance::Zero();
        ASSERT_NE(e.update(in), nullptr);
      }
      for (int k = 0; k < c.messages; ++k, t += dt)
      {
        Eigen::Matrix<double, 5, 1> z;
        for (int i = 0; i < 5; ++i)
          z(i) = g(rng);
        const Eigen::Matrix<double, 5, 1> x = root * z;
        EstimatorInput in;
        in.stamp = t;
        in.v_contact = Eigen::Vector3d(x(0), x(1), 0.0);
        in.omega = Eigen::Vector3d(x(2), x(3), c.spin + x(4));
        in.twist_covariance = twist;
        in.body_heading = c.body_heading;
        const ContactEstimateData* d = e.update(in);
        ASSERT_NE(d, nullptr);
        ASSERT_FALSE(d->slips_defined) << c.name << " " << k;
        const EstimateCovariance& v = d->covariance;
        if (v.status == CovarianceStatus::Undefined)
        {
          ++undefined;
          EXPECT_EQ(v.brush_method, CovarianceMethod::None);
          EXPECT_GT(d->brush.sliding_fraction, StandstillCovariance::kSlidingShare) << c.name << " " << k;
          continue;
        }
        ++walks;
        ASSERT_EQ(v.brush_method, CovarianceMethod::RandomWalk) << c.name << " " << k;
        EXPECT_EQ(covarianceProblem<3>(v.brush), nullptr);
        approximate += v.status == CovarianceStatus::Approximate;
        for (int i = 0; i < 3; ++i)
          if (k == checks[i])
          {
            F[i].emplace_back(d->brush.F_x, d->brush.F_y, d->brush.M_z);
            walked[i] += v.brush / kDraws;
          }
      }
    }
    if (c.tolerance == 0.0)
    {
      EXPECT_GT(undefined, kDraws * c.messages / 2) << c.name;  // spinning, from the first tens of milliseconds on
      continue;
    }
    // (after spinning in place most bristles slide at first: no covariance until enough have re-adhered)
    if (c.spun == 0.0)
    {
      EXPECT_EQ(undefined, 0) << c.name;
    }
    EXPECT_EQ(approximate, walks) << c.name;  // always (StandstillCovariance: what it leaves out)
    double worst = 1.0;
    int compared = 0;
    for (int i = 0; i < 3; ++i)
    {
      if (c.spun > 0.0 && F[i].size() < static_cast<std::size_t>(kDraws))
        continue;  // not every realisation walked here
      ++compared;
      ASSERT_EQ(F[i].size(), static_cast<std::size_t>(kDraws));
      const Eigen::Matrix3d mc = sampleCovariance(F[i]);
      for (int j = 0; j < 3; ++j)
      {
        const double ratio = std::sqrt(walked[i](j, j) / mc(j, j));
        worst = std::abs(ratio - 1.0) > std::abs(worst - 1.0) ? ratio : worst;
        EXPECT_GE(ratio, 1.0 - c.tolerance) << c.name << ", message " << checks[i] << ", component " << j;
        EXPECT_LE(ratio, 1.0 + (c.above > 0.0 ? c.above : c.tolerance))
            << c.name << ", message " << checks[i] << ", component " << j
                                             << ": walked " << std::sqrt(walked[i](j, j)) << ", Monte Carlo "
                                             << std::sqrt(mc(j, j));
      }
      for (int j = 0; j < 3; ++j)
        for (int l = j + 1; l < 3; ++l)
        {
          const double r_walked = walked[i](j, l) / std::sqrt(walked[i](j, j) * walked[i](l, l));
          const double r_mc = mc(j, l) / std::sqrt(mc(j, j) * mc(l, l));
          std::printf("  %s, message %d: correlation %d%d walked %.2f, Monte Carlo %.2f\n", c.name, checks[i], j, l,
                      r_walked, r_mc);
          EXPECT_NEAR(r_walked, r_mc, c.tolerance) << c.name << ", message " << checks[i] << ", correlation " << j << l;
        }
      std::printf("  %s, message %d: walked / Monte Carlo standard deviations %.2f %.2f %.2f\n", c.name, checks[i],
                  std::sqrt(walked[i](0, 0) / mc(0, 0)), std::sqrt(walked[i](1, 1) / mc(1, 1)),
                  std::sqrt(walked[i](2, 2) / mc(2, 2)));
    }
    EXPECT_GE(compared, 1) << c.name;
    std::printf("%s: worst walked / Monte Carlo standard deviation %.3f (%d checks)\n", c.name, worst, compared);
  }
}

TEST(EstimateCovariance, StandstillWalkGrowsIsHeldByFrictionAndIsLostWithItsNoise)
{
  EstimatorSettings settings;  // auto, the defaults
  Eigen::Matrix<double, 6, 1> sd;
  sd << 0.004, 0.004, 0.0, 0.03, 0.03, 0.05;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> g(0.0, 1.0);
  double t = 0.0;
  const auto parked = [&](ContactEstimator& e, double scale, CovarianceStatus status = CovarianceStatus::Ok) {
    EstimatorInput in;
    in.stamp = t += 0.01;
    // (scaled on V_C and omega_z: the rolling speed's noise stays below the standstill speed)
    Eigen::Matrix<double, 6, 1> scaled = sd;
    for (int i : { 0, 1, 5 })
      scaled(i) *= scale;
    in.v_contact = Eigen::Vector3d(scaled(0) * g(rng), scaled(1) * g(rng), 0.0);
    in.omega = Eigen::Vector3d(scaled(3) * g(rng), scaled(4) * g(rng), scaled(5) * g(rng));
    in.twist_covariance = scaled.cwiseAbs2().asDiagonal();
    in.twist_covariance_status = status;
    const ContactEstimateData* d = e.update(in);
    EXPECT_NE(d, nullptr);
    return *d;
  };
  ContactEstimator e(settings);
  // grows message by message from the model's own start: a walk
  double last = 0.0;
  for (int k = 0; k < 20; ++k)
  {
    const ContactEstimateData d = parked(e, 1.0);
    ASSERT_EQ(d.covariance.status, CovarianceStatus::Approximate) << k;
    ASSERT_EQ(d.covariance.brush_method, CovarianceMethod::RandomWalk) << k;
    if (k > 0)
    {
      EXPECT_GT(d.covariance.brush_spread, last) << k;
    }
    last = d.covariance.brush_spread;
  }
  // a message whose noise is unknown: lost until the slips are defined again (or a reset)
  EXPECT_EQ(parked(e, 1.0, CovarianceStatus::Unknown).covariance.status, CovarianceStatus::Unknown);
  for (int k = 0; k < 3; ++k)
  {
    const ContactEstimateData d = parked(e, 1.0);
    EXPECT_EQ(d.covariance.status, CovarianceStatus::Undefined) << k;
    EXPECT_EQ(d.covariance.brush_method, CovarianceMethod::None) << k;
  }
  // a reset: the model's own start, walked afresh
  e.reset();
  const ContactEstimateData fresh = parked(e, 1.0);
  EXPECT_EQ(fresh.covariance.brush_method, CovarianceMethod::RandomWalk);
  EXPECT_LT(fresh.covariance.brush_spread, last);
  // switched off and on again while parked: the messages between were not walked
  EstimatorSettings off = settings;
  off.propagate_covariance = false;
  e.configure(off);
  EXPECT_EQ(parked(e, 1.0).covariance.status, CovarianceStatus::Disabled);
  e.configure(settings);
  EXPECT_EQ(parked(e, 1.0).covariance.status, CovarianceStatus::Undefined);
  // a noise a hundred times the demo's: held at the friction limit, still a covariance
  ContactEstimator loud(settings);
  const double limit = settings.friction * settings.verticalLoad();
  double largest = 0.0;
  for (int k = 0; k < 30; ++k)
  {
    const ContactEstimateData d = parked(loud, 100.0);
    if (d.covariance.brush_method != CovarianceMethod::RandomWalk)
      continue;  // (where the noise has pushed most bristles onto their bounds: not followed)
    largest = std::max({ largest, d.covariance.brush(0, 0), d.covariance.brush(1, 1) });
    EXPECT_LE(d.covariance.brush(0, 0), limit * limit * (1.0 + 1e-12)) << k;
    EXPECT_LE(d.covariance.brush(1, 1), limit * limit * (1.0 + 1e-12)) << k;
    EXPECT_EQ(covarianceProblem<3>(d.covariance.brush), nullptr) << k;
  }
  EXPECT_NEAR(largest, limit * limit, 1e-9 * limit * limit);  // reached, and held
  // the steady model answers zero at standstill: nothing to walk
  EstimatorSettings steady = settings;
  steady.brush_model = BrushModelKind::Steady;
  ContactEstimator s(steady);
  EXPECT_EQ(parked(s, 1.0).covariance.status, CovarianceStatus::Undefined);
}

TEST(AutoBelowTheNoise, TargetFollowsTheSpreadAndTheErrorStaysWithinIt)
{
  // With noisy odometry the forces' own spread s may exceed the accuracy target: auto then answers to f s
  // (f = auto_noise_fraction), and its error against the converged reference stays within that at held inputs.
  BrushParameters p = test::figure4Parameters();
  p.accuracy_target = 1e-3;
  p.auto_noise_fraction = 0.25;
  BrushAuto quiet(p), noisy(p);
  const ContactKinematics k = ContactKinematics::fromSlips({ 0.05, 0.02 }, 3.33, 1.0, 1.0);
  const BrushForces ref = BrushSteady(p).evaluate({ 0.05, 0.02 }, 3.33, 3.33, 0.0, 1e-9);
  noisy.setInputSpread(0.08);  // 8 % of mu F_z: the target becomes 2 %
  BrushForces q, n;
  for (int i = 0; i < 5; ++i)
  {
    q = quiet.update(k, 0.02);
    n = noisy.update(k, 0.02);
  }
  EXPECT_NEAR(noisy.lastTarget(), 0.02, 1e-15);
  EXPECT_EQ(quiet.lastTarget(), 1e-3);
  EXPECT_LE(n.error_estimate, 0.02);
  EXPECT_LE(test::forceDistance(n, ref, p), 0.02);
  EXPECT_LE(test::forceDistance(q, ref, p), 1e-3);
  EXPECT_LE(noisy.cost(), quiet.cost());  // never more effort for a looser target
  // a spread below the target changes nothing
  BrushAuto calm(p);
  calm.setInputSpread(1e-3);
  calm.update(k, 0.02);
  EXPECT_EQ(calm.lastTarget(), 1e-3);
}

}  // namespace
}  // namespace sphere_contact_estimator
