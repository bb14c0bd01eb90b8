// Through the critical speed and at the extremes: finite, continuous, and flagged as documented.

// STL
#include <cmath>
#include <limits>
#include <random>
#include <vector>

// GTest
#include <gtest/gtest.h>

// Package
#include "cylinder_test_support.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

namespace sphere_contact_estimator
{
namespace
{
using test::paperParameters;

void expectFinite(const CylinderState& s)
{
  for (double x : { s.v, s.h, s.xi_plus, s.xi_minus, s.F_N, s.F_N_impact, s.F_R, s.F_R_impact, s.torque, s.mu_roll,
                    s.mu_roll_error })
    EXPECT_TRUE(std::isfinite(x)) << "v = " << s.v;
  EXPECT_GE(s.h, 0.0);
  EXPECT_GE(s.F_R, 0.0);
  EXPECT_GE(s.mu_roll, 0.0);
  EXPECT_LE(s.xi_minus, s.xi_plus);
}

// The largest relative jump of any state field between v(1 - d) and v(1 + d).
double jumpAcross(const CylinderModel& model, double v, double d)
{
  const CylinderState a = model.solve(v * (1.0 - d)), b = model.solve(v * (1.0 + d));
  double jump = 0.0;
  const auto rel = [&jump](double x, double y, double scale) { jump = std::max(jump, std::abs(x - y) / scale); };
  rel(a.h, b.h, std::max(a.h, b.h));
  rel(a.xi_plus, b.xi_plus, a.xi_plus);
  rel(a.xi_minus, b.xi_minus, a.xi_plus);
  rel(a.F_R, b.F_R, a.F_R);
  rel(a.mu_roll, b.mu_roll, a.mu_roll);
  return jump;
}

TEST(CylinderRegimes, SweepThroughTheCriticalSpeed)
{
  for (const CylinderModelKind kind : { CylinderModelKind::Exact, CylinderModelKind::Table })
  {
    const auto model = makeCylinderModel(kind, paperParameters());
    const double v_c = model->scales().v_critical;
    ASSERT_TRUE(std::isfinite(v_c));
    // Geometric sweep from creep to far past v_c: finite everywhere, regimes as documented.
    for (double v = 1e-9; v < 1e3 * v_c; v *= 1.05)
    {
      const CylinderState s = model->solve(v);
      expectFinite(s);
      if (v < 0.999 * v_c)
      {
        EXPECT_EQ(s.regime, CylinderRegime::ContactPatch) << "v = " << v;
        EXPECT_TRUE(s.valid()) << "v = " << v;
        EXPECT_GT(s.xi_plus - s.xi_minus, 0.0) << "v = " << v;
      }
      else if (v > 1.001 * v_c)
      {
        EXPECT_EQ(s.regime, CylinderRegime::PointContact) << "v = " << v;
        EXPECT_FALSE(s.valid());
        EXPECT_TRUE(s.flags & cylinder_flags::kSelfInconsistent);
        // note 13: the weight rests on F'_N alone, whose lever arm is the whole of mu_roll
        EXPECT_NEAR(s.F_N_impact, paperParameters().M * paperParameters().g, 1e-12 * s.F_N_impact);
        EXPECT_EQ(s.F_N, 0.0);
        EXPECT_NEAR(s.mu_roll, s.xi_plus, 1e-12 * s.xi_plus);
      }
    }
    // Continuous at v_c: the jump across it shrinks in proportion to the gap.
    const double j3 = jumpAcross(*model, v_c, 1e-3), j5 = jumpAcross(*model, v_c, 1e-5),
                 j7 = jumpAcross(*model, v_c, 1e-7);
    EXPECT_LT(j3, 0.05);
    EXPECT_LT(j5, 0.02 * j3);
    EXPECT_LT(j7, 0.02 * j5);
    // As v -> v_c from below the patch closes: xi_- -> xi_+ = m v / gamma.
    const CylinderState below = model->solve(v_c * (1.0 - 1e-6));
    EXPECT_LT(below.xi_plus - below.xi_minus, 1e-4 * below.xi_plus);
    EXPECT_NEAR(below.xi_plus, paperParameters().m * v_c / paperParameters().gamma, 1e-5 * below.xi_plus);
  }
}

TEST(CylinderRegimes, CriticalSpeedIsWhereThePatchCloses)
{
  // v_c (CylinderScales) from M g = m v^2 xi_+ / R with xi_+ = m v / gamma, against the exact solver:
  // the patch width falls to zero exactly there.
  const CylinderExact model(paperParameters());
  const double v_c = model.scales().v_critical;
  const CylinderState s1 = model.solve(0.99 * v_c), s2 = model.solve(0.999 * v_c);
  const double w1 = s1.xi_plus - s1.xi_minus, w2 = s2.xi_plus - s2.xi_minus;
  // extrapolate the width linearly to zero
  const double v0 = 0.99 * v_c + (0.999 * v_c - 0.99 * v_c) * w1 / (w1 - w2);
  EXPECT_NEAR(v0, v_c, 1e-3 * v_c);
}

TEST(CylinderRegimes, UnderdampedSurfacesAreFlaggedAndStayContinuous)
{
  // 4 m k >= gamma^2 breaks eq. 2; with m k > gamma^2 the patch loses consistency before v_c and
  // the state is reported at xi_+ = m v / gamma. h stays continuous across every switch.
  for (double m : { 0.3 * 2.5e11 / 1e7, 2.0 * 2.5e11 / 1e7, 20.0 * 2.5e11 / 1e7 })
  {
    CylinderParameters p = paperParameters();
    p.m = m;  // 4 m k = 1.2, 8, 80 gamma^2
    const CylinderExact model(p);
    double previous_h = model.solve(0.0).h;
    bool saw_no_steady_state = false;
    for (double v = 1e-4; v < 50.0 * model.scales().v_critical; v *= 1.001)
    {
      const CylinderState s = model.solve(v);
      expectFinite(s);
      EXPECT_TRUE(s.flags & cylinder_flags::kUnderdamped);
      EXPECT_FALSE(s.valid());
      EXPECT_LT(std::abs(s.h - previous_h), 0.01 * previous_h) << "m = " << m << " v = " << v;
      previous_h = s.h;
      saw_no_steady_state |= s.regime == CylinderRegime::NoSteadyState;
      if (s.regime == CylinderRegime::NoSteadyState)
      {
        EXPECT_TRUE(s.flags & cylinder_flags::kNoSteadyState);
      }
    }
    EXPECT_EQ(saw_no_steady_state, m * p.k > p.gamma * p.gamma) << "m = " << m;
  }
}

TEST(CylinderRegimes, DegenerateButAllowedParameters)
{
  // gamma = 0 and m = 0: an elastic bed, symmetric contact, no resistance at any speed.
  CylinderParameters p = paperParameters();
  p.gamma = 0.0;
  p.m = 0.0;
  for (const CylinderModelKind kind : { CylinderModelKind::Exact, CylinderModelKind::Expansion, CylinderModelKind::Table })
  {
    const auto model = makeCylinderModel(kind, p);
    for (double v : { 0.0, 1e-12, 1.0, 1e3, 1e8 })
    {
      const CylinderState s = model->solve(v);
      expectFinite(s);
      EXPECT_NEAR(s.mu_roll, 0.0, 1e-15) << toString(kind) << " v = " << v;
      EXPECT_NEAR(s.h, model->scales().h0, 1e-12 * model->scales().h0) << toString(kind) << " v = " << v;
      EXPECT_TRUE(s.flags & cylinder_flags::kUnderdamped);  // 4 m k < gamma^2 fails: 0 < 0
    }
  }
  // gamma = 0 with m > 0: v_c = 0, point contact at any v > 0; finite down to the smallest speeds.
  p.m = 100.0;
  const CylinderExact inertial(p);
  for (double v : { 1e-300, 1e-100, 1e-10, 1.0, 1e6 })
  {
    const CylinderState s = inertial.solve(v);
    expectFinite(s);
    EXPECT_EQ(s.regime, CylinderRegime::PointContact);
    EXPECT_FALSE(s.valid());
  }
  // m = 0: no critical speed; the patch narrows but never closes.
  p = paperParameters();
  p.m = 0.0;
  const CylinderExact massless(p);
  EXPECT_TRUE(std::isinf(massless.scales().v_critical));
  for (double v : { 1.0, 1e2, 1e4, 1e6 })
  {
    const CylinderState s = massless.solve(v);
    expectFinite(s);
    EXPECT_EQ(s.regime, CylinderRegime::ContactPatch);
    EXPECT_GT(s.xi_plus - s.xi_minus, 0.0);
  }
  // A very stiff surface and a very soft one.
  for (double k : { 1e15, 1e2 })
  {
    p = paperParameters();
    p.k = k;
    const CylinderExact model(p);
    for (double v : { 0.0, 1e-6, 0.5, 30.0, 1e4 })
      expectFinite(model.solve(v));
    EXPECT_EQ(k < 1e3, bool(model.solve(0.0).flags & cylinder_flags::kLargeDeformation)) << "k = " << k;
  }
}

TEST(CylinderRegimes, RandomParametersAcrossTheSupportedRange)
{
  // Log-uniform parameters over the whole supported range (CylinderParameters::kRange*), with its corners
  // drawn often, and speeds from the smallest double to just below the speed of light.
  using P = CylinderParameters;
  std::mt19937_64 rng(2024);
  const auto draw = [&rng](P::Range r) {
    switch (rng() % 6)
    {
      case 0:
        return r.lo;
      case 1:
        return r.hi;
      default:
        return std::pow(10.0, std::uniform_real_distribution<double>(std::log10(r.lo), std::log10(r.hi))(rng));
    }
  };
  for (int i = 0; i < 3000; ++i)
  {
    P p;
    p.R = draw(P::kRangeR);
    p.M = draw(P::kRangeM);
    p.k = draw(P::kRangeK);
    p.gamma = i % 10 == 0 ? 0.0 : draw(P::kRangeGamma);
    p.m = i % 7 == 0 ? 0.0 : draw(P::kRangeSurfaceDensity);
    p.g = draw(P::kRangeG);
    const CylinderExact exact(p);
    const CylinderExpansion expansion(p);
    for (double v : { 0.0, std::numeric_limits<double>::denorm_min(), 1e-12, draw({ 1e-9, 1e8 }), 2.9e8 })
    {
      const CylinderState s = exact.solve(v);
      SCOPED_TRACE(testing::Message() << "R=" << p.R << " M=" << p.M << " k=" << p.k << " gamma=" << p.gamma
                                      << " m=" << p.m << " g=" << p.g << " v=" << v);
      expectFinite(s);
      expectFinite(expansion.solve(v));
      if (s.regime == CylinderRegime::ContactPatch)
      {
        EXPECT_NEAR(s.F_N + s.F_N_impact, p.M * p.g, 1e-9 * p.M * p.g);
      }
    }
  }
}

TEST(CylinderRegimes, ExpansionFlagsItsOwnRange)
{
  const CylinderExpansion model(paperParameters());
  const CylinderExact exact(paperParameters());
  bool left_range = false;
  for (double v = 1e-4; v < 1e3; v *= 1.02)
  {
    const CylinderState s = model.solve(v);
    expectFinite(s);
    const bool flagged = s.flags & cylinder_flags::kExpansionOutOfRange;
    // once out of range it stays out (the truncation error grows with v)
    if (left_range)
    {
      EXPECT_TRUE(flagged) << "v = " << v;
    }
    left_range |= flagged;
    // where it says it is in range, it is within its tolerance of the exact solution (2x margin
    // for the estimate being one term)
    if (!flagged)
    {
      EXPECT_NEAR(s.mu_roll, exact.solve(v).mu_roll, 2.0 * CylinderExpansion::kTolerance * s.mu_roll) << "v = " << v;
    }
  }
  EXPECT_TRUE(left_range);
  EXPECT_TRUE(model.solve(0.01).valid());
  EXPECT_FALSE(model.solve(*model.scales().v_star).valid());  // the next term is 22 % of mu* there
}

}  // namespace
}  // namespace sphere_contact_estimator
