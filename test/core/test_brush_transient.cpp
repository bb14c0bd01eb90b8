// The transient model under both sliding laws: against the closed-form transients (eqs. 28, 55), its steady state
// against the steady model, pure spin (Sect. 5), convergence, its error estimate over noisy histories, passivity, and
// how it is stepped.

// STL
#include <cmath>
#include <random>
#include <vector>

// Boost
#include <boost/math/constants/constants.hpp>

// GTest
#include <gtest/gtest.h>

// Package
#include "brush_test_support.h"
#include "bristle_path.h"
#include "noisy_history.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"

namespace sphere_contact_estimator
{
namespace
{
using test::figure4Parameters;
using test::forceDistance;
using test::kSlidingLaws;
namespace cf = brush_closed_form;

// Largest |u - oracle| over the bristles, relative to the largest |oracle|. Bristles where the oracle
// itself breaks the friction bound (even a huge mu caps within ~1e-9 a of the edge, where q_z -> 0)
// are outside the vanishing-sliding oracle's validity and skipped.
template <class Oracle>
double fieldError(const BrushTransient& model, Oracle oracle)
{
  const BrushParameters& p = model.parameters();
  double error = 0.0, scale = 0.0;
  model.forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool) {
    const Eigen::Vector2d o = oracle(x);
    if (p.k * o.norm() > p.mu * p.qz(x.squaredNorm()))
      return;
    error = std::max(error, (u - o).norm());
    scale = std::max(scale, o.norm());
  });
  return error / scale;
}

TEST(BrushTransient, MatchesEqs28And55)
{
  // Vanishing sliding, constant slips, from undeformed: the bristle field at every travelled distance,
  // in the transient region (eq. 28 / 55) and behind the travelling edge (eq. 23 / 51).
  const Eigen::Vector2d sigma(0.01, -0.02);
  const double phi = 3.33, chi = 0.9;
  for (bool tilt : { false, true })
  {
    BrushParameters p = figure4Parameters(tilt, 48);
    p.mu = 1e6;
    BrushTransient model(p);
    const ContactKinematics k = ContactKinematics::fromSlips(sigma, phi, chi, 2.0);  // V_r = 2 m/s
    double s = 0.0;
    for (double ds : { 0.01, 0.02, 0.03, 0.05, 0.2 })
    {
      model.update(k, ds / 2.0);
      s += ds;
      const double e = fieldError(model, [&](const Eigen::Vector2d& x) {
        return tilt ? cf::transientTilting(x, s, p.a, sigma, chi * phi, (1 - chi) * phi)
                    : cf::transientRolling(x, s, p.a, sigma, phi);
      });
      EXPECT_LT(e, 2e-3) << "tilt " << tilt << " s = " << s;
    }
  }
}

TEST(BrushTransient, ReachesTheSteadyModel)
{
  // Constant inputs with friction: after the bristles have crossed the patch the transient state is the
  // steady one. Both are discretisations; they meet as the resolution grows.
  for (auto law : kSlidingLaws)
  for (bool tilt : { false, true })
    for (const auto& [sx, sy, phi] : { std::tuple{ 0.05, 0.02, 3.33 }, { -0.2, 0.1, 3.33 }, { 0.0, 0.0, 10.0 } })
    {
      std::vector<double> d;
      for (int n : { 16, 64 })
      {
        const BrushParameters p = figure4Parameters(tilt, n, law);
        BrushTransient transient(p);
        const BrushForces t = transient.update(ContactKinematics::fromSlips({ sx, sy }, phi, 0.9, 1.0), 4.0 * p.a);
        const BrushForces s = BrushSteady(figure4Parameters(tilt, 32, law))
                                  .evaluate({ sx, sy }, phi, 0.9 * phi, 0.1 * phi, 1e-7, nullptr, BrushSteady::kReferenceWork);
        d.push_back(forceDistance(t, s, p));
      }
      EXPECT_LT(d[1], std::max(0.5 * d[0], 1e-3)) << toString(law) << " tilt " << tilt << " sigma_x " << sx;
      EXPECT_LT(d[1], 0.01) << toString(law) << " tilt " << tilt << " sigma_x " << sx;  // 1 % of mu F_z at 64
    }
}

// The example point of issue 11: a spin pole in the front of the patch, where a re-adhering streak of 0.5 % of the
// area carries a large share of F_y.
BrushParameters exampleParameters(bool tilt, int resolution)
{
  BrushParameters p;
  p.sliding_law = SlidingLaw::Rigid;
  p.a = 0.030132135540406;
  p.F_z = 721.6240066650845;
  p.mu = 0.8447950430510605;
  p.k = 195451215.1840554;
  p.tilt = tilt;
  p.resolution = resolution;
  return p;
}
const Eigen::Vector2d kExampleSigma(-0.009505213968784471, 0.004217246676809281);
constexpr double kExamplePhi = -9.057291504918961;

// At held inputs, after 6a of travel and then over two lattice spacings more (its error moves with where the lattice
// stands, so one sample can be lucky): the largest error against `ref`, and whether the estimate covered it.
struct HeldRun
{
  double error = 0.0;
  bool covered = true;
};
HeldRun runHeld(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi, double chi, const BrushForces& ref)
{
  BrushTransient model(p);
  const ContactKinematics k = ContactKinematics::fromSlips(sigma, phi, chi, 1.0);
  model.update(k, 6.0 * p.a);
  HeldRun run;
  for (int i = 0; i < 16; ++i)
  {
    const BrushForces f = model.update(k, 2.0 * p.a / p.resolution / 8.0);
    const double e = forceDistance(f, ref, p);
    run.error = std::max(run.error, e);
    run.covered = run.covered && f.error_estimate >= e;
  }
  return run;
}

TEST(BrushTransient, RigidLawConvergesMonotonicallyAtTheExamplePointOfIssue11)
{
  // Before the rows' correction and the re-adhesion on entering G, the error read 3.5, 1.6, 3.1, 1.3 and 0.19 % of
  // mu F_z at resolutions 8-128 without tilt: the rows hit or missed the streak, and bristles that should re-adhere
  // beside the pole slid on.
  for (bool tilt : { false, true })
  {
    const BrushForces ref = BrushSteady(exampleParameters(tilt, 32))
                                .evaluate(kExampleSigma, kExamplePhi, 0.9 * kExamplePhi, 0.1 * kExamplePhi, 1e-10,
                                          nullptr, BrushSteady::kReferenceWork);
    std::vector<double> e;
    for (int n : { 8, 16, 32, 64, 128 })
    {
      const HeldRun run = runHeld(exampleParameters(tilt, n), kExampleSigma, kExamplePhi, 0.9, ref);
      EXPECT_TRUE(run.covered) << "tilt " << tilt << " resolution " << n;
      e.push_back(run.error);
    }
    for (std::size_t i = 1; i < e.size(); ++i)
      EXPECT_LT(e[i], e[i - 1]) << "tilt " << tilt << " resolution " << (8 << i);
    const double order = std::log2(e[2] / e[4]) / 2.0;
    std::printf("example point, tilt %d: %.2e %.2e %.2e %.2e %.2e of mu F_z, order %.2f from 32 to 128\n", tilt, e[0],
                e[1], e[2], e[3], e[4], order);
    EXPECT_GT(order, 1.5) << "tilt " << tilt;
    if (!tilt)
    {
      EXPECT_LT(e[2], 1.5e-3);  // resolution 32 (was 3.1 %)
      EXPECT_LT(e[4], 1.5e-4);  // resolution 128
    }
  }
}

TEST(BrushTransient, CoulombLawConvergesMonotonicallyAtTheExamplePoint)
{
  // The issue's example point under eq. (4b) (Fig. 4's parameters, sigma = 0, phi = 3.33 1/m): the trial deflection
  // scaled back onto the bound, combined over one and two half steps, at held inputs converges to the steady solver
  // at every doubling of the resolution, about at second order, and its estimate covers the error.
  for (bool tilt : { false, true })
  {
    const BrushForces ref = BrushSteady(figure4Parameters(tilt))
                                .evaluate({ 0.0, 0.0 }, 3.33, 0.9 * 3.33, 0.1 * 3.33, 1e-7, nullptr,
                                          BrushSteady::kReferenceWork);
    std::vector<double> e;
    for (int n : { 8, 16, 32, 64, 128 })
    {
      const HeldRun run = runHeld(figure4Parameters(tilt, n), { 0.0, 0.0 }, 3.33, 0.9, ref);
      EXPECT_TRUE(run.covered) << "tilt " << tilt << " resolution " << n;
      e.push_back(run.error);
    }
    for (std::size_t i = 1; i < e.size(); ++i)
      EXPECT_LT(e[i], e[i - 1]) << "tilt " << tilt << " resolution " << (8 << i);
    const double order = std::log2(e[0] / e[4]) / 4.0;
    std::printf("Coulomb example point, tilt %d: %.2e %.2e %.2e %.2e %.2e of mu F_z, order %.2f from 8 to 128\n", tilt,
                e[0], e[1], e[2], e[3], e[4], order);
    EXPECT_GT(order, 1.5) << "tilt " << tilt;
  }
}

TEST(BrushTransient, ConvergesMonotonicallyOnTheFigure4Set)
{
  // A spread of the Fig. 4 set, with and without tilt, under both laws: the error at held inputs falls at every
  // doubling of the resolution (the whole set, 168 points: model_accuracy, docs/benchmarks.md), and the estimate
  // covers it.
  for (auto law : kSlidingLaws)
  for (bool tilt : { false, true })
    for (double sy : { 0.0, 0.1 })
      for (double sx : { -1.0, -0.3, 0.0, 0.1, 0.4 })
      {
        const BrushForces ref = BrushSteady(figure4Parameters(tilt, 32, law))
                                    .evaluate({ sx, sy }, 3.33, 0.9 * 3.33, 0.1 * 3.33,
                                              law == SlidingLaw::Rigid ? 1e-10 : 1e-7, nullptr,
                                              BrushSteady::kReferenceWork);
        double last = INFINITY;
        for (int n : { 8, 16, 32, 64 })
        {
          const HeldRun run = runHeld(figure4Parameters(tilt, n, law), { sx, sy }, 3.33, 0.9, ref);
          SCOPED_TRACE(::testing::Message() << toString(law) << " tilt " << tilt << " sigma (" << sx << ", " << sy
                                            << ") resolution " << n);
          EXPECT_LT(run.error, last);
          EXPECT_TRUE(run.covered);
          last = run.error;
        }
      }
}

