// Eq. (4b)'s sliding pieces by the stiff collocation (path/coulomb_collocation.h) against the general stepper
// (CoulombStepper::General, Magnus steps of the half-angle system) and against a brute-force return-mapping march along
// single paths: the two steppers agree within the collocation's estimate on seeded random paths over the envelope, the
// collocation passes a spin pole (where the drive vanishes and flips) and finds re-adhesions, and it converges with the
// tolerance on a path sliding from rim to rim.

// STL
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <random>

// GTest
#include <gtest/gtest.h>

// Package
#include "brush_test_support.h"
#include "bristle_path.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"

namespace sphere_contact_estimator
{
namespace
{
using cd = std::complex<double>;
using test::figure4Parameters;

double distance(const PathIntegrals& a, const PathIntegrals& b)
{
  return std::max({ std::abs(a.force.real() - b.force.real()), std::abs(a.force.imag() - b.force.imag()),
                    std::abs(a.moment - b.moment) });
}

PathIntegrals general(const BristleField& f, const BristlePath& path, double tolerance, bool keep = false)
{
  return solvePath(f, path, tolerance, keep, kUnlimitedWork, CoulombStepper::General);
}

// A straight path of the parabolic bound marched by the return mapping (backward Euler of eq. 4b, FASTSIM's step):
// the trial deflection propagated as adhering, scaled back onto the bound where beyond it; the trapezoid rule.
PathIntegrals march(const BristleField& f, const BristlePath& path, int n)
{
  PathIntegrals out;
  const double L = path.length, h = L / n, x_e = path.entry.real(), y0 = path.entry.imag();
  cd u = 0.0;
  for (int k = 0; k < n; ++k)
  {
    const double t0 = k * h, t1 = t0 + h;
    cd trial = u + f.drive(cd(x_e - t0 - 0.5 * h, y0)) * h;
    const double b = t1 * (L - t1);  // 1 - r^2 on the path
    if (std::abs(trial) > b)
      trial *= b / std::abs(trial);
    const cd z0(x_e - t0, y0), z1(x_e - t1, y0);
    out.force += 0.5 * h * (u + trial);
    out.moment += 0.5 * h * (std::imag(std::conj(z0) * u) + std::imag(std::conj(z1) * trial));
    u = trial;
  }
  return out;
}

TEST(BrushCollocation, AgreesWithTheGeneralStepperOnRandomPaths)
{
  // Over the envelope's slips and spins (both laws' random tests draw the same), the three pressures, with and without
  // tilt, paths anywhere across the patch, tolerances 1e-3 to 1e-7: the difference to the general stepper run 1e4 times
  // tighter is within the collocation's own estimate at every path.
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0, sliding = 0;
  double worst = 0.0;
  for (int i = 0; i < 600; ++i)
  {
    BrushParameters p;
    p.pressure = static_cast<PressureDistribution>(i % 3);
    p.tilt = (i / 3) % 2;
    const Eigen::Vector2d sigma(0.5 * u(rng), 0.5 * u(rng));
    const double phi = 20.0 * u(rng), chi = u(rng);
    double phi_gamma = chi * phi;
    const double phi_psi = phi - phi_gamma;
    if (std::abs(phi_gamma) * p.a > 0.95)
      phi_gamma = std::copysign(0.95 / p.a, phi_gamma);
    BristleField f;
    ASSERT_TRUE(BrushSteady(p).field(sigma, phi, phi_gamma, phi_psi, f));
    const BristlePath path = BristlePath::across(f, 1.5 * u(rng));
    const double tolerance = std::pow(10.0, -3.0 - 4.0 * (0.5 + 0.5 * u(rng)));
    const PathIntegrals a = solvePath(f, path, tolerance);
    const PathIntegrals ref = general(f, path, std::min(1e-11, 1e-4 * tolerance));
    const double error = distance(a, ref);
    EXPECT_LE(error, a.error + ref.error) << "path " << i << " tolerance " << tolerance << " pressure "
                                          << toString(p.pressure) << " tilt " << p.tilt;
    EXPECT_FALSE(a.truncated) << "path " << i;
    worst = std::max(worst, error / (a.error + ref.error));
    ++checked;
    sliding += a.sliding > 0.0;
  }
  std::printf("collocation against the general stepper: %d paths (%d sliding), largest error / estimate %.2f\n", checked,
              sliding, worst);
  EXPECT_GT(sliding, 400);
}

TEST(BrushCollocation, PassesThroughASpinPole)
{
  // Fig. 4's parameters, sigma = (0, 0.1): the pole lies on the path y = 0, where the drive vanishes and reverses. The
  // bristle, sliding along it, keeps its direction there (the law turns it only as far as its tip moves, and by symmetry
  // not at all) and slides on to the trailing edge, the bound shrinking faster than the reversed drive pulls it in.
  // Paths beside it turn smoothly away: the path integrals are continuous across y = 0, and the collocation agrees with
  // a brute-force march on it and beside it.
  const BrushSteady model(figure4Parameters());
  BristleField f;
  ASSERT_TRUE(model.field({ 0.0, 0.1 }, 3.33, 0.0, 0.0, f));
  ASSERT_NEAR(f.pole().imag(), 0.0, 1e-15);
  for (double theta : { 0.0, 1e-3, -0.05 })
  {
    const BristlePath path = BristlePath::across(f, theta);
    const PathIntegrals a = solvePath(f, path, 1e-8);
    // the march converges at first order: its error at n steps is about its change to 2n
    const PathIntegrals m1 = march(f, path, 200000), m2 = march(f, path, 400000);
    const double march_error = 2.0 * distance(m1, m2);
    EXPECT_LE(distance(a, m2), a.error + march_error) << "theta " << theta;
    EXPECT_LT(march_error, 1e-6);
    std::printf("through the pole, theta %g: F (%.7f, %.7f), M %.7f; march (%.7f, %.7f), %.7f; estimate %.1e\n", theta,
                a.force.real(), a.force.imag(), a.moment, m2.force.real(), m2.force.imag(), m2.moment, a.error);
  }
}

TEST(BrushCollocation, FindsTheReAdhesions)
{
  // Spin against slip, where bristles slide, re-adhere beside the pole and slide again: the pieces the collocation finds
  // are the general stepper's, their ends within 1e-6 of travel, and the integrals within the estimates.
  const BrushSteady model(figure4Parameters());
  BristleField f;
  ASSERT_TRUE(model.field({ 0.0, -0.05 }, 10.0, 0.0, 0.0, f));
  int with_readhesion = 0;
  for (int j = 0; j < 41; ++j)
  {
    const BristlePath path = BristlePath::across(f, -1.4 + 2.8 * j / 40.0);
    const PathIntegrals a = solvePath(f, path, 1e-7, true);
    const PathIntegrals b = general(f, path, 1e-10, true);
    ASSERT_EQ(a.pieces, b.pieces) << "path " << j;
    for (int k = 0; k < a.pieces; ++k)
    {
      EXPECT_EQ(a.piece[k].adhering, b.piece[k].adhering);
      EXPECT_NEAR(a.piece[k].end, b.piece[k].end, 1e-6) << "path " << j << " piece " << k;
    }
    EXPECT_LE(distance(a, b), a.error + b.error) << "path " << j;
    with_readhesion += a.pieces > 2;
  }
  EXPECT_GE(with_readhesion, 5);
}

TEST(BrushCollocation, ConvergesRimToRimWithTheTolerance)
{
  // The common case, a path sliding from rim to rim (Fig. 4's large slips): at each tolerance the collocation is within
  // its estimate of the general stepper run far tighter, and its estimate falls with the tolerance.
  const BrushSteady model(figure4Parameters());
  BristleField f;
  ASSERT_TRUE(model.field({ 0.5, 0.05 }, 3.33, 0.0, 0.0, f));
  const BristlePath path = BristlePath::across(f, 0.2);
  const PathIntegrals ref = general(f, path, 1e-11);
  double previous = INFINITY;
  for (double tolerance : { 1e-3, 1e-4, 1e-5, 1e-6, 1e-7 })
  {
    const PathIntegrals a = solvePath(f, path, tolerance);
    ASSERT_NEAR(a.sliding, path.length, 1e-12);
    EXPECT_LE(distance(a, ref), a.error + ref.error) << "tolerance " << tolerance;
    EXPECT_LE(a.error, tolerance);
    EXPECT_LT(a.error, previous);
    previous = a.error;
    std::printf("rim to rim at %.0e: error %.1e, estimate %.1e, work %ld\n", tolerance, distance(a, ref), a.error, a.work);
  }
}

}  // namespace
}  // namespace sphere_contact_estimator
