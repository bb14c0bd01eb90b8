// The slow Coulomb-law reference (test/support/brush_coulomb_reference.h, Romano et al. eq. 4b by return mapping
// along the paths, Richardson along them): without spin it is the rigid law, the paper's example point under the
// Coulomb law, the full-sliding and small-slip limits (eqs. 61-62), its error estimate against finer runs, and the
// FASTSIM-like marching scheme (BrushMarching with SlidingLaw::Coulomb) converging to it at first order.

// STL
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

// GTest
#include <gtest/gtest.h>

// Package
#include "brush_brute_force.h"
#include "brush_coulomb_reference.h"
#include "brush_marching.h"
#include "brush_test_support.h"

namespace sphere_contact_estimator
{
namespace
{
using test::coulombReference;
using test::CoulombReference;
using test::figure4Parameters;
using test::forceDistance;
using test::marchCoulomb;

constexpr PressureDistribution kPressures[] = { PressureDistribution::Parabolic, PressureDistribution::Hertzian,
                                                PressureDistribution::Uniform };

TEST(BrushCoulombReference, WithoutSpinItIsTheRigidLaw)
{
  // One drive direction sigma along every path: a sliding bristle's tip slides along sigma under either law. The
  // rigid reference's own error from its runs at half the paths and at half the steps (Simpson along the paths
  // converges slowly on a thin Hertzian sliding band at the trailing rim, where q_z has a square root).
  for (auto pressure : kPressures)
    for (const Eigen::Vector2d& sigma : { Eigen::Vector2d(0.004, -0.002), Eigen::Vector2d(-0.03, 0.05),
                                          Eigen::Vector2d(2.0, 1.0) })
    {
      BrushParameters p = figure4Parameters();
      p.pressure = pressure;
      const CoulombReference c = coulombReference(p, sigma, 0.0, 0.0, 0.0, 200, 500);
      const BrushForces r = test::bruteForceSteady(p, sigma, 0.0, 0.0, 0.0, 400, 1600);
      const double rigid_error = forceDistance(r, test::bruteForceSteady(p, sigma, 0.0, 0.0, 0.0, 200, 1600), p) +
                                 forceDistance(r, test::bruteForceSteady(p, sigma, 0.0, 0.0, 0.0, 400, 800), p);
      const double d = forceDistance(c.forces, r, p);
      std::printf("no spin, %s, sigma (%g, %g): Coulomb - rigid %.1e of mu F_z (errors %.1e, %.1e)\n",
                  toString(pressure), sigma.x(), sigma.y(), d, c.error, rigid_error);
      EXPECT_LE(d, c.error + rigid_error + 1e-12) << toString(pressure);
      EXPECT_LT(c.error, 1e-5) << toString(pressure);
      EXPECT_NEAR(c.forces.sliding_fraction, r.sliding_fraction, 1e-3) << toString(pressure);
      EXPECT_NEAR(c.forces.max_utilisation, r.max_utilisation, 1e-3) << toString(pressure);
      // Not extrapolated: with one drive direction the return mapping is exact between events, so the march has no
      // first-order error, only that of the events' positions within the steps.
      const double d_march = forceDistance(marchCoulomb(p, sigma, 0.0, 0.0, 0.0, 200, 1000), r, p);
      EXPECT_LE(d_march, 1e-6 + rigid_error) << toString(pressure);
    }
}

TEST(BrushCoulombReference, TheExamplePoint)
{
  // Fig. 4 parameters, sigma = 0, phi = 3.33 1/m, no tilt. Two other solvers under the Coulomb law:
  // F_y = 1484.3835 N, M_z = 36.41168 N m; the rigid law gives F_y = 996.56 N, M_z = 45.316 N m.
  const BrushParameters p = figure4Parameters();
  const double muFz = p.mu * p.F_z;
  const auto t0 = std::chrono::steady_clock::now();
  const CoulombReference c = coulombReference(p, { 0.0, 0.0 }, 3.33, 0.0, 0.0, 500, 4000);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("example point, Coulomb: F_x %.6f N, F_y %.6f N, M_z %.7f N m, sliding %.5f, error %.1e of mu F_z "
              "(%.2f s)\n",
              c.forces.F_x, c.forces.F_y, c.forces.M_z, c.forces.sliding_fraction, c.error, seconds);
  EXPECT_LT(c.error, 1e-7);
  EXPECT_NEAR(c.forces.F_x, 0.0, c.error * muFz + 1e-9 * muFz);  // mirror symmetry about y = 0
  EXPECT_NEAR(c.forces.F_y, 1484.3835, c.error * muFz + 5e-5);   // + the quoted values' last digit
  EXPECT_NEAR(c.forces.M_z, 36.41168, c.error * muFz * p.a + 5e-6);
  const BrushForces rigid = test::bruteForceSteady(p, { 0.0, 0.0 }, 3.33, 0.0, 0.0, 1000, 400);
  std::printf("example point, rigid: F_y %.4f N, M_z %.5f N m\n", rigid.F_y, rigid.M_z);
  EXPECT_NEAR(rigid.F_y, 996.56, 0.05);
  EXPECT_NEAR(rigid.M_z, 45.316, 0.005);
}

TEST(BrushCoulombReference, FullSlidingAndSmallSlipLimits)
{
  for (auto pressure : kPressures)
  {
    BrushParameters p = figure4Parameters();
    p.pressure = pressure;
    const double muFz = p.mu * p.F_z;

    // Large slip, |sigma| = 5: the force on the sphere has the sign of sigma. Every bristle slides with u = b sigma /
    // |sigma| (b = mu q_z / k, eq. 4), so that k integral u dA = mu F_z sigma / |sigma|, but for a leading strip
    // 0 < s < s_a where u = sigma s stays below b (eqs. 8, 17c); b is concave along every path (or constant), so a
    // bristle on the bound stays there. The strip's deficit, by an independent quadrature: none under the parabolic
    // pressure (b' < |sigma| from the rim on), small under the Hertzian one, k a b^2 / |sigma| under the uniform one.
    const Eigen::Vector2d sigma(3.0, -4.0), dir = sigma.normalized();
    const double ns = sigma.norm();
    double deficit = 0.0, deficit_moment = 0.0;  // [N], [N m]
    const int n_theta = 2000, n_s = 200;
    for (int i = 0; i < n_theta; ++i)
    {
      const double theta = -0.5 * M_PI + (i + 0.5) * M_PI / n_theta, y = p.a * std::sin(theta);
      const double x_L = p.a * std::cos(theta), dy = x_L * M_PI / n_theta;
      const auto gap = [&](double s) {  // b - |sigma| s along the path, s from the leading edge
        return p.mu / p.k * p.qz(std::pow(x_L - s, 2) + y * y) - ns * s;
      };
      // The gap is concave: it changes sign once (q_z = 0 on the rim); lo keeps r^2 < a^2 in floating point.
      double lo = 1e-10 * p.a, hi = 2.0 * x_L;
      if (gap(lo) <= 0.0)
        continue;  // slides from the rim on
      for (int it = 0; it < 100; ++it)
        (gap(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
      const double s_a = hi;
      for (int j = 0; j < n_s; ++j)  // s = s_a t^2: smooth also where b has a square root at the rim
      {
        const double t = (j + 0.5) / n_s, s = s_a * t * t, ds = 2.0 * s_a * t / n_s;
        const double g = std::max(0.0, gap(s)) * p.k * ds * dy;
        deficit += g;
        deficit_moment += ((x_L - s) * dir.y() - y * dir.x()) * g;
      }
    }
    const CoulombReference slip = coulombReference(p, sigma, 0.0, 0.0, 0.0, 200, 1000);
    std::printf("slip (3, -4), %s: F (%.6f, %.6f) N, M_z %.7f N m; strip: F (%.6f, %.6f) N, M_z %.7f N m; error %.1e\n",
                toString(pressure), slip.forces.F_x, slip.forces.F_y, slip.forces.M_z, (muFz - deficit) * dir.x(),
                (muFz - deficit) * dir.y(), -deficit_moment, slip.error);
    const double tolerance = slip.error * muFz + 1e-8 * muFz;  // + the strip quadrature's own error
    EXPECT_NEAR(slip.forces.F_x, (muFz - deficit) * dir.x(), tolerance) << toString(pressure);
    EXPECT_NEAR(slip.forces.F_y, (muFz - deficit) * dir.y(), tolerance) << toString(pressure);
    EXPECT_NEAR(slip.forces.M_z, -deficit_moment, tolerance * p.a) << toString(pressure);
    EXPECT_GT(slip.forces.sliding_fraction, 0.95) << toString(pressure);

    // Pure spin, huge: q along A_phi x everywhere, M_z = mu integral r q_z dA with the sign of phi: 8/15 mu F_z a
    // (parabolic), 3 pi / 16 (Hertzian), 2/3 (uniform). Under the Coulomb law a sliding bristle's direction lags the
    // drive's by ~b / (phi r^2), which leaves a net force; with the reference's error (~4e-6) ~1e-5 mu F_z here.
    const double lever = pressure == PressureDistribution::Parabolic ? 8.0 / 15.0 :
                         (pressure == PressureDistribution::Hertzian ? 3.0 * M_PI / 16.0 : 2.0 / 3.0);
    const CoulombReference spin = coulombReference(p, { 0.0, 0.0 }, -1e5 / p.a, 0.0, 0.0, 200, 400);
    std::printf("pure spin, %s: M_z / (mu F_z a) %.7f (limit %.7f), |F| / (mu F_z) %.1e, error %.1e\n",
                toString(pressure), spin.forces.M_z / (muFz * p.a), -lever,
                std::hypot(spin.forces.F_x, spin.forces.F_y) / muFz, spin.error);
    EXPECT_NEAR(spin.forces.M_z, -lever * muFz * p.a, 1e-4 * muFz * p.a) << toString(pressure);
    EXPECT_NEAR(std::hypot(spin.forces.F_x, spin.forces.F_y), 0.0, 1e-4 * muFz) << toString(pressure);

    // Small slips (eqs. 61-62): F = C_sigma sigma + C_phi phi e_y, M_z = -C_Msigma_y sigma_y, C_sigma = 8/3 k a^3,
    // C_phi = C_Msigma_y = 3 pi a / 32 C_sigma; eq. 61b leaves out the spin's own moment, k integral y^2 phi
    // (x_L - x) dA = 8/15 k a^5 phi (eq. 23). Sliding near the trailing rim is of relative order 1e-5 here.
    const Eigen::Vector2d small(2e-6, -1e-6);
    const double phi = 2e-4;
    const CoulombReference lin = coulombReference(p, small, phi, 0.0, 0.0, 100, 200);
    const double C_sigma = 8.0 / 3.0 * p.k * std::pow(p.a, 3), C_phi = 3.0 * M_PI * p.a / 32.0 * C_sigma;
    const double F_scale = C_sigma * small.norm();
    EXPECT_NEAR(lin.forces.F_x, C_sigma * small.x(), 2e-4 * F_scale) << toString(pressure);
    EXPECT_NEAR(lin.forces.F_y, C_sigma * small.y() + C_phi * phi, 2e-4 * F_scale) << toString(pressure);
    EXPECT_NEAR(lin.forces.M_z, -C_phi * small.y() + 8.0 / 15.0 * p.k * std::pow(p.a, 5) * phi, 2e-4 * F_scale * p.a)
        << toString(pressure);
  }
}

TEST(BrushCoulombReference, ErrorEstimateCoversAFinerRun)
{
  struct Point
  {
    const char* name;
    PressureDistribution pressure;
    bool tilt;
    Eigen::Vector2d sigma;
    double phi, chi;
  };
  using P = PressureDistribution;
  for (const Point& q : { Point{ "slip and spin", P::Parabolic, false, { 0.05, 0.02 }, 3.33, 1.0 },
                          Point{ "Hertzian, tilt", P::Hertzian, true, { 0.03, -0.01 }, 5.0, 0.7 },
                          Point{ "uniform, tilt", P::Uniform, true, { -0.01, 0.02 }, -7.0, 1.2 } })
  {
    BrushParameters p = figure4Parameters(q.tilt);
    p.pressure = q.pressure;
    const double pg = q.chi * q.phi, pp = q.phi - pg;
    const CoulombReference coarse = coulombReference(p, q.sigma, q.phi, pg, pp, 100, 250);
    const CoulombReference fine = coulombReference(p, q.sigma, q.phi, pg, pp, 400, 1000);
    const double d = forceDistance(coarse.forces, fine.forces, p);
    std::printf("%s: coarse - fine %.1e of mu F_z, estimates %.1e (coarse), %.1e (fine)\n", q.name, d, coarse.error,
                fine.error);
    EXPECT_LE(d, coarse.error) << q.name;
    EXPECT_LT(fine.error, coarse.error / 4.0) << q.name;  // second order along the paths after extrapolation
    EXPECT_GT(coarse.error, 0.0) << q.name;
    // Not extrapolated, the march is first order along the paths: its error halves with the step.
    const double e1 = forceDistance(marchCoulomb(p, q.sigma, q.phi, pg, pp, 400, 250), fine.forces, p);
    const double e2 = forceDistance(marchCoulomb(p, q.sigma, q.phi, pg, pp, 400, 500), fine.forces, p);
    std::printf("%s: march at 250 and 500 steps %.2e, %.2e of mu F_z\n", q.name, e1, e2);
    EXPECT_GT(e1 / e2, 1.8) << q.name;
    EXPECT_LT(e1 / e2, 2.2) << q.name;
  }
}

TEST(BrushCoulombReference, FastsimLikeMarchingConvergesToIt)
{
  // BrushMarching with SlidingLaw::Coulomb caps each cell by the return mapping: first order, so its error against
  // the reference about halves as the resolution doubles. With SlidingLaw::Rigid it stays the Sect. 6 law, which
  // differs at this point by far more than either error.
  BrushParameters p = figure4Parameters(true);
  const Eigen::Vector2d sigma(0.05, 0.02);
  const double phi = 3.33, pg = 0.9 * phi, pp = phi - pg;
  const CoulombReference c = coulombReference(p, sigma, phi, pg, pp, 400, 1000);
  double previous = INFINITY;
  for (int resolution : { 16, 32, 64, 128 })
  {
    p.resolution = resolution;
    p.sliding_law = SlidingLaw::Coulomb;
    const double e = forceDistance(test::BrushMarching(p).evaluate(sigma, phi, pg, pp), c.forces, p);
    p.sliding_law = SlidingLaw::Rigid;
    const double r = forceDistance(test::BrushMarching(p).evaluate(sigma, phi, pg, pp), c.forces, p);
    std::printf("marching at resolution %d: Coulomb %.2e, rigid %.2e of mu F_z from the Coulomb reference\n",
                resolution, e, r);
    EXPECT_LT(e, 0.6 * previous) << resolution;
    EXPECT_GT(r, 10.0 * e) << resolution;
    previous = e;
  }
  EXPECT_LT(previous, 2e-3);
}

TEST(BrushCoulombReference, NoSteadyStateInsideTheTiltingRadius)
{
  const BrushParameters p = figure4Parameters(true);
  const CoulombReference c = coulombReference(p, { 0.01, 0.0 }, 25.0, 25.0, 0.0, 20, 20);  // |R_gamma| = 0.8 a
  EXPECT_EQ(c.forces.flags, brush_flags::kNoSteadyStateTilt);
  EXPECT_EQ(c.forces.F_x, 0.0);
  EXPECT_EQ(c.forces.F_y, 0.0);
  EXPECT_EQ(c.forces.M_z, 0.0);
  // Without tilt the same spin is a plain Sect. 3 case.
  EXPECT_EQ(coulombReference(figure4Parameters(false), { 0.01, 0.0 }, 25.0, 25.0, 0.0, 20, 20).forces.flags, 0u);
}

}  // namespace
}  // namespace sphere_contact_estimator