TEST(BrushTransient, SlidingBristlesReAdhereWhereTheirPathsEnterG)
{
  // Without tilt the bristles follow their paths exactly (straight, with a drive linear along them), so at held
  // inputs every lattice bristle holds the steady deflection at its place, streaks beside the spin pole included,
  // where the sliding direction turns within a substep. Testing the adhering step against the bound instead
  // re-adhered too early or not at all there: whole rows off by 5-100 % of the bound.
  const BrushParameters p = exampleParameters(false, 128);  // a row crosses the streak (y0 = 0.027-0.043 a)
  BrushTransient model(p);
  model.update(ContactKinematics::fromSlips(kExampleSigma, kExamplePhi, 1.0, 1.0), 6.0 * p.a);
  BristleField field;
  ASSERT_TRUE(BrushSteady(p).field(kExampleSigma, kExamplePhi, 0.0, 0.0, field));
  const double unit = deflectionUnit(p);
  double worst = 0.0;
  int re_adhered = 0;
  model.forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool sliding) {
    const BristlePath path = BristlePath::across(field, std::asin(x.y() / p.a));
    const PathIntegrals solved = solvePath(field, path, 1e-12, true);
    const double tau = path.entry.real() - x.x() / p.a;
    const std::complex<double> v = deflectionAt(field, path, solved, tau);
    worst = std::max(worst, std::abs(std::complex<double>(u.x(), u.y()) / unit - v));
    for (int i = 1; i < solved.pieces; ++i)  // adhering again after sliding
      re_adhered += !sliding && solved.piece[i].adhering && !solved.piece[i - 1].adhering &&
                    tau >= solved.piece[i].begin && tau <= solved.piece[i].end;
  });
  EXPECT_GT(re_adhered, 20);  // the streak is there, and sampled along a row
  EXPECT_LT(worst, 1e-9);     // of the bound at the centre
}

TEST(BrushTransient, TurningAnEmptyPatchKeepsTheRowsCorrected)
{
  // The estimator turns the bristle state with the frame when it re-initialises its heading; with nothing deflected
  // the lattice is laid out anew along the frame, so that its rows stay bristle paths and keep their correction.
  const BrushParameters p = exampleParameters(false, 32);
  const ContactKinematics k = ContactKinematics::fromSlips(kExampleSigma, kExamplePhi, 1.0, 1.0);
  BrushTransient plain(p), turned(p);
  turned.rotateFrame(0.3);
  const BrushForces a = plain.update(k, 6.0 * p.a), b = turned.update(k, 6.0 * p.a);
  EXPECT_EQ(a.F_x, b.F_x);
  EXPECT_EQ(a.F_y, b.F_y);
  EXPECT_EQ(a.M_z, b.M_z);
}

TEST(BrushTransient, ConvergesWithResolution)
{
  // Observed order of the steady state with partial sliding against a fine run.
  const Eigen::Vector2d sigma(0.05, 0.02);
  for (auto law : kSlidingLaws)
  {
    const auto run = [&](int n) {
      BrushTransient m(figure4Parameters(false, n, law));
      return m.update(ContactKinematics::fromSlips(sigma, 3.33, 1.0, 1.0), 0.2);
    };
    const BrushParameters p = figure4Parameters(false, 32, law);
    const BrushForces ref = BrushSteady(p).evaluate(sigma, 3.33, 0.0, 0.0, 1e-8, nullptr, BrushSteady::kReferenceWork);
    const double e16 = forceDistance(run(16), ref, p), e32 = forceDistance(run(32), ref, p),
                 e64 = forceDistance(run(64), ref, p);
    const double q = std::log2(e16 / e64) / 2.0;
    std::printf("transient, %s law, partial sliding: errors %.2e %.2e %.2e of mu F_z, observed order %.2f\n",
                toString(law), e16, e32, e64, q);
    EXPECT_GT(q, 0.8) << toString(law);
    EXPECT_LT(e64, 0.01) << toString(law);
  }
}

TEST(BrushTransient, PureSpinSect5)
{
  // V_r = 0, spinning at psi_dot about the patch centre with a small sliding velocity.
  const double psi_dot = 4.0;
  ContactKinematics k;
  k.V_s = Eigen::Vector2d(0.002, -0.001);
  k.omega_z = psi_dot;
  k.psi_dot = psi_dot;  // pure turning: chi_psi = 1
  const Eigen::Vector2d sigma = -k.V_s / std::abs(psi_dot);
  const double phi_psi = -psi_dot / std::abs(psi_dot);

  // With the turn coupling (Sect. 4 formulation) and vanishing sliding: eq. 59, bounded.
  BrushParameters p = figure4Parameters(true, 32);
  p.mu = 1e6;
  BrushTransient coupled(p);
  for (int i = 1; i <= 8; ++i)
  {
    coupled.update(k, 0.4);
    const double psi = psi_dot * 0.4 * i;
    EXPECT_LT(fieldError(coupled, [&](const Eigen::Vector2d& x) { return cf::spinCoupled(x, psi, sigma, phi_psi); }),
              1e-3) << "psi = " << psi;
  }
  // Without it (Sect. 3 formulation): eq. 60, growing linearly with the turn angle.
  p.tilt = false;
  BrushTransient uncoupled(p);
  double first = 0.0;
  for (int i = 1; i <= 4; ++i)
  {
    const BrushForces f = uncoupled.update(k, 1.0);
    const double psi = psi_dot * i;
    EXPECT_LT(fieldError(uncoupled, [&](const Eigen::Vector2d& x) { return cf::spinUncoupled(x, psi, sigma, phi_psi); }),
              1e-9) << "psi = " << psi;
    if (i == 1)
      first = f.M_z;
    EXPECT_NEAR(f.M_z, i * first, 1e-9 * i * std::abs(first));  // grows in proportion to psi, without bound
  }
  // With limited friction both stay bounded: the moment settles and never exceeds the full-sliding one.
  for (auto law : kSlidingLaws)
  for (bool tilt : { false, true })
  {
    BrushTransient limited(figure4Parameters(tilt, 32, law));
    std::vector<double> M;
    for (int i = 0; i < 40; ++i)
      M.push_back(limited.update(k, 0.25).M_z);
    // |M_z| <= mu integral q_z r dA = mu F_z 8a/15 for the parabolic pressure (to the lattice quadrature)
    for (double m : M)
      EXPECT_LE(std::abs(m), 3000.0 * 8.0 * 0.05 / 15.0 * (1 + 1e-3)) << "tilt " << tilt;
    // settled: the last 2.5 s change by < 0.1 % (under eq. (4b) with the turn coupling, where the sliding bristles'
    // direction turns with the frame against a lattice at rest, the lattice leaves a periodic +-0.13 % at resolution 32)
    const double settled = law == SlidingLaw::Coulomb && tilt ? 3e-3 : 1e-3;
    for (std::size_t i = M.size() - 10; i < M.size(); ++i)
      EXPECT_NEAR(M[i], M.back(), settled * std::abs(M.back())) << toString(law) << " tilt " << tilt;
    EXPECT_GT(limited.forces().sliding_fraction, 0.5);
  }
}

TEST(BrushTransient, StepSizeDoesNotMatter)
{
  // Many small updates or one large one: the same state (substeps adapt to the motion).
  const ContactKinematics k = ContactKinematics::fromSlips({ 0.05, 0.02 }, 3.33, 0.9, 1.5);
  for (auto law : kSlidingLaws)
  for (bool tilt : { false, true })
  {
    const BrushParameters p = figure4Parameters(tilt, 32, law);
    BrushTransient one(p), many(p);
    const BrushForces a = one.update(k, 0.06);
    BrushForces b;
    for (int i = 0; i < 600; ++i)
      b = many.update(k, 1e-4);
    EXPECT_LT(forceDistance(a, b, p), 5e-3) << "tilt " << tilt;
  }
}

TEST(BrushTransient, ContinuousThroughStandstillAndResettable)
{
  for (auto law : kSlidingLaws)
  {
  SCOPED_TRACE(toString(law));
  const BrushParameters p = figure4Parameters(true, 32, law);
  BrushTransient model(p);
  // decelerate to rest and start again: forces change smoothly, nothing is divided by V_r
  BrushForces last = model.update(ContactKinematics::fromSlips({ 0.05, 0.0 }, 1.0, 0.9, 1.0), 0.2);
  for (double v = 1.0; v >= -1e-12; v -= 0.01)
  {
    ContactKinematics k = ContactKinematics::fromSlips({ 0.05, 0.0 }, 1.0, 0.9, 1.0);
    k.V_r *= std::max(v, 0.0);
    k.V_s *= std::max(v, 0.0);
    k.omega_z *= std::max(v, 0.0);
    k.psi_dot *= std::max(v, 0.0);
    const BrushForces f = model.update(k, 0.002);
    EXPECT_TRUE(std::isfinite(f.F_x) && std::isfinite(f.F_y) && std::isfinite(f.M_z));
    EXPECT_LT(forceDistance(f, last, p), 0.05) << "v " << v;
    last = f;
  }
  model.reset();
  const BrushForces zero = model.forces();
  EXPECT_EQ(zero.F_x, 0.0);
  EXPECT_EQ(zero.M_z, 0.0);
  }
}

TEST(BrushTransient, MirrorSymmetryAndFrictionLimitAlongARandomRun)
{
  // Random kinematics changing every 5 ms, through standstill and reversal: |F_t| <= mu F_z at every
  // step, and the mirrored run (y -> -y: V_y, V_s,y, omega_z, psi_dot change sign) mirrors the forces.
  for (auto law : kSlidingLaws)
  for (bool tilt : { false, true })
  {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const BrushParameters p = figure4Parameters(tilt, 24, law);
    BrushTransient model(p), mirror(p);
    for (int i = 0; i < 200; ++i)
    {
      ContactKinematics k;
      k.V_r = Eigen::Vector2d(2.0 * u(rng), i % 20 == 0 ? 0.0 : 0.3 * u(rng));
      if (i % 17 == 0)
        k.V_r.setZero();
      k.V_s = Eigen::Vector2d(0.2 * u(rng), 0.2 * u(rng));
      k.omega_z = 10.0 * u(rng);
      k.psi_dot = 0.5 * (1.0 + u(rng)) * k.omega_z;
      ContactKinematics m = k;
      m.V_r.y() = -k.V_r.y();
      m.V_s.y() = -k.V_s.y();
      m.omega_z = -k.omega_z;
      m.psi_dot = -k.psi_dot;
      const BrushForces f = model.update(k, 0.005), g = mirror.update(m, 0.005);
      EXPECT_LE(std::hypot(f.F_x, f.F_y), p.mu * p.F_z * (1 + 1e-12)) << i;
      EXPECT_NEAR(f.F_x, g.F_x, 1e-9 * p.F_z) << i;
      EXPECT_NEAR(f.F_y, -g.F_y, 1e-9 * p.F_z) << i;
      EXPECT_NEAR(f.M_z, -g.M_z, 1e-9 * p.F_z * p.a) << i;
    }
  }
}

