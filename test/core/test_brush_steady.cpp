// The steady-state model with limited friction: against the closed forms, its convergence, symmetry, the
// friction limit, tilt and Assumption 4.1.

// STL
#include <cmath>
#include <random>
#include <vector>

// GTest
#include <gtest/gtest.h>

// Package
#include "brush_test_support.h"
#include "sphere_contact_estimator/core/brush_steady.h"
#include "sphere_contact_estimator/core/friction_cap.h"

namespace sphere_contact_estimator
{
namespace
{
using test::figure4Parameters;
using test::forceDistance;

// Observed order from errors at resolutions n, 2n, 4n, ...: least-squares slope of log e over log n.
double observedOrder(const std::vector<int>& n, const std::vector<double>& e)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(n.size());
  for (std::size_t i = 0; i < n.size(); ++i)
  {
    const double x = std::log(n[i]), y = std::log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return -(m * sxy - sx * sy) / (m * sxx - sx * sx);
}

TEST(BrushSteady, VanishingSlidingMatchesEqs23And51)
{
  // mu large: no bristle reaches the bound except in a band of width ~1e-9 a at the trailing edge.
  const Eigen::Vector2d sigma(0.01, -0.02);
  const double phi = 3.33, chi = 0.9;
  for (bool tilt : { false, true })
  {
    BrushParameters p = figure4Parameters(tilt, 128);
    p.mu = 1e6;
    const BrushForces f = BrushSteady(p).evaluate(sigma, phi, chi * phi, (1 - chi) * phi);
    const BrushForces g = test::integrateField(
        [&](const Eigen::Vector2d& x) {
          return tilt ? brush_closed_form::steadyTilting(x, p.a, sigma, chi * phi, (1 - chi) * phi)
                      : brush_closed_form::steadyRolling(x, p.a, sigma, phi);
        },
        p.a, p.k, 600);
    const double scale = std::hypot(g.F_x, g.F_y);
    EXPECT_NEAR(f.F_x, g.F_x, 2e-4 * scale) << "tilt " << tilt;
    EXPECT_NEAR(f.F_y, g.F_y, 2e-4 * scale) << "tilt " << tilt;
    EXPECT_NEAR(f.M_z, g.M_z, 2e-4 * scale * p.a) << "tilt " << tilt;
    EXPECT_LT(f.sliding_fraction, 0.01);
  }
}

TEST(BrushSteady, ConvergesWithResolution)
{
  // Second order without sliding (smooth field, midpoint rules); with partial sliding the kinks where
  // bristles reach and leave the bound lower it. Errors against a run at 16x the finest resolution.
  struct Case
  {
    const char* name;
    double mu, sigma_x, sigma_y, phi;
    bool tilt;
    double min_order;
  };
  for (const Case& c : { Case{ "adhesion", 1e6, 0.01, 0.02, 3.33, false, 1.8 },
                         Case{ "adhesion, tilt", 1e6, 0.01, 0.02, 3.33, true, 1.8 },
                         Case{ "partial sliding", 1.0, 0.05, 0.02, 3.33, false, 0.9 },
                         Case{ "partial sliding, tilt", 1.0, 0.05, 0.02, 3.33, true, 0.9 } })
  {
    const auto run = [&](int n) {
      BrushParameters p = figure4Parameters(c.tilt, n);
      p.mu = c.mu;
      return BrushSteady(p).evaluate({ c.sigma_x, c.sigma_y }, c.phi, 0.9 * c.phi, 0.1 * c.phi);
    };
    const BrushParameters p = figure4Parameters();
    const BrushForces ref = run(1024);
    std::vector<int> n{ 16, 32, 64 };
    std::vector<double> e;
    for (int r : n)
      e.push_back(forceDistance(run(r), ref, p));
    const double q = observedOrder(n, e);
    RecordProperty(std::string("order ") + c.name, std::to_string(q));
    std::printf("steady, %s: errors %.2e %.2e %.2e of mu F_z, observed order %.2f\n", c.name, e[0], e[1], e[2], q);
    EXPECT_GT(q, c.min_order) << c.name;
    EXPECT_LT(e.back(), 0.01) << c.name;  // within 1 % of mu F_z at resolution 64
  }
}

TEST(BrushSteady, MirrorSymmetry)
{
  // Reflecting y -> -y maps (sigma_y, phi) to (-sigma_y, -phi) and flips F_y and M_z, keeps F_x.
  for (bool tilt : { false, true })
  {
    const BrushSteady model(figure4Parameters(tilt, 48));
    for (const auto& [sx, sy, phi] : { std::tuple{ 0.1, 0.05, 3.33 }, { -0.3, 0.2, -8.0 }, { 0.02, -0.01, 1.0 } })
    {
      const BrushForces a = model.evaluate({ sx, sy }, phi, 0.9 * phi, 0.1 * phi);
      const BrushForces b = model.evaluate({ sx, -sy }, -phi, -0.9 * phi, -0.1 * phi);
      EXPECT_NEAR(a.F_x, b.F_x, 1e-9 * 3000);
      EXPECT_NEAR(a.F_y, -b.F_y, 1e-9 * 3000);
      EXPECT_NEAR(a.M_z, -b.M_z, 1e-9 * 3000 * 0.05);
      EXPECT_NEAR(a.sliding_fraction, b.sliding_fraction, 1e-12);
    }
  }
}

TEST(BrushSteady, NeverExceedsTheFrictionLimit)
{
  // |F_t| <= mu F_z holds bristle by bristle, so at every input; huge slips saturate onto the circle.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (bool tilt : { false, true })
  {
    const BrushParameters p = figure4Parameters(tilt, 24);
    const BrushSteady model(p);
    for (int i = 0; i < 300; ++i)
    {
      const double scale = std::pow(10.0, 3.0 * u(rng) - 1.0);  // 1e-4 .. 1e2
      const Eigen::Vector2d sigma(scale * u(rng), scale * u(rng));
      const double phi = 20.0 * scale * u(rng), chi = 0.5 + 0.5 * u(rng);
      const BrushForces f = model.evaluate(sigma, phi, chi * phi, (1 - chi) * phi);
      if (f.flags & brush_flags::kNoSteadyStateTilt)
        continue;
      EXPECT_LE(std::hypot(f.F_x, f.F_y), p.mu * p.F_z * (1 + 1e-9));
      EXPECT_LE(f.max_utilisation, 1.0);
      EXPECT_GE(f.sliding_fraction, 0.0);
      EXPECT_LE(f.sliding_fraction, 1.0);
    }
    const BrushForces big = model.evaluate({ 1e6, 0.0 }, 0.0, 0.0, 0.0);
    EXPECT_NEAR(big.F_x, p.mu * p.F_z, 1e-3 * p.mu * p.F_z);  // full sliding: the whole mu F_z
    EXPECT_NEAR(big.sliding_fraction, 1.0, 1e-12);
  }
}

TEST(BrushSteady, TiltApproachesNoTiltAsTheTiltingRadiusGrows)
{
  // The paper explains the overlap of its solid and dashed curves by large |R_gamma|: curved paths and
  // the turn coupling change the forces in proportion to 1 / |R_gamma| = |phi_gamma| (at fixed slips)
  // and, for a pure spin, at second order, against the spin's own first-order effect.
  BrushParameters p = figure4Parameters(true, 256);
  p.mu = 1e6;  // vanishing sliding: the comparison is about the kinematics
  const BrushSteady tilted(p);
  p.tilt = false;
  const BrushSteady straight(p);
  double previous_slip = INFINITY, previous_spin = INFINITY;
  for (double phi_gamma : { 1.0, 0.25, 0.0625 })
  {
    const Eigen::Vector2d sigma(0.01, 0.005);
    const double d = forceDistance(tilted.evaluate(sigma, phi_gamma, phi_gamma, 0.0), straight.evaluate(sigma, phi_gamma, 0.0, 0.0), p);
    const double phi = phi_gamma / 0.9;  // chi_gamma = 0.9 as in Fig. 4
    const BrushForces spin_only = straight.evaluate(Eigen::Vector2d::Zero(), phi, 0.0, 0.0);
    const double r = forceDistance(tilted.evaluate(Eigen::Vector2d::Zero(), phi, phi_gamma, phi - phi_gamma), spin_only, p) /
                     forceDistance(spin_only, BrushForces{}, p);
    std::printf("|R_gamma| = %.3g m: tilt - no tilt = %.2e mu F_z at sigma = (0.01, 0.005); %.2e of the effect of a pure spin\n",
                1.0 / phi_gamma, d, r);
    EXPECT_LT(d, 0.3 * previous_slip) << "phi_gamma " << phi_gamma;
    EXPECT_LT(r, 0.3 * previous_spin) << "phi_gamma " << phi_gamma;
    previous_slip = d;
    previous_spin = r;
  }
  EXPECT_LT(previous_slip, 1e-4);
  EXPECT_LT(previous_spin, 2e-3);
}

TEST(BrushSteady, TiltingRadiusBelowThePatchRadiusIsFlagged)
{
  const BrushParameters p = figure4Parameters(true);
  const BrushSteady model(p);
  const BrushForces inside = model.evaluate({ 0.0, 0.0 }, 30.0, 30.0, 0.0);  // |R_gamma| = a / 1.5
  EXPECT_TRUE(inside.flags & brush_flags::kNoSteadyStateTilt);
  EXPECT_FALSE(inside.valid());
  EXPECT_TRUE(model.evaluate({ 0.0, 0.0 }, 19.0, 19.0, 0.0).valid());  // |R_gamma| = 1.05 a
  // without tilt the same spin is fine (straight paths)
  EXPECT_TRUE(BrushSteady(figure4Parameters(false)).evaluate({ 0.0, 0.0 }, 30.0, 30.0, 0.0).valid());
}

TEST(BrushSteady, CappingAlongThePathIsNotPointwiseClipping)
{
  // conventions.md: with spin, bristles that slid near the leading edge re-adhere from their capped
  // deflection, so clipping the unbounded eq. 23 field point by point is a different model, off by
  // several per cent of mu F_z. Without spin the two agree.
  const BrushParameters p = figure4Parameters(false, 256);
  const FrictionCap cap(p);
  const auto clipped = [&](const Eigen::Vector2d& sigma, double phi) {
    return test::integrateField(
        [&](const Eigen::Vector2d& x) {
          Eigen::Vector2d u = brush_closed_form::steadyRolling(x, p.a, sigma, phi);
          cap.apply(u, x, Eigen::Vector2d(sigma.x() - phi * x.y(), sigma.y() + phi * x.x()));
          return u;
        },
        p.a, p.k, 400);
  };
  const BrushSteady model(p);
  for (const Eigen::Vector2d& sigma : { Eigen::Vector2d(0.05, 0.02), Eigen::Vector2d(0.0, -0.05) })
    EXPECT_LT(forceDistance(model.evaluate(sigma, 0.0, 0.0, 0.0), clipped(sigma, 0.0), p), 2e-3);
  // Spin against a lateral slip: u_y of eq. 23 rises, then falls towards the trailing edge, where the
  // capped bristles re-adhere; F_y differs by 8 % of mu F_z.
  const Eigen::Vector2d sigma(0.0, -0.05);
  EXPECT_GT(forceDistance(model.evaluate(sigma, 10.0, 0.0, 0.0), clipped(sigma, 10.0), p), 0.05);
}

TEST(BrushSteady, StandstillAndDegenerateInputs)
{
  BrushSteady model(figure4Parameters());
  const BrushForces s = model.update(ContactKinematics{}, 0.0);
  EXPECT_TRUE(s.flags & brush_flags::kStandstill);
  BrushParameters p = figure4Parameters();
  p.mu = 0.0;
  const BrushForces f = BrushSteady(p).evaluate({ 0.1, 0.1 }, 1.0, 0.0, 0.0);
  EXPECT_EQ(f.F_x, 0.0);
  EXPECT_EQ(f.F_y, 0.0);
  p = figure4Parameters();
  p.F_z = 0.0;
  EXPECT_EQ(BrushSteady(p).evaluate({ 0.1, 0.1 }, 1.0, 0.0, 0.0).F_x, 0.0);
}

}  // namespace
}  // namespace sphere_contact_estimator
