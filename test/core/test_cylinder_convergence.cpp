// The exact solution against the small-velocity expansions as v -> 0, the eq. 16 discrepancy, and the
// slopes of the exact solution against finite differences.

// STL
#include <cmath>
#include <vector>

// GTest
#include <gtest/gtest.h>

// Package
#include "cylinder_test_support.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"

namespace sphere_contact_estimator
{
namespace
{
using test::paperParameters;
using test::variedParameters;

// Speeds v0 / 2^n, small enough for the expansions to be in their asymptotic range.
std::vector<double> halvingSpeeds(const CylinderModel& model)
{
  const double v0 = 0.05 * *model.scales().v_star;
  std::vector<double> v;
  for (int n = 0; n < 6; ++n)
    v.push_back(v0 / std::pow(2.0, n));
  return v;
}

// log2 of successive error ratios: the observed order of err(v) ~ v^q.
std::vector<double> observedOrders(const std::vector<double>& err)
{
  std::vector<double> q;
  for (std::size_t i = 1; i < err.size(); ++i)
    q.push_back(std::log2(err[i - 1] / err[i]));
  return q;
}

TEST(CylinderConvergence, ExactMeetsExpansionsAtTheExpectedOrder)
{
  // Continuing the perturbation solution of eq. 18 one order further gives: xi_+, xi_- and h carry a v^3
  // term beyond eqs. 21, 23, 24, and mu_roll has no v^3 term beyond eq. 27, so its error is O(v^4).
  for (const CylinderParameters& p : variedParameters())
  {
    const CylinderExact exact(p);
    const CylinderExpansion expansion(p);
    std::vector<double> e_h, e_xp, e_xm, e_mu;
    for (double v : halvingSpeeds(exact))
    {
      const CylinderState a = exact.solve(v), b = expansion.solve(v);
      ASSERT_TRUE(b.valid()) << "v = " << v;
      e_h.push_back(std::abs(a.h - b.h));
      e_xp.push_back(std::abs(a.xi_plus - b.xi_plus));
      e_xm.push_back(std::abs(a.xi_minus - b.xi_minus));
      e_mu.push_back(std::abs(a.mu_roll - b.mu_roll));
      // the expansion's own error estimate is the size of the actual error
      EXPECT_NEAR(b.mu_roll_error, e_mu.back(), 0.1 * e_mu.back()) << "v = " << v;
    }
    for (double q : observedOrders(e_h))
      EXPECT_NEAR(q, 3.0, 0.1);
    for (double q : observedOrders(e_xp))
      EXPECT_NEAR(q, 3.0, 0.1);
    for (double q : observedOrders(e_xm))
      EXPECT_NEAR(q, 3.0, 0.1);
    for (double q : observedOrders(e_mu))
      EXPECT_NEAR(q, 4.0, 0.1);
  }
}

TEST(CylinderConvergence, Eq17NotA14AgreesWithEq27)
{
  // The two lines of eq. 16 differ in the impact term: m ydot^2(xi_+)/2 v (line 1, eq. A14) against
  // m v^3 2h/R (line 2, eq. 17); ydot(xi_+) = -v xi_+/R makes the first half the second. Only the second
  // reproduces the v^2 term of eq. 27: (mu - eq. 27)/v^2 -> 0 for eq. 17, while the A14 variant misses it
  // by 3 m / (4 xi0 k) (the impact part of the v^2 coefficient, halved).
  for (const CylinderParameters& p : variedParameters())
  {
    if (p.m == 0.0)
      continue;  // without surface mass the two lines coincide
    const CylinderExact exact(p);
    const CylinderExpansion expansion(p);
    const double offset = 3.0 * p.m / (4.0 * exact.scales().xi0 * p.k);
    double previous = INFINITY;
    for (double v : halvingSpeeds(exact))
    {
      const CylinderState s = exact.solve(v);
      const double mu27 = expansion.solve(v).mu_roll;
      const double mu17 = s.mu_roll;
      const double muA14 = p.R * (s.F_R - 0.5 * s.F_R_impact) / (p.M * p.g);
      const double r17 = (mu17 - mu27) / (v * v), rA14 = (muA14 - mu27) / (v * v);
      EXPECT_LT(std::abs(r17), 0.3 * previous) << "v = " << v;  // vanishes (like v^2)
      previous = std::abs(r17);
      EXPECT_NEAR(rA14, -offset, 0.02 * offset + std::abs(r17)) << "v = " << v;  // does not vanish
    }
    EXPECT_LT(previous, 1e-3 * offset);
  }
}

TEST(CylinderConvergence, SlopesMatchFiniteDifferences)
{
  // The implicit-differentiation slopes that feed the table, against central differences.
  for (const CylinderParameters& p : variedParameters())
  {
    const CylinderExact model(p);
    const double v_c = model.scales().v_critical;
    for (double v : { 1e-3, 0.05, 0.45, 1.0, 4.0, 20.0, 30.0, 80.0 })
    {
      if (std::isfinite(v_c) && std::abs(v / v_c - 1.0) < 0.01)
        continue;  // the kink at v_c
      CylinderExact::Slopes d;
      model.solve(v, &d);
      const double dv = 1e-5 * v;
      const CylinderState a = model.solve(v - dv), b = model.solve(v + dv);
      const double scale_h = model.scales().h0 / v, scale_x = model.scales().xi0 / v;
      EXPECT_NEAR(d.dh_dv, (b.h - a.h) / (2 * dv), 1e-6 * scale_h) << "v = " << v;
      EXPECT_NEAR(d.dxi_minus_dv, (b.xi_minus - a.xi_minus) / (2 * dv), 1e-6 * scale_x) << "v = " << v;
      EXPECT_NEAR(d.dmu_roll_dv, (b.mu_roll - a.mu_roll) / (2 * dv), 1e-6 * scale_x) << "v = " << v;
    }
  }
}

// The root of eq. 18 that the iteration limit stops short of is flagged (and invalidates the state); the
// default limit is never reached over the paper's speeds.
TEST(CylinderConvergence, UnconvergedRootIsFlagged)
{
  CylinderExact exact(paperParameters());
  for (double v : { 0.01, 0.1, 1.0, 10.0 })
  {
    const CylinderState converged = exact.solve(v);
    EXPECT_EQ(converged.flags & cylinder_flags::kRootNotConverged, 0u) << v;
  }
  exact.setMaxIterations(1);
  int flagged = 0;
  for (double v : { 0.01, 0.1, 1.0, 10.0 })
  {
    const CylinderState s = exact.solve(v);
    if (s.regime != CylinderRegime::ContactPatch)
      continue;
    EXPECT_TRUE(s.flags & cylinder_flags::kRootNotConverged) << v;
    EXPECT_FALSE(s.valid()) << v;
    ++flagged;
  }
  EXPECT_GT(flagged, 0);
}

}  // namespace
}  // namespace sphere_contact_estimator