TEST(BrushTransient, TiltingRadiusInsideThePatch)
{
  // |R_gamma| < a: bristles on circles inside the patch never leave it (Fig. 2). No steady state, but the
  // transient model stays defined, bounded by friction and the friction limit.
  for (auto law : kSlidingLaws)
  {
  const BrushParameters p = figure4Parameters(true, 32, law);
  BrushTransient model(p);
  const ContactKinematics k = ContactKinematics::fromSlips({ 0.02, 0.0 }, 40.0, 1.0, 1.0);  // R_gamma = a / 2
  for (int i = 0; i < 50; ++i)
  {
    const BrushForces f = model.update(k, 0.01);
    EXPECT_TRUE(std::isfinite(f.F_x) && std::isfinite(f.F_y) && std::isfinite(f.M_z));
    EXPECT_LE(std::hypot(f.F_x, f.F_y), p.mu * p.F_z * (1 + 1e-12));
  }
  }
}

// One seeded random noisy history (test::drawNoisyHistory) on the lattices of `coarse` and `fine` (the same but for
// the resolution): each(coarse answer, fine answer) for its last 12 of 24 messages.
template <class Each>
void compareAlongNoisyHistory(std::mt19937_64& rng, const BrushParameters& coarse, const BrushParameters& fine,
                              Each each)
{
  const test::NoisyHistoryDraw draw = test::drawNoisyHistory(rng, coarse);
  BrushTransient coarse_model(coarse), fine_model(fine);
  for (int m = 0; m < 24; ++m)
  {
    const ContactKinematics k = draw.history.message(rng, draw.parked && m >= 16, coarse);
    const double step = m == 0 ? 0.0 : draw.dt;
    const BrushForces c = coarse_model.update(k, step), f = fine_model.update(k, step);
    if (m >= 12)
      each(c, f);
  }
}

TEST(BrushTransient, ARenewedLatticeAnswersAsANewOne)
{
  // auto reuses a dropped lattice's storage for its next finer one (renew): that lattice must be the one the
  // constructor builds. One driven along a random noisy history (at 64, under another law, with and without tilt,
  // stepped by substeps and whole, with a work budget, coarsened), renewed, against one built with the same
  // parameters, along another history: the same answers, bit for bit, at every message.
  std::mt19937_64 rng(31);
  int stale = 0;  // histories where the driven lattice predicted another step than a new one of its parameters
  for (int h = 0; h < 24; ++h)
  {
    const SlidingLaw law = h % 2 == 0 ? SlidingLaw::Coulomb : SlidingLaw::Rigid;
    BrushParameters p = test::drawEnvelopeParameters(rng, h, law);
    p.resolution = 16;
    const SlidingLaw other = law == SlidingLaw::Coulomb ? SlidingLaw::Rigid : SlidingLaw::Coulomb;
    BrushParameters old = test::drawEnvelopeParameters(rng, h + 1, other);
    old.resolution = 64;
    old.tilt = h % 3 == 0;
    BrushTransient used(old);
    used.setWorkBudget(50000);
    const test::NoisyHistoryDraw before = test::drawNoisyHistory(rng, old);
    for (int m = 0; m < 8; ++m)
    {
      used.setStepping(m < 3 ? TransientStepping::Substeps : TransientStepping::WholeStep);
      used.update(before.history.message(rng, false, old), m == 0 ? 0.0 : before.dt);
    }
    ASSERT_TRUE(used.coarsen());
    used.update(before.history.message(rng, false, old), before.dt);
    BrushTransient fresh(p);
    const test::NoisyHistoryDraw draw = test::drawNoisyHistory(rng, p);
    const ContactKinematics first = draw.history.message(rng, false, p);
    stale += used.predictWork(first, draw.dt) != BrushTransient(used.parameters()).predictWork(first, draw.dt);
    const std::size_t capacity = used.pointCapacity();
    used.renew(p);
    EXPECT_EQ(used.pointCapacity(), capacity) << "the storage was not kept";
    ASSERT_EQ(used.predictWork(first, draw.dt), fresh.predictWork(first, draw.dt)) << "history " << h;
    for (int m = 0; m < 24; ++m)
    {
      const ContactKinematics k = draw.history.message(rng, draw.parked && m >= 16, p);
      const double step = m == 0 ? 0.0 : draw.dt;
      const BrushForces a = used.update(k, step), b = fresh.update(k, step);
      ASSERT_EQ(a.F_x, b.F_x) << "history " << h << ", message " << m;
      ASSERT_EQ(a.F_y, b.F_y) << "history " << h << ", message " << m;
      ASSERT_EQ(a.M_z, b.M_z) << "history " << h << ", message " << m;
      ASSERT_EQ(a.error_estimate, b.error_estimate) << "history " << h << ", message " << m;
      ASSERT_EQ(a.work, b.work) << "history " << h << ", message " << m;
      ASSERT_EQ(used.predictWork(k, draw.dt), fresh.predictWork(k, draw.dt)) << "history " << h << ", message " << m;
    }
  }
  EXPECT_GE(stale, 4) << "too few driven lattices remembered their steps: the comparison shows little";
}

TEST(BrushTransient, ErrorEstimateCoversNoisyHistoriesAtRandomPoints)
{
  // Seeded random operating points over the envelope (a = 0.01-0.08 m, F_z = 20-5000 N, mu = 0.2-1.2,
  // k = 10^6.5-10^9 N/m^3, slips and spins from 1e-3 of |sigma_x| <= 0.3, |sigma_y| <= 0.1, |a phi| <= 1 to all
  // of it, the three pressures, tilt and no tilt), each a history of 24 messages with noise on the slips and
  // spins (1e-3 to 1e-1), 0.03-2.5 patch radii rolled per message, some ending at standstill with spin and
  // slip noise. The estimate at resolution 16 against the model at 64 (whose own estimate is added): at least
  // 99 % covered, never by less than half.
  // (Under eq. (4b): never short.)
  for (auto law : kSlidingLaws)
  {
  std::mt19937_64 rng(23);
  int checked = 0, short_count = 0;
  double worst = 0.0;
  for (int h = 0; h < 60; ++h)
  {
    BrushParameters p = test::drawEnvelopeParameters(rng, h, law);
    p.standstill_speed = 0.05;
    BrushParameters fine = p;
    p.resolution = 16;
    fine.resolution = 64;
    compareAlongNoisyHistory(rng, p, fine, [&](const BrushForces& c, const BrushForces& f) {
      const double ratio = forceDistance(c, f, p) / (c.error_estimate + f.error_estimate + 1e-300);
      ++checked;
      short_count += ratio > 1.0;
      worst = std::max(worst, ratio);
    });
  }
  std::printf("%s law: error / estimate at most %.2f, short at %d of %d messages\n", toString(law), worst, short_count,
              checked);
  RecordProperty(std::string("worst_error_over_estimate_") + toString(law), std::to_string(worst));
  EXPECT_LE(short_count, law == SlidingLaw::Rigid ? checked / 100 : 0) << "worst error / estimate " << worst;
  EXPECT_LE(worst, law == SlidingLaw::Rigid ? 2.0 : 1.0);
  }
}

// How far estimates cover their errors against a finer reference: the error beyond the reference's own estimate over
// the estimate, its largest and how many pass 1.
struct Coverage
{
  int checked = 0, short_count = 0;
  double worst = 0.0;

  void add(const BrushForces& coarse, const BrushForces& fine, const BrushParameters& p)
  {
    const double ratio = (forceDistance(coarse, fine, p) - fine.error_estimate) / (coarse.error_estimate + 1e-300);
    ++checked;
    short_count += ratio > 1.0;
    worst = std::max(worst, ratio);
  }
  // printed and recorded as the test's worst_error_over_estimate
  void report(const char* what) const
  {
    std::printf("%s: error beyond the reference's estimate / estimate at most %.2f, short at %d of %d messages\n", what,
                worst, short_count, checked);
    ::testing::Test::RecordProperty("worst_error_over_estimate", std::to_string(worst));
  }
};

TEST(BrushTransient, EstimateCoversTheDefaultRobotsNoisyHistories)
{
  // The default robot's parameters (config/contact_estimator.yaml: a = 1 cm, 5 kg on mu = 0.8, k = 2e8 N/m^3, the
  // parabolic pressure; an adhesion zone over most of the patch, a thin sliding crescent) at auto's configured
  // resolution, 32, where the envelope's histories above never reached: random noisy histories of the same kind (slips
  // and spins from 1e-3 of the envelope to all of it, noise 1e-3 to 1e-1, 0.03-2.5 patch radii a message, some ending
  // parked), against resolution 256 (its own estimate added). With the sub-lattices' spread taken twice, these 1800
  // messages came to 0.99 of their estimates and 13 200 of them (docs/speed_and_accuracy.md) passed it at 4, by up to
  // 1.2x, where an update's four sub-lattices happen to agree: the tail grows with the sample, so this sample must stay
  // clear of it (with three times the spread: 0.61 here, 0.75 over the 13 200).
  std::mt19937_64 rng(404);
  Coverage coverage;
  for (int h = 0; h < 150; ++h)
  {
    BrushParameters p = test::drawEnvelopeParameters(rng, 0);  // (its draws, then the robot's values)
    p.a = 0.01, p.F_z = 5.0 * 9.81, p.mu = 0.8, p.k = 2e8;
    p.pressure = PressureDistribution::Parabolic;
    p.tilt = false;
    p.standstill_speed = 0.05;
    BrushParameters fine = p;
    p.resolution = 32;
    fine.resolution = 256;
    compareAlongNoisyHistory(rng, p, fine,
                             [&](const BrushForces& c, const BrushForces& f) { coverage.add(c, f, p); });
  }
  coverage.report("the default robot at resolution 32");
  EXPECT_EQ(coverage.short_count, 0) << "worst " << coverage.worst;
  EXPECT_LE(coverage.worst, 0.8);
}

