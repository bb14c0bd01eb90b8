// The tabulated model: its measured error, its convergence with table size, and its fallbacks.

// STL
#include <cmath>
#include <random>

// GTest
#include <gtest/gtest.h>

// Package
#include "cylinder_test_support.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

namespace sphere_contact_estimator
{
namespace
{
using test::paperParameters;
using test::variedParameters;

TEST(CylinderTable, MeasuredErrorBoundsRandomSpeeds)
{
  // The error measured on construction (cell midpoints) bounds the error anywhere in the table.
  std::mt19937_64 rng(42);
  for (const CylinderParameters& p : variedParameters())
  {
    const CylinderTable table(p);
    const CylinderExact exact(p);
    ASSERT_GT(table.vMax(), 0.0);
    const CylinderTable::Error& e = table.measuredError();
    std::uniform_real_distribution<double> speed(0.0, table.vMax());
    double worst_mu = 0.0;
    for (int i = 0; i < 2000; ++i)
    {
      const double v = speed(rng);
      const CylinderState a = table.solve(v), b = exact.solve(v);
      worst_mu = std::max(worst_mu, std::abs(a.mu_roll - b.mu_roll));
      EXPECT_LE(std::abs(a.mu_roll - b.mu_roll), 1.5 * e.mu_roll + 1e-15) << "v = " << v;
      EXPECT_LE(std::abs(a.h - b.h), 1.5 * e.h + 1e-15) << "v = " << v;
      EXPECT_LE(std::abs(a.xi_minus - b.xi_minus), 1.5 * e.xi_minus + 1e-15) << "v = " << v;
      EXPECT_EQ(a.regime, b.regime);
      EXPECT_DOUBLE_EQ(table.muRoll(v), a.mu_roll);
    }
    // and the measurement is not a loose bound
    EXPECT_GT(worst_mu, 0.1 * e.mu_roll);
    // The default table is accurate to better than 1e-6 of the largest mu_roll.
    EXPECT_LT(e.mu_roll, 1e-6 * table.solve(*table.scales().v_star).mu_roll);
  }
}

TEST(CylinderTable, ErrorFallsAsTheFourthPowerOfTheSpacing)
{
  // Cubic Hermite interpolation through exact values and exact slopes: error ~ n^-4 (spacing in u).
  const CylinderParameters p = paperParameters();
  double previous = 0.0;
  for (std::size_t n : { 65u, 129u, 257u, 513u })
  {
    const CylinderTable table(p, n);
    const double e = table.measuredError().mu_roll;
    if (previous > 0.0)
    {
      EXPECT_NEAR(std::log2(previous / e), 4.0, 0.35) << "n = " << n;
    }
    previous = e;
  }
}

TEST(CylinderTable, OutsideTheTable)
{
  const CylinderParameters p = paperParameters();
  const CylinderExact exact(p);
  const CylinderTable table(p, 64, 2.0);  // a user range well below v_c
  EXPECT_DOUBLE_EQ(table.vMax(), 2.0);
  // between v_max and v_c: exact solver, flagged, still valid
  const CylinderState mid = table.solve(5.0);
  EXPECT_TRUE(mid.flags & cylinder_flags::kTableFallback);
  EXPECT_TRUE(mid.valid());
  EXPECT_DOUBLE_EQ(mid.mu_roll, exact.solve(5.0).mu_roll);
  // past v_c: the closed-form point contact, no fallback flag
  const double v = 2.0 * table.scales().v_critical;
  const CylinderState far = table.solve(v);
  EXPECT_EQ(far.regime, CylinderRegime::PointContact);
  EXPECT_FALSE(far.flags & cylinder_flags::kTableFallback);
  EXPECT_DOUBLE_EQ(far.mu_roll, exact.solve(v).mu_roll);
  // the requested range is capped at v_c
  const CylinderTable capped(p, 64, 1e3);
  EXPECT_LT(capped.vMax(), table.scales().v_critical);
  EXPECT_GT(capped.vMax(), 0.999 * table.scales().v_critical);
}

TEST(CylinderTable, NoTableWhereThePatchRegimeHasAGap)
{
  CylinderParameters p = paperParameters();
  p.m = 2.0 * p.gamma * p.gamma / p.k;  // m k > gamma^2
  const CylinderTable table(p);
  EXPECT_EQ(table.vMax(), 0.0);
  const double v = 0.1 * table.scales().v_critical;
  const CylinderState s = table.solve(v);
  EXPECT_EQ(s.regime, CylinderRegime::ContactPatch);
  EXPECT_TRUE(s.flags & cylinder_flags::kTableFallback);
  EXPECT_DOUBLE_EQ(s.mu_roll, CylinderExact(p).solve(v).mu_roll);
}

}  // namespace
}  // namespace sphere_contact_estimator