// The elastic energy of the bristles, sum of k |u|^2 / 2 over the lattice cells [J].
double elasticEnergy(const BrushTransient& model)
{
  const BrushParameters& p = model.parameters();
  const double cell = model.spacing() * model.spacing();
  double e = 0.0;
  model.forEachBristle([&](const Eigen::Vector2d&, const Eigen::Vector2d& u, bool) { e += 0.5 * p.k * u.squaredNorm() * cell; });
  return e;
}

// The default stepping against the lattice's half-spacing substeps (two independent time integrations of the same
// lattice) on seeded random points of the envelope with noisy histories of 0.03-2.5 patch radii a message, some ending
// parked with spin, under both laws: the answers within the sum of the two estimates. With tilt the rolling chi_gamma
// and the parked turn are drawn too.
void expectSteppingsAgreeOnNoisyHistories(bool tilt, int histories, int resolution, unsigned seed)
{
  for (auto law : kSlidingLaws)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int checked = 0, short_count = 0;
    double worst = 0.0;
    for (int h = 0; h < histories; ++h)
    {
      BrushParameters p = test::drawEnvelopeParameters(rng, h, law);
      p.tilt = tilt;
      p.resolution = resolution;
      const double scale = std::pow(10.0, -2.0 * u(rng));
      const Eigen::Vector2d base = scale * Eigen::Vector2d(0.3 * (2.0 * u(rng) - 1.0), 0.1 * (2.0 * u(rng) - 1.0));
      const double a_phi = scale * (2.0 * u(rng) - 1.0), noise = std::pow(10.0, -3.0 + 2.0 * u(rng));
      const double dt = std::pow(10.0, -1.5 + 1.9 * u(rng)) * p.a;  // at V_r = 1 m/s
      double chi = 1.0, chi_parked = 0.0;
      if (tilt)
      {
        chi = 0.2 + u(rng);
        chi_parked = 2.0 * u(rng);
      }
      const bool parked = u(rng) < 0.3;
      const test::NoisyHistory history{ base, a_phi, noise, chi, chi_parked };
      BrushTransient whole(p), substeps(p);
      substeps.setStepping(TransientStepping::Substeps);
      for (int m = 0; m < 24; ++m)
      {
        const ContactKinematics k = history.message(rng, parked && m >= 16, p);
        const BrushForces a = whole.update(k, m == 0 ? 0.0 : dt), b = substeps.update(k, m == 0 ? 0.0 : dt);
        if (m < 12)
          continue;
        const double ratio = forceDistance(a, b, p) / (a.error_estimate + b.error_estimate + 1e-300);
        ++checked;
        short_count += ratio > 1.0;
        worst = std::max(worst, ratio);
      }
    }
    std::printf("%s law%s: whole steps against substeps, difference / estimates at most %.2f, beyond at %d of %d\n",
                toString(law), tilt ? ", tilt" : "", worst, short_count, checked);
    EXPECT_EQ(short_count, 0) << toString(law) << " worst " << worst;
  }
}

TEST(BrushTransient, WholeStepsAgreeWithSubstepsOnNoisyHistories)
{
  // Each bristle over the whole message along its path, without tilt
  expectSteppingsAgreeOnNoisyHistories(false, 40, 24, 29);
}

TEST(BrushTransient, ArcsAgreeWithSubstepsOnNoisyTiltedHistories)
{
  // With tilt, the bristles stepped one by one with the adhering ones' closed forms along their arcs (advanceArcs)
  expectSteppingsAgreeOnNoisyHistories(true, 16, 16, 31);
}

TEST(BrushTransient, TiltedAdheringBristlesFollowTheirArcsInClosedForm)
{
  // With tilt the roots move along arcs and the coupling turns the deflections: an adhering bristle that cannot reach its
  // bound within an update is advanced in closed form along its arc (advanceArcs). Against the substeps of the same
  // lattice, 16 and 64 of them over the update (each update one substep), for the bristles well inside throughout: the
  // substeps' difference from the closed form falls as their length squared (second order), towards it.
  for (double chi : { 0.3, 0.6, 1.0 })
  {
    BrushParameters p;
    p.a = 0.01, p.F_z = 49.0, p.k = 2e8, p.mu = 50.0;  // high friction: every bristle adheres
    p.tilt = true;
    p.resolution = 16;
    const ContactKinematics kin = ContactKinematics::fromSlips({ 0.003, -0.002 }, 20.0, chi, 1.0);
    const double dt = 0.002, rate = kin.omegaGamma();
    BrushTransient whole(p), sub16(p), sub64(p);
    for (BrushTransient* m : { &whole, &sub16, &sub64 })
    {
      m->setStepping(TransientStepping::Substeps);
      m->update(kin, 0.004);  // the same state before
    }
    whole.setStepping(TransientStepping::WholeStep);
    std::vector<Eigen::Vector2d> start;
    whole.forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d&, bool) { start.push_back(x); });
    whole.update(kin, dt);
    for (int n = 0; n < 16; ++n)
      sub16.update(kin, dt / 16);
    for (int n = 0; n < 64; ++n)
      sub64.update(kin, dt / 64);
    // each starting bristle's end: x1 = R(omega_gamma dt) x0 - S(omega_gamma, dt) V_r
    const double c = std::cos(rate * dt), s = std::sin(rate * dt);
    const Eigen::Matrix2d R = (Eigen::Matrix2d() << c, -s, s, c).finished();
    const Eigen::Matrix2d S = (Eigen::Matrix2d() << s, -(1.0 - c), 1.0 - c, s).finished() / rate;
    const auto deflectionAt = [](const BrushTransient& m, const Eigen::Vector2d& x, bool& found) {
      Eigen::Vector2d u = Eigen::Vector2d::Zero();
      found = false;
      m.forEachBristle([&](const Eigen::Vector2d& y, const Eigen::Vector2d& v, bool) {
        if ((y - x).norm() < 1e-9)
          u = v, found = true;
      });
      return u;
    };
    double d16 = 0.0, d64 = 0.0, change = 0.0;
    int compared = 0;
    for (const Eigen::Vector2d& x0 : start)
    {
      const Eigen::Vector2d x1 = R * x0 - S * kin.V_r;
      if (std::max(x0.norm(), x1.norm()) > 0.9 * p.a)
        continue;  // (by the rim the arc may leave the patch: its substeps)
      bool a = false, b = false, e = false;
      const Eigen::Vector2d u = deflectionAt(whole, x1, a), u16 = deflectionAt(sub16, x1, b), u64 = deflectionAt(sub64, x1, e);
      ASSERT_TRUE(a && b && e);
      ++compared;
      d16 = std::max(d16, (u16 - u).norm());
      d64 = std::max(d64, (u64 - u).norm());
      change = std::max(change, (u64 - u16).norm());
    }
    std::printf("chi_gamma %.1f: %d bristles, the closed form against 16 substeps %.3g m, against 64 %.3g m\n", chi,
                compared, d16, d64);
    EXPECT_GT(compared, 100);
    EXPECT_GT(d16, 0.0);
    EXPECT_LT(d64, d16 / 10.0) << "chi_gamma " << chi;  // 16 for second order
    EXPECT_LT(d16, 1e-6);  // of deflections about 1e-3 m
  }
}

TEST(BrushTransient, OneLongUpdateIsAsAccurateAsItsEstimate)
{
  // An update that rolls three transits at once (a gap in the messages, a warm start), then short ones, at held inputs:
  // every answer within its estimate of the steady solver's. Two points where a long sliding step once passed over a
  // re-adhesion (soft bristles with spin: 1.3e-3 of mu F_z off against an estimate of 2.6e-4, for as long as the
  // bristles remembered it; stiff ones ran out of steps), and seeded random points of the envelope, under both laws.
  struct Held
  {
    BrushParameters p;
    Eigen::Vector2d sigma;
    double phi, chi;
  };
  std::vector<Held> points;
  {
    Held q;
    q.p.pressure = PressureDistribution::Parabolic;
    q.p.a = 0.05621487332751267, q.p.F_z = 181.32724513820312, q.p.mu = 0.5235709358150521, q.p.k = 4081523.4185242085;
    q.sigma = { 0.13884614137970547, 0.04047948252099325 }, q.phi = -4.163254847079314, q.chi = 0.427726523421208;
    points.push_back(q);
    q.p.pressure = PressureDistribution::Hertzian;
    q.p.a = 0.046281820501449064, q.p.F_z = 54.8216483014941, q.p.mu = 0.30614817502247993, q.p.k = 978964578.8578024;
    q.sigma = { 0.021286472570293213, 0.005429991361654688 }, q.phi = 0.36966583248314516, q.chi = 1.4516694484901684;
    points.push_back(q);
  }
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 16; ++i)
  {
    Held q;
    q.p = test::drawEnvelopeParameters(rng, i);
    const double scale = std::pow(10.0, -1.5 * u(rng));
    q.sigma = scale * Eigen::Vector2d(0.3 * (2.0 * u(rng) - 1.0), 0.1 * (2.0 * u(rng) - 1.0));
    q.phi = scale * (2.0 * u(rng) - 1.0) / q.p.a;
    q.chi = 2.0 * u(rng) - 0.5;
    points.push_back(q);
  }
  for (auto law : kSlidingLaws)
  {
    int checked = 0, short_count = 0;
    double worst = 0.0;
    for (Held q : points)
    {
      q.p.tilt = false;
      q.p.sliding_law = law;
      q.p.resolution = 64;
      const BrushForces ref = BrushSteady(q.p).evaluate(q.sigma, q.phi, 0.0, 0.0, 1e-7);
      BrushTransient model(q.p);
      const ContactKinematics k = ContactKinematics::fromSlips(q.sigma, q.phi, q.chi, 1.0);
      model.update(k, 6.0 * q.p.a);  // V_r = 1 m/s
      for (int m = 0; m < 8; ++m)
      {
        const BrushForces f = model.update(k, 2.0 * q.p.a / q.p.resolution / 8.0);
        const double ratio = forceDistance(f, ref, q.p) / (f.error_estimate + ref.error_estimate + 1e-300);
        ++checked;
        short_count += ratio > 1.0;
        worst = std::max(worst, ratio);
      }
    }
    std::printf("%s law: one update of three transits, then short ones: error / estimate at most %.2f, beyond at %d of "
                "%d\n", toString(law), worst, short_count, checked);
    EXPECT_EQ(short_count, 0) << toString(law) << " worst " << worst;
  }
}

// The transient model at held inputs (sigma, phi at V_r [m/s], `updates` of dt each) at each resolution, within its
// estimate of the steady solver's forces at 1e-8
void expectWithinEstimateAtHeldInputs(BrushParameters p, const Eigen::Vector2d& sigma, double phi, double V_r,
                                      int updates, double dt, std::initializer_list<int> resolutions)
{
  const BrushForces ref = BrushSteady(p).evaluate(sigma, phi, phi, 0.0, 1e-8);
  const ContactKinematics k = ContactKinematics::fromSlips(sigma, phi, 1.0, V_r);
  for (const int resolution : resolutions)
  {
    p.resolution = resolution;
    BrushTransient model(p);
    BrushForces f;
    for (int m = 0; m < updates; ++m)
      f = model.update(k, dt);
    const double error = forceDistance(f, ref, p);
    std::printf("resolution %d: error %.3g, estimate %.3g\n", resolution, error, f.error_estimate);
    EXPECT_LE(error, f.error_estimate + ref.error_estimate) << "resolution " << resolution;
  }
}

TEST(BrushTransient, AHertzianTrailingLayerThinnerThanASpacingIsInTheSum)
{
  // Sweep seed 9018's robot (a = 7.8 mm, k = 1.78e8 N/m^3, 30.7 kg, mu = 1.05, Hertzian, the rigid law; its weave at
  // sigma_y = 0.055, phi = 7.75 1/m): the bound is so wide (13.9 mm at the centre) that the bristles reach it only in a
  // layer (|u| / c)^2 a / 2 = 40 um wide along the trailing edge, where the Hertzian bound falls to 0 as a square root.
  // The last cell before the edge had held its bristle's adhering deflection up to the edge: 7e-5 of mu F_z off the
  // steady forces at every resolution from 128 to 400, which the sub-lattices (making the same error) did not see, up
  // to 1.4 times the estimate (at 184 and 224). Held inputs, three resolutions: within the estimate.
  BrushParameters p;
  p.a = 0.007816927178840305;
  p.k = 177706327.30855578;
  p.F_z = 30.658575641417155 * 9.81;
  p.mu = 1.0515832164397025;
  p.pressure = PressureDistribution::Hertzian;
  p.sliding_law = SlidingLaw::Rigid;
  // two transits an update
  expectWithinEstimateAtHeldInputs(p, { 0.001, 0.055 }, 7.75, 1.546, 4, 0.01, { 168, 184, 224 });
}

TEST(BrushTransient, AParabolicTrailingLayerThinnerThanASpacingIsInTheSum)
{
  // The same under the parabolic pressure, where the layer is |u| / c a / 2 wide: a random robot of the held-input
  // check (model_accuracy --held-transient 2 600, point 77: a = 7.8 mm, k = 1.69e8 N/m^3, F_z = 328 N, mu = 0.89, the
  // rigid law, slips of 6e-4) has a layer of 2 um, and its forces stood 5.3e-7 of mu F_z off the steady ones at every
  // resolution from 64 to 512 (0.5 % of the forces), up to 1.6 times the estimate (at 448).
  BrushParameters p;
  p.a = 0.007845319619327044;
  p.k = 168607043.00420624;
  p.F_z = 328.2775759237389;
  p.mu = 0.8913128104066002;
  p.pressure = PressureDistribution::Parabolic;
  p.sliding_law = SlidingLaw::Rigid;
  // 4a in 5 updates at 1 m/s
  expectWithinEstimateAtHeldInputs(p, { 0.00012563885728140246, -0.00060843383912506 }, -0.00258180195856906 / p.a,
                                   1.0, 5, 0.8 * p.a, { 384, 448 });
}

TEST(BrushTransient, HeldInputsGiveTheSameAnswerHoweverTheTravelIsSplit)
{
  // At held inputs every bristle's path is the same however the updates split it, and so are the forces, within the
  // estimates. A random robot of a held-input check (a = 16 mm, k = 5.18e7 N/m^3, F_z = 56.1 N, mu = 1, parabolic,
  // sigma = (-0.00973, -0.00487), a phi = -0.813, eq. 4b) rolled 4a in 4 updates and in 6: a sixth of the bristles past
  // the spin pole took a whole update in one return mapping that adhered through a re-adhesion (test_bristle_advance:
  // AWholeMessagePastASpinPoleFromBeyondARightAngle), and the forces of 6 stood 1.7e-4 of mu F_z off those of 4 at
  // resolutions 128 to 512, 2.5 times the estimate at 512.
  BrushParameters p = test::spinPoleRobot();
  p.resolution = 128;
  const ContactKinematics k = test::spinPoleKinematics(p);
  const auto rolled = [&](int updates) {
    BrushTransient model(p);
    BrushForces f;
    for (int m = 0; m < updates; ++m)
      f = model.update(k, 4.0 * p.a / updates);
    return f;
  };
  const BrushForces four = rolled(4), six = rolled(6);
  const double apart = forceDistance(four, six, p);
  std::printf("4 updates against 6: apart %.3g, estimates %.3g and %.3g\n", apart, four.error_estimate,
              six.error_estimate);
  // the same lattice and paths: only the bristles' time steps may differ, far within either estimate
  EXPECT_LE(apart, 0.1 * std::min(four.error_estimate, six.error_estimate));
}

TEST(BrushTransient, EstimateCoversTheErrorAtEveryPhaseOfTheLattice)
{
  // The lattice's error repeats with its phase against the patch edge, every spacing of travel. At this random point
  // of the benchmark's (uniform pressure, stiff bristles for the load: an adhesion zone at the leading edge a third of a
  // spacing long at resolution 128) the error swings between 5e-5 and 4.2e-4 of mu F_z over a spacing, and the
  // sub-lattices' spread at the worst phase fell short of it by 1.3x; the estimate takes the largest spread over the last
  // spacing of travel. Held inputs, a spacing and a half in eighths of a spacing, after the window has seen one.
  BrushParameters p;
  p.pressure = PressureDistribution::Uniform;
  p.a = 0.0595308357369365, p.F_z = 35.439464271254565, p.mu = 0.8526503646401415, p.k = 80830381.51309131;
  p.sliding_law = SlidingLaw::Coulomb;
  p.resolution = 128;
  const Eigen::Vector2d sigma(0.11229486935118993, 0.009142771485366033);
  const double phi = 4.789168384873715, chi = 1.4135382086500192;
  const BrushForces ref = BrushSteady(p).evaluate(sigma, phi, 0.0, 0.0, 1e-8, nullptr, BrushSteady::kReferenceWork);
  ASSERT_FALSE(ref.flags & brush_flags::kAccuracyNotMet);
  BrushTransient model(p);
  const ContactKinematics k = ContactKinematics::fromSlips(sigma, phi, chi, 1.0);
  model.update(k, 6.0 * p.a);
  const double eighth = 2.0 * p.a / p.resolution / 8.0;
  for (int m = 0; m < 8; ++m)
    model.update(k, eighth);
  double worst = 0.0, smallest = INFINITY, largest = 0.0;
  for (int m = 0; m < 12; ++m)
  {
    const BrushForces f = model.update(k, eighth);
    const double error = forceDistance(f, ref, p);
    smallest = std::min(smallest, error);
    largest = std::max(largest, error);
    worst = std::max(worst, error / (f.error_estimate + ref.error_estimate));
  }
  std::printf("error over a spacing and a half: %.2e to %.2e of mu F_z; error / estimate at most %.2f\n", smallest, largest,
              worst);
  EXPECT_GT(largest, 3.0 * smallest);  // the phase matters here (else the point no longer tests the window)
  EXPECT_LE(worst, 1.0);
}

// Noisy messages at held slips and spin: the transient model at resolution 32 against 256 (its own estimate added)
// once the patch has been renewed (2a of travel), each message rolling `spacings` lattice spacings at V_r = 1 m/s, until
// `messages` or 4a of travel, whichever is later.
struct NoisyRoll
{
  BrushParameters p;
  Eigen::Vector2d sigma;
  double noise;       // of each slip
  double a_phi_noise;  // of the spin, times a
  double spacings;
  int messages;
};

void coverAlongNoisyRoll(std::mt19937_64& rng, const NoisyRoll& r, Coverage& c)
{
  std::normal_distribution<double> g(0.0, 1.0);
  BrushParameters coarse_p = r.p, fine_p = r.p;
  coarse_p.resolution = 32;
  fine_p.resolution = 256;
  const double dt = r.spacings * 2.0 * r.p.a / coarse_p.resolution;
  BrushTransient coarse(coarse_p), reference(fine_p);
  double travel = 0.0;
  for (int m = 0; m < r.messages || travel < 4.0 * r.p.a; ++m)
  {
    const Eigen::Vector2d sigma = r.sigma + r.noise * Eigen::Vector2d(g(rng), g(rng));
    const ContactKinematics k = ContactKinematics::fromSlips(sigma, r.a_phi_noise * g(rng) / r.p.a, 1.0, 1.0);
    const double step = m == 0 ? 0.0 : dt;
    const BrushForces f = coarse.update(k, step), ref = reference.update(k, step);
    travel += step;
    if (travel < 2.0 * r.p.a)
      continue;
    c.add(f, ref, coarse_p);
  }
}

BrushParameters rollParameters(double a, double F_z, double mu, double k)
{
  BrushParameters p;
  p.a = a, p.F_z = F_z, p.mu = mu, p.k = k;
  p.pressure = PressureDistribution::Parabolic;
  p.sliding_law = SlidingLaw::Coulomb;
  p.tilt = false;
  p.standstill_speed = 0.05;
  return p;
}

TEST(BrushTransient, EstimateCoversNoisySkidsThatRollAboutASpacingAMessage)
{
  // Sweep seed 1136 at 1 kHz: a noisy skid (slip about -1) of a small patch whose bristles are soft for its load (they
  // adhere nearly everywhere), rolling about one spacing a message, so that every message stood at nearly the same
  // phase of the lattice. The sub-lattices' spread of consecutive messages varied fivefold while the error stayed put,
  // and the estimate of one message fell 2.1x short of its error. Random points around it (a = 4.2-4.5 mm, 280-330 N,
  // mu 0.55-0.62, k = 7.5e7-9e7 N/m^3, slips -0.9 to -1 with 3-4 % noise, 0.95-1.05 spacings a message). Before the
  // window held the spreads of the updates up to eight spacings back, 140 of these 1585 messages fell short, by up to
  // 3.6x (with four spacings, in an earlier draw, 1 of 526 by 1.8x).
  std::mt19937_64 rng(1136);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Coverage c;
  for (int h = 0; h < 48; ++h)
  {
    const BrushParameters p = rollParameters(0.0042 + 0.0003 * u(rng), 280.0 + 50.0 * u(rng), 0.55 + 0.07 * u(rng),
                                             7.5e7 + 1.5e7 * u(rng));
    const Eigen::Vector2d sigma(-0.9 - 0.1 * u(rng), 0.02 * (2.0 * u(rng) - 1.0));
    const double noise = 0.03 + 0.01 * u(rng), spacings = 0.95 + 0.1 * u(rng);
    coverAlongNoisyRoll(rng, { p, sigma, noise, 0.02 * noise, spacings, 0 }, c);
  }
  c.report("noisy skids at about a spacing a message");
  EXPECT_GT(c.checked, 1000);
  EXPECT_EQ(c.short_count, 0) << "worst " << c.worst;
}

TEST(BrushTransient, EstimateCoversNoisyRollsOfTensOfSpacingsAMessage)
{
  // Sweep seed 1083 at 100 Hz: rolling at 0.95 m/s with 5 % slip (a 6.9-mm patch, 171 N, mu 0.49, k 1.6e8 N/m^3), each
  // message rolling 22 spacings and so standing at a phase of its own. One message's sub-lattices happened to agree
  // while its neighbours' spreads, at nearly the same slips, were ten times larger: its estimate fell 2x short. Random
  // points around it (a = 6.5-7.5 mm, 160-180 N, mu 0.45-0.53, k = 1.4e8-1.8e8 N/m^3, slips -0.05 to -0.06 with 0.5 %
  // noise, the spin's a phi with 0.02, 18-26 spacings a message, 40 messages each). Before the window kept the last
  // update's spread, 6 of these 1520 fell short, by up to 1.2x.
  std::mt19937_64 rng(1083);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Coverage c;
  for (int h = 0; h < 40; ++h)
  {
    const BrushParameters p = rollParameters(0.0065 + 0.001 * u(rng), 160.0 + 20.0 * u(rng), 0.45 + 0.08 * u(rng),
                                             1.4e8 + 0.4e8 * u(rng));
    const Eigen::Vector2d sigma(-0.05 - 0.01 * u(rng), 0.0);
    coverAlongNoisyRoll(rng, { p, sigma, 0.005, 0.02, 18.0 + 8.0 * u(rng), 40 }, c);
  }
  c.report("noisy rolls of tens of spacings a message");
  EXPECT_GT(c.checked, 1000);
  EXPECT_EQ(c.short_count, 0) << "worst " << c.worst;
}

TEST(BrushTransient, ThePatchNeverGivesEnergyBack)
{
  // Passivity: from any state, a step with limited friction stores no more elastic energy than the same step without
  // sliding would (friction only takes energy out of the bristles). Random states (random kinematics through standstill
  // and reversal, noise on every message), random steps, under both laws, each step from a copy of the state.
  // Under eq. (4b) every bristle's deflection is the adhering trial scaled back, |u| <= |u_trial|: never more energy.
  // The rigid law sets a sliding bristle along the drive of the moment at |u| = f whatever its trial did, but outside
  // G the drive pushes it outward faster than the bound grows, so its trial is beyond the bound there too.
  for (auto law : kSlidingLaws)
  {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int steps = 0, gains = 0;
    double worst_gain = 0.0;
    for (bool tilt : { false, true })
    {
      const BrushParameters p = figure4Parameters(tilt, 24, law);
      BrushTransient model(p);
      for (int i = 0; i < 300; ++i)
      {
        ContactKinematics k;
        k.V_r = Eigen::Vector2d(u(rng), i % 30 < 10 ? 0.0 : 0.3 * u(rng)) * (i % 30 < 5 ? 0.0 : 1.0);
        k.V_s = Eigen::Vector2d(0.1 * u(rng), 0.1 * u(rng));
        k.omega_z = 8.0 * u(rng);
        k.psi_dot = (0.5 + 0.5 * u(rng)) * k.omega_z;
        const double dt = 0.002 * (1.0 + u(rng));
        BrushTransient adhering = model;
        BrushParameters no_sliding = p;
        no_sliding.mu = 1e6;  // a bound of metres: never reached
        adhering.setParameters(no_sliding);
        adhering.update(k, dt);
        model.update(k, dt);
        const double e_limited = elasticEnergy(model), e_adhering = elasticEnergy(adhering);
        ++steps;
        const double gain = (e_limited - e_adhering) / std::max(e_adhering, 1e-300);
        // (with tilt an adhering bristle out of reach of its bound takes the rest of the update in closed form, one
        // near it the substeps, which the bound then may not cap: the two models differ there by the substeps' own
        // error, not by friction)
        const double slack = tilt ? 1e-9 : 1e-12;
        gains += gain > slack;
        worst_gain = std::max(worst_gain, gain);
        EXPECT_LE(e_limited, e_adhering * (1.0 + slack)) << toString(law) << " tilt " << tilt << " step " << i;
      }
    }
    std::printf("%s law: the limited step stored more energy than the adhering one at %d of %d steps (by up to %.2g)\n",
                toString(law), gains, steps, worst_gain);
  }
}

TEST(BrushTransient, BadStepsAreRejected)
{
  BrushTransient model(figure4Parameters());
  EXPECT_THROW(model.update(ContactKinematics{}, -1.0), std::invalid_argument);
  EXPECT_THROW(model.update(ContactKinematics{}, NAN), std::invalid_argument);
  ContactKinematics k;
  k.V_s.x() = INFINITY;
  EXPECT_THROW(model.update(k, 0.01), std::invalid_argument);
  // A huge step: without tilt every bristle takes it whole along its path (its work that of any step); with tilt,
  // whose substeps are bounded in number, flagged.
  const ContactKinematics fast = ContactKinematics::fromSlips({ 0.1, 0.0 }, 3.0, 0.9, 10.0);
  const BrushForces f = model.update(fast, 1e3);
  EXPECT_FALSE(f.flags & brush_flags::kSubstepsTruncated);
  EXPECT_TRUE(std::isfinite(f.F_x));
  // no more work than the updates of 1 ms that roll a transit
  BrushTransient stepped(figure4Parameters());
  long transit = 0;
  for (int i = 0; i < 10; ++i)
    transit += stepped.update(fast, 1e-3).work;
  EXPECT_LE(f.work, transit);
  const BrushForces settled = model.update(fast, 1e-3);
  EXPECT_LE(forceDistance(f, settled, model.parameters()), f.error_estimate + settled.error_estimate);
  BrushParameters tilted = figure4Parameters();
  tilted.tilt = true;
  BrushTransient with_tilt(tilted);
  const BrushForces g = with_tilt.update(fast, 1e3);
  EXPECT_TRUE(g.flags & brush_flags::kSubstepsTruncated);
  EXPECT_TRUE(std::isfinite(g.F_x));
}

TEST(BrushTransient, ForcesAfterAnUpdateAreItsAnswerAtNoWork)
{
  // forces() gives the last update's answer without summing the lattice again (auto reads it at its switches and counts
  // what it costs, forcesWork): the sums of that very state, dropped by every other change of the state
  for (auto law : kSlidingLaws)
  for (bool tilt : { false, true })
  {
    SCOPED_TRACE(::testing::Message() << toString(law) << " tilt " << tilt);
    const BrushParameters p = figure4Parameters(tilt, 24, law);
    const auto expectSameSums = [](const BrushForces& a, const BrushForces& b) {
      EXPECT_EQ(a.F_x, b.F_x);
      EXPECT_EQ(a.F_y, b.F_y);
      EXPECT_EQ(a.M_z, b.M_z);
      EXPECT_EQ(a.sliding_fraction, b.sliding_fraction);
      EXPECT_EQ(a.max_utilisation, b.max_utilisation);
    };
    BrushTransient model(p);
    EXPECT_GT(model.forcesWork(), 0);  // nothing kept before an update
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    BrushForces f;
    for (int i = 0; i < 40; ++i)
    {
      const ContactKinematics k =
          ContactKinematics::fromSlips({ 0.05 + 0.03 * u(rng), 0.03 * u(rng) }, 2.0 * u(rng), 1.0, 1.0);
      f = model.update(k, 0.002 + 0.004 * (1.0 + u(rng)));
      EXPECT_EQ(model.forcesWork(), 0);
      const BrushForces g = model.forces();
      expectSameSums(g, f);
      EXPECT_EQ(g.error_estimate, f.error_estimate);
      EXPECT_EQ(g.flags, 0u);
      EXPECT_EQ(g.work, 0);
    }
    // what the sums give of that state: a retune that changes no force (the target) drops the kept answer, not the state
    BrushTransient retuned = model;
    BrushParameters q = p;
    q.accuracy_target *= 2.0;
    retuned.setParameters(q);
    EXPECT_GT(retuned.forcesWork(), 0);
    expectSameSums(retuned.forces(), f);
    // a turn of the frame by a right angle: the forces in the new axes (F_x, F_y) -> (F_y, -F_x), not the kept ones
    const double scale = p.mu * p.F_z;
    ASSERT_GT(std::abs(f.F_x + f.F_y) / scale, 0.1);  // (kept ones would be far off)
    BrushTransient turned = model;
    turned.rotateFrame(0.5 * boost::math::double_constants::pi);
    EXPECT_GT(turned.forcesWork(), 0);
    const BrushForces t = turned.forces();
    EXPECT_NEAR(t.F_x, f.F_y, (f.error_estimate + t.error_estimate) * scale);
    EXPECT_NEAR(t.F_y, -f.F_x, (f.error_estimate + t.error_estimate) * scale);
    // coarsened, and reset
    BrushTransient coarse = model;
    ASSERT_TRUE(coarse.coarsen());
    EXPECT_GT(coarse.forcesWork(), 0);
    EXPECT_NE(coarse.forces().F_x, f.F_x);
    model.reset();
    EXPECT_GT(model.forcesWork(), 0);
    EXPECT_EQ(model.forces().F_x, 0.0);
  }
}

TEST(BrushTransient, CoarseningKeepsEveryOtherBristle)
{
  // Rolling at Fig. 4's inputs at resolution 32, then halved: the bristles of the coarser lattice are the finer one's at
  // the same places, with the same deflections; its forces are within both estimates of the finer ones and move on
  // continuously as it rolls.
  BrushParameters p = test::figure4Parameters(false, 32);
  BrushTransient fine(p);
  const ContactKinematics k = ContactKinematics::fromSlips({ 0.05, 0.02 }, 3.33, 1.0, 1.0);
  for (int i = 0; i < 30; ++i)
    fine.update(k, 0.005);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> before;
  fine.forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool) { before.emplace_back(x, u); });
  const BrushForces f = fine.forces();
  BrushTransient coarse = fine;
  ASSERT_TRUE(coarse.coarsen());
  EXPECT_EQ(coarse.lastResolution(), 16);
  EXPECT_NEAR(coarse.spacing(), 2.0 * fine.spacing(), 1e-15);
  int kept = 0;
  coarse.forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool) {
    for (const auto& [y, v] : before)
      if ((x - y).norm() < 1e-12)
      {
        EXPECT_EQ(u, v);
        ++kept;
        return;
      }
    ADD_FAILURE() << "a coarse bristle at " << x.transpose() << " is none of the fine ones";
  });
  EXPECT_GT(kept, 150);  // about a quarter of the fine lattice's ~800
  const BrushForces g = coarse.forces();
  const double scale = p.mu * p.F_z;
  EXPECT_LE(std::abs(g.F_x - f.F_x) / scale, f.error_estimate + g.error_estimate);
  EXPECT_LE(std::abs(g.F_y - f.F_y) / scale, f.error_estimate + g.error_estimate);
  const BrushForces next = coarse.update(k, 0.001);
  EXPECT_LE(std::abs(next.F_y - g.F_y) / scale, 0.02);
  // down to kMinCoarsened, no further
  while (coarse.coarsen())
    ;
  EXPECT_EQ(coarse.lastResolution(), BrushTransient::kMinCoarsened);
}

TEST(BrushTransient, AtAFixedResolutionAnEstimateAboveTheTargetIsFlagged)
{
  // The transient model at a fixed resolution is the user's choice of lattice, not of accuracy: where its estimate
  // passes accuracy_target the answer says so (BRUSH_FLAG_ACCURACY_NOT_MET), as auto's and the steady model's do.
  // (Before, it never did: stream_sweep.py --set brush_model=transient, seed 8000 at 0.1 %, 252 unflagged answers over
  // the target, and bag_analyze's summary said "target met at every estimate".) Fig. 4's noisy 10-ms messages at 8 and
  // 32 under both laws and targets: flagged exactly where the estimate is above the target, and each target both ways.
  std::mt19937_64 rng(17);
  std::normal_distribution<double> noise(0.0, 1.0);
  int flagged = 0, answers = 0;
  for (SlidingLaw law : { SlidingLaw::Coulomb, SlidingLaw::Rigid })
    for (int resolution : { 8, 32 })
      for (double target : { 1e-3, 1e-2 })
      {
        BrushParameters p = test::figure4Parameters(false, resolution, law);
        p.accuracy_target = target;
        BrushTransient model(p);
        for (int m = 0; m < 40; ++m)
        {
          const BrushForces f = model.update(
              ContactKinematics::fromSlips({ 0.05 + 0.005 * noise(rng), 0.02 + 0.005 * noise(rng) },
                                           3.33 + 0.1 * noise(rng), 1.0, 1.0),
              0.01);
          ASSERT_EQ(f.error_estimate > target, (f.flags & brush_flags::kAccuracyNotMet) != 0)
              << toString(law) << " at " << resolution << ", target " << target << ", message " << m
              << ": estimate " << f.error_estimate;
          flagged += (f.flags & brush_flags::kAccuracyNotMet) != 0;
          ++answers;
        }
      }
  EXPECT_GT(flagged, 0);
  EXPECT_LT(flagged, answers);
}

TEST(BrushTransient, SubstepsCutShortKeepTheirErrorInTheEstimateUntilTheirBristlesLeave)
{
  // With tilt the lattice takes substeps. Where the work budget cannot pay for them (a fixed lattice at a small budget,
  // auto's at its coarsest) it takes fewer and longer ones, and the answer makes no claim beyond the friction circle's;
  // the bristles then inside carry their error on into later updates, until each has left the patch: by the lattice's
  // loop (TransientStepping::Substeps) all of them together, the friction circle's 2 until the patch centre of then,
  // moved as a root, lies 2a away; bristle by bristle (the default, advanceArcs) 3 bounds each cut bristle, which
  // leave with it. Fig. 4 with tilt at 16 under both laws: settled, one update rolling a patch radius cut to a single
  // substep, then updates of a twentieth of a patch radius each, against the model at 64 with its own estimate: every
  // error within the estimate, the estimate at least 2 after the cut (by the loop, until 2a away), below 1 by the end.
  for (TransientStepping stepping : { TransientStepping::Substeps, TransientStepping::WholeStep })
  {
    const bool loop = stepping == TransientStepping::Substeps;
    for (SlidingLaw law : kSlidingLaws)
    {
      const BrushParameters p = test::figure4Parameters(true, 16, law);
      BrushTransient cut(p), reference(test::figure4Parameters(true, 64, law));
      cut.setStepping(stepping);
      const ContactKinematics k = ContactKinematics::fromSlips({ 0.05, 0.02 }, 3.33, 1.0, 1.0);
      for (int m = 0; m < 8; ++m)
      {
        cut.update(k, 0.02);
        reference.update(k, 0.02);
      }
      const long one_substep = BrushTransient::leastUpdateWork(p.resolution, true);
      cut.setWorkBudget(one_substep);
      const BrushForces at_cut = cut.update(k, p.a);  // 1 m/s
      reference.update(k, p.a);
      ASSERT_TRUE(at_cut.flags & brush_flags::kSubstepsTruncated);
      EXPECT_LE(at_cut.work, one_substep);
      cut.setWorkBudget(BrushModel::kUnlimitedBudget);
      double worst = 0.0, largest_past = 0.0;
      int carried = 0;
      for (int m = 0; m < 60; ++m)
      {
        const BrushForces c = cut.update(k, 0.05 * p.a), f = reference.update(k, 0.05 * p.a);
        worst = std::max(worst, (forceDistance(c, f, p) - f.error_estimate) / c.error_estimate);
        largest_past = std::max(largest_past, forceDistance(c, f, p));
        // the old patch centre rolled 0.05 a per update (about: the tilt turns it by 0.05 a / 0.3 m a message)
        if ((loop && 0.05 * (m + 1) < 1.9) || m == 0)
        {
          EXPECT_GE(c.error_estimate, 2.0) << toString(law) << ", update " << m << " after the cut";
        }
        carried += c.error_estimate >= 2.0;
        if (m == 59)
        {
          EXPECT_LT(c.error_estimate, 1.0) << toString(law) << ": the carried error never cleared";
        }
      }
      std::printf("%s, %s law: after substeps cut short, error beyond the reference's estimate / estimate at most "
                  "%.3f; the error at most %.4f of mu F_z; at least 2 for %d updates\n", loop ? "loop" : "bristles",
                  toString(law), worst, largest_past, carried);
      EXPECT_LE(worst, 1.0) << toString(law);
    }
    // Seeded random points of the envelope with tilt under eq. (4b) (whose estimate is never short on noisy histories,
    // ErrorEstimateCoversNoisyHistoriesAtRandomPoints): a noisy history at 16 whose ninth update is cut to one substep,
    // against the model at 64: every later answer within its estimate, while the error is carried and once it has
    // left. (Without the carry these stay within theirs, at most 0.89 of it: the spreads at 16 are wide there; Fig. 4's
    // above fall short by up to 1.7x.)
    std::mt19937_64 rng(59);
    int cut_histories = 0, checked = 0, cleared = 0, short_count = 0;
    double worst = 0.0;
    for (int h = 0; h < 36; ++h)
    {
      BrushParameters p = test::drawEnvelopeParameters(rng, h);
      p.tilt = true;
      p.standstill_speed = 0.05;
      BrushParameters fine = p;
      p.resolution = 16;
      fine.resolution = 64;
      const test::NoisyHistoryDraw draw = test::drawNoisyHistory(rng, p);
      BrushTransient coarse_model(p), fine_model(fine);
      coarse_model.setStepping(stepping);
      bool was_cut = false;
      double at_cut = 0.0;  // the estimate right after the cut
      for (int m = 0; m < 24; ++m)
      {
        const ContactKinematics k = draw.history.message(rng, draw.parked && m >= 16, p);
        coarse_model.setWorkBudget(m == 8 ? BrushTransient::leastUpdateWork(p.resolution, true)
                                          : BrushModel::kUnlimitedBudget);
        const double step = m == 0 ? 0.0 : draw.dt;
        const BrushForces c = coarse_model.update(k, step), f = fine_model.update(k, step);
        if (m == 8)
        {
          was_cut = (c.flags & brush_flags::kSubstepsTruncated) != 0;
          at_cut = c.error_estimate;
        }
        if (m < 8 || !was_cut)
          continue;
        const double ratio = (forceDistance(c, f, p) - f.error_estimate) / c.error_estimate;
        ++checked;
        // (bristle by bristle: once the estimate fell below a tenth of what it was at the cut)
        cleared += loop ? coarse_model.cutShortError() == 0.0 : c.error_estimate < 0.1 * at_cut;
        short_count += ratio > 1.0;
        worst = std::max(worst, ratio);
      }
      cut_histories += was_cut;
    }
    std::printf("random points, %s: %d histories cut short, %d answers after the cut (%d once the error had left): "
                "error beyond the reference's estimate / estimate at most %.3f, short at %d\n", loop ? "loop" : "bristles",
                cut_histories, checked, cleared, worst, short_count);
    EXPECT_EQ(short_count, 0) << "worst " << worst;
    EXPECT_GE(cut_histories, 12);
    EXPECT_GE(cleared, 50) << "too few answers after the carried error left: its clearing was not tried";
  }
}

TEST(BrushTransient, SlidingStepsTheBudgetCannotPayForAreFlagged)
{
  // Without tilt each bristle crosses the whole update along its path; under eq. (4b) a sliding one takes steps, and
  // past the budget the rest of its path in one return mapping (2 bounds of error, in the estimate). Such an update
  // says so (kSubstepsTruncated) however early the budget ran out: one that left nothing for any step used to pass
  // unflagged (auto's warm start into sweep seed 1014's pivot: no step taken, estimate 2.0, no flag, and carried as if
  // it were the steady state). Fig. 4 at 16 with spin, settled: an update of a patch radius with no room for a step is
  // flagged and within its estimate of the model at 64; the next, unbudgeted, is not flagged.
  const BrushParameters p = test::figure4Parameters(false, 16, SlidingLaw::Coulomb);
  BrushTransient model(p), reference(test::figure4Parameters(false, 64, SlidingLaw::Coulomb));
  const ContactKinematics k = ContactKinematics::fromSlips({ 0.05, 0.02 }, 3.33, 1.0, 1.0);
  for (int m = 0; m < 8; ++m)
  {
    model.update(k, 0.02);
    reference.update(k, 0.02);
  }
  const long least = BrushTransient::leastUpdateWork(p.resolution, false);
  model.setWorkBudget(least);
  const BrushForces cut = model.update(k, p.a), f = reference.update(k, p.a);
  EXPECT_TRUE(cut.flags & brush_flags::kSubstepsTruncated);
  EXPECT_LE(cut.work, least);
  EXPECT_GT(cut.sliding_fraction, 0.0) << "no bristle slides: nothing was cut";
  EXPECT_LE(forceDistance(cut, f, p), cut.error_estimate + f.error_estimate);
  model.setWorkBudget(BrushModel::kUnlimitedBudget);
  const BrushForces next = model.update(k, 0.02);
  reference.update(k, 0.02);
  EXPECT_FALSE(next.flags & brush_flags::kSubstepsTruncated);
}

TEST(BrushTransient, OnsetsAreCountedAndTheBudgetBoundsThem)
{
  // The first update of a transient model starts every bristle undeformed where it stands; rolling 10 ms at 1.9 m/s
  // with large slips under the uniform pressure (whose bound does not vanish at the rim) nearly every one reaches its
  // bound, each onset a quartic's root isolated (about a step's instructions: bench/work_units.cpp found such an update
  // at 10.5 ns a unit, 1.05 ms within the budget, while they went uncounted). Each counts as a step: under the rigid law,
  // whose sliding takes no steps, the work is at least the least update's and a step for every bristle left sliding
  // (each began to slide at an isolated onset). Within a budget that cannot pay for them, under either law, the onsets
  // it cannot pay for are not located: the rest of each such path in one return mapping, its error two bounds, the
  // update flagged and within its estimate of the uncut one.
  for (SlidingLaw law : kSlidingLaws)
  {
    SCOPED_TRACE(toString(law));
    BrushParameters p;
    p.a = 0.025;
    p.k = 4.6e8;
    p.F_z = 26.6;
    p.mu = 0.43;
    p.pressure = PressureDistribution::Uniform;
    p.resolution = 32;
    p.sliding_law = law;
    const ContactKinematics k = ContactKinematics::fromSlips({ 0.11, 0.16 }, 0.42 / p.a, 0.9, 1.94);
    BrushTransient whole_model(p), cut_model(p);
    const BrushForces whole = whole_model.update(k, 0.01);
    int inside = 0;
    whole_model.forEachBristle([&](const Eigen::Vector2d&, const Eigen::Vector2d&, bool) { ++inside; });
    const long least = BrushTransient::leastUpdateWork(p.resolution, false);
    const double sliding = whole.sliding_fraction * inside;
    ASSERT_GT(whole.sliding_fraction, 0.5);
    std::printf("%s law: the first update %ld units, the least %ld, %.0f bristles sliding\n", toString(law), whole.work,
                least, sliding);
    if (law == SlidingLaw::Rigid)
    {
      EXPECT_GE(whole.work, least + static_cast<long>(sliding) * BrushTransient::kStepWork);
    }
    EXPECT_FALSE(whole.flags & brush_flags::kSubstepsTruncated);
    const long budget = least + inside / 8 * BrushTransient::kStepWork;  // for an eighth of them
    cut_model.setWorkBudget(budget);
    const BrushForces cut = cut_model.update(k, 0.01);
    EXPECT_TRUE(cut.flags & brush_flags::kSubstepsTruncated);
    EXPECT_LE(cut.work, budget + BrushTransient::kStepWork);
    EXPECT_LE(cut.max_utilisation, 1.0 + 1e-12);  // every return mapping back on its bound
    EXPECT_GT(forceDistance(cut, whole, p), 0.0) << "the budget cut nothing";
    EXPECT_LE(forceDistance(cut, whole, p), cut.error_estimate + whole.error_estimate);
  }
}

TEST(BrushTransient, TheStreakBoundsSearchIsCountedAndBounded)
{
  // Under the rigid law each update bounds the re-adhering streaks no row may cross (streakBound): it locates G's
  // component around a front-half pole across the paths, on tilted paths Taylor series whose roots are isolated, which
  // had gone uncounted (0.3 ms of an update at resolution 16: bench/work_units.cpp). Counted, to a precision that
  // serves against three spacings; where the budget leaves too little for it, the most that as many bands as it looks
  // for could hold instead, in the estimate. The robot of the steady solver's test of the same search, settled.
  const BrushParameters p = test::rigidSearchRobot(16);
  const test::RigidSearchInputs in;
  const ContactKinematics k = ContactKinematics::fromSlips(in.sigma, in.a_phi / p.a, 0.9, 1.0);
  BrushTransient model(p);
  for (int m = 0; m < 8; ++m)
    model.update(k, 0.02);
  BrushTransient whole_model = model, cut_model = model;
  const BrushForces whole = whole_model.update(k, 0.002);
  const long least = BrushTransient::leastUpdateWork(p.resolution, true);
  const double most = 8 * 2.0 * peakFactor(p.pressure) * 3.0 * 2.0 / p.resolution;  // 8 bands, each 3 spacings (2a / n)
  EXPECT_GT(whole.work, least + 1000) << "the search counted nothing";
  EXPECT_LT(whole.error_estimate, most);
  cut_model.setWorkBudget(least);
  const BrushForces cut = cut_model.update(k, 0.002);
  EXPECT_GE(cut.error_estimate, most);
  EXPECT_LE(cut.work, least + 1000);  // (the search's first path: about 500 units)
}

TEST(BrushTransient, ABudgetThatFallsShortIsSharedByEveryBristleThatTakesSubsteps)
{
  // With tilt, bristle by bristle (advanceArcs): where the budget cannot pay for every substep of the bristles that
  // need them, each takes a share of what is left (fewer, longer substeps), not the first rows all and the last one
  // each. Seeded random slips where much of the patch slides, Fig. 4's robot with tilt at 16 under both laws, settled,
  // then one update rolling half a patch radius, by three models from the same state: uncut, cut to a single substep
  // (the least budget) and cut to a budget halfway between. Halfway: the work within that budget; on the whole far
  // nearer the uncut answer than the single substep (what a bristle leaves unused goes to those after it); and the
  // answers then and after, against the model at 64, within their estimates.
  std::mt19937_64 rng(2111);
  std::uniform_real_distribution<double> slip(-0.3, 0.3);
  for (SlidingLaw law : kSlidingLaws)
  {
    const BrushParameters p = test::figure4Parameters(true, 16, law);
    const long least = BrushTransient::leastUpdateWork(p.resolution, true);
    double off_one = 0.0, off_halfway = 0.0;
    int cuts = 0, short_count = 0;
    for (int draw = 0; draw < 12; ++draw)
    {
      const ContactKinematics k = ContactKinematics::fromSlips({ slip(rng), slip(rng) }, 3.33, 1.0, 1.0);
      BrushTransient model(p), reference(test::figure4Parameters(true, 64, law));
      for (int m = 0; m < 8; ++m)
      {
        model.update(k, 0.02);
        reference.update(k, 0.02);
      }
      BrushTransient uncut = model, one = model, halfway = model;
      const BrushForces whole = uncut.update(k, 0.5 * p.a);
      one.setWorkBudget(least);
      const BrushForces single = one.update(k, 0.5 * p.a);
      const long budget = (least + whole.work) / 2;
      halfway.setWorkBudget(budget);
      const BrushForces shared = halfway.update(k, 0.5 * p.a), f = reference.update(k, 0.5 * p.a);
      ASSERT_TRUE(single.flags & brush_flags::kSubstepsTruncated);
      ASSERT_TRUE(shared.flags & brush_flags::kSubstepsTruncated) << "a halfway budget of " << budget << " did not cut";
      EXPECT_LE(shared.work, budget);
      ++cuts;
      off_one += forceDistance(single, whole, p);
      off_halfway += forceDistance(shared, whole, p);
      short_count += forceDistance(shared, f, p) - f.error_estimate > shared.error_estimate;
      halfway.setWorkBudget(BrushModel::kUnlimitedBudget);
      for (int m = 0; m < 12; ++m)
      {
        const BrushForces c = halfway.update(k, 0.05 * p.a), r = reference.update(k, 0.05 * p.a);
        short_count += forceDistance(c, r, p) - r.error_estimate > c.error_estimate;
      }
    }
    std::printf("%s law: %d updates cut halfway; off the uncut answer %.4f (a single substep: %.4f) of mu F_z summed; "
                "estimates short at %d\n", toString(law), cuts, off_halfway, off_one, short_count);
    // (0.06 and 0.03 of it measured under eq. (4b) and the rigid law)
    EXPECT_LT(off_halfway, 0.25 * off_one) << toString(law);
    EXPECT_EQ(short_count, 0) << toString(law);
  }
}

TEST(BrushTransient, ACoarsenedLatticePredictsItsOwnStep)
{
  // auto coarsens a lattice whose predicted step does not fit the budget, and again while the coarser one's does not:
  // that prediction must be of the coarser lattice's sliding steps, not the finer one's. Fig. 4's 10-ms message at
  // 1 m/s under eq. (4b): rolled at 32, then halved, its prediction before its first step against the one its own
  // steps then give. (Before, the finer lattice's steps were kept: 19.8 k units against 7.7 k, and sweep seed 1253,
  // whose step at 32 did not fit, was cut to 8 where 16 fitted.)
  BrushTransient fine(test::figure4Parameters(false, 32));
  const ContactKinematics k = ContactKinematics::fromSlips({ 0.05, 0.02 }, 3.33, 1.0, 1.0);
  for (int i = 0; i < 12; ++i)
    fine.update(k, 0.01);
  BrushTransient coarse = fine;
  ASSERT_TRUE(coarse.coarsen());
  const long predicted = coarse.predictWork(k, 0.01);
  coarse.update(k, 0.01);
  const long own = coarse.predictWork(k, 0.01);
  std::printf("coarsened 32 -> 16: predicted %ld units before its first step, %ld after it\n", predicted, own);
  EXPECT_LT(std::abs(predicted - own), own / 4);
}

}  // namespace
}  // namespace sphere_contact_estimator
