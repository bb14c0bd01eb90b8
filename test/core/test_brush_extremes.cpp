// The brush models at the extremes (issue 6): standstill to 1e3 m/s, slips and spins to 1e6, no friction,
// no load, tiny and huge patches and stiffnesses, tilting radii across the patch radius. Every output finite,
// |F_t| <= mu F_z, the documented flags set, and continuity where the models hand over.

// STL
#include <cmath>
#include <random>
#include <stdexcept>

// GTest
#include <gtest/gtest.h>

// Package
#include "brush_test_support.h"
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"

namespace sphere_contact_estimator
{
namespace
{
using test::figure4Parameters;
using test::forceDistance;

void expectSound(const BrushForces& f, const BrushParameters& p)
{
  EXPECT_TRUE(std::isfinite(f.F_x) && std::isfinite(f.F_y) && std::isfinite(f.M_z));
  EXPECT_TRUE(std::isfinite(f.sliding_fraction) && std::isfinite(f.max_utilisation));
  EXPECT_LE(std::hypot(f.F_x, f.F_y), p.mu * p.F_z * (1.0 + 1e-9) + 1e-300);
  EXPECT_GE(f.sliding_fraction, 0.0);
  EXPECT_LE(f.sliding_fraction, 1.0);
  EXPECT_LE(f.max_utilisation, 1.0 + 1e-12);
}

TEST(BrushExtremes, SlipsPassedOnAreTheKinematicsOwn)
{
  // update(kinematics, slips, dt), which the estimator and auto call with the slips they computed, answers as
  // update(kinematics, dt) bit for bit along a random history through standstill; slips of other kinematics, or of
  // another standstill speed, throw, changing nothing (the model answers on as one that never saw them)
  const BrushParameters p = figure4Parameters(false, 16);
  for (BrushModelKind kind : { BrushModelKind::Linear, BrushModelKind::Steady, BrushModelKind::Transient, BrushModelKind::Auto })
  {
    SCOPED_TRACE(toString(kind));
    const auto passed = makeBrushModel(kind, p), own = makeBrushModel(kind, p);
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 60; ++i)
    {
      const double V_r = i % 20 < 3 ? 0.5 * p.standstill_speed : 0.5 + 0.5 * u(rng);  // standstill now and then
      const ContactKinematics k = ContactKinematics::fromSlips({ 0.05 * u(rng), 0.05 * u(rng) }, 3.0 * u(rng), 1.0, V_r);
      const Slips s = computeSlips(k, p.standstill_speed);
      if (i % 10 == 5)
      {
        const ContactKinematics other = ContactKinematics::fromSlips({ 0.01, 0.0 }, 0.0, 1.0, 2.0 * V_r + 0.1);
        EXPECT_THROW(passed->update(k, computeSlips(other, p.standstill_speed), 0.01), std::invalid_argument);
        // the same rolling speed, but defined at another standstill speed than the model's
        EXPECT_THROW(passed->update(k, computeSlips(k, s.defined ? 2.0 * V_r : 0.25 * V_r), 0.01), std::invalid_argument);
      }
      const BrushForces a = passed->update(k, s, 0.01), b = own->update(k, 0.01);
      EXPECT_EQ(a.F_x, b.F_x) << "message " << i;
      EXPECT_EQ(a.F_y, b.F_y) << "message " << i;
      EXPECT_EQ(a.M_z, b.M_z) << "message " << i;
      EXPECT_EQ(a.error_estimate, b.error_estimate) << "message " << i;
      EXPECT_EQ(a.flags, b.flags) << "message " << i;
    }
  }
}

TEST(BrushExtremes, RandomKinematicsAndParameters)
{
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto logUniform = [&](double lo, double hi) {
    return std::pow(10.0, std::log10(lo) + (std::log10(hi) - std::log10(lo)) * 0.5 * (u(rng) + 1.0));
  };
  for (int it = 0; it < 120; ++it)
  {
    BrushParameters p;
    p.a = logUniform(1e-6, 1e3);
    p.k = logUniform(1e-3, 1e20);
    p.F_z = it % 13 == 0 ? 0.0 : logUniform(1e-6, 1e12);
    p.mu = it % 11 == 0 ? 0.0 : logUniform(1e-3, 1e3);
    p.tilt = it % 2;
    p.resolution = 4 + it % 13;
    for (BrushModelKind kind : { BrushModelKind::Linear, BrushModelKind::Steady, BrushModelKind::Transient, BrushModelKind::Auto })
    {
      const auto model = makeBrushModel(kind, p);
      for (int j = 0; j < 6; ++j)
      {
        ContactKinematics k;
        const double V = j == 0 ? 0.0 : (j == 1 ? 1e-12 : logUniform(1e-9, 1e3));
        k.V_r = Eigen::Vector2d(V * u(rng), V * u(rng));
        k.V_s = Eigen::Vector2d(logUniform(1e-9, 1e6) * u(rng), logUniform(1e-9, 1e6) * u(rng));
        k.omega_z = logUniform(1e-9, 1e4) * u(rng);
        k.psi_dot = k.omega_z * u(rng);
        SCOPED_TRACE(testing::Message() << toString(kind) << " a=" << p.a << " k=" << p.k << " F_z=" << p.F_z << " mu=" << p.mu);
        const BrushForces f = model->update(k, logUniform(1e-6, 0.1));
        expectSound(f, p);
        if (kind == BrushModelKind::Steady || kind == BrushModelKind::Linear)
        {
          if (k.V_r.norm() < p.standstill_speed)
          {
            EXPECT_TRUE(f.flags & brush_flags::kStandstill);
          }
        }
      }
    }
  }
}

TEST(BrushExtremes, HugeSlipsAndSpinsSaturate)
{
  for (bool tilt : { false, true })
  {
    const BrushParameters p = figure4Parameters(tilt, 16);
    for (const auto& [sx, sy, phi] : { std::tuple{ 1e6, 0.0, 0.0 }, { -1e6, 1e6, 0.0 }, { 0.0, 0.0, 1e6 }, { 1e6, -1e6, -1e6 } })
    {
      for (BrushModelKind kind : { BrushModelKind::Linear, BrushModelKind::Steady, BrushModelKind::Transient, BrushModelKind::Auto })
      {
        const auto model = makeBrushModel(kind, p);
        const BrushForces f = model->update(ContactKinematics::fromSlips({ sx, sy }, phi, 0.9, 1.0), 0.2);
        SCOPED_TRACE(testing::Message() << toString(kind) << " tilt " << tilt << " sigma (" << sx << ", " << sy << ") phi " << phi);
        expectSound(f, p);
        if (phi == 0.0)  // full sliding along -sigma: the whole mu F_z
        {
          EXPECT_NEAR(std::hypot(f.F_x, f.F_y), p.mu * p.F_z, 0.01 * p.mu * p.F_z);
        }
      }
    }
  }
}

TEST(BrushExtremes, ContinuousThroughTheStandstillThreshold)
{
  // The auto model hands over from the steady family to the transient one as V_r falls below the
  // standstill speed: the published forces do not jump (the carried difference decays).
  BrushParameters p = figure4Parameters(false, 16);
  p.standstill_speed = 0.05;
  BrushAuto model(p);
  const Eigen::Vector2d sigma(0.02, 0.01);
  BrushForces previous;
  bool saw_transient = false, saw_steady = false;
  for (int i = 0; i < 400; ++i)
  {
    const double V = std::max(0.0, 0.2 - 0.0005 * i);  // 0.2 m/s to rest in 4 s
    ContactKinematics k = ContactKinematics::fromSlips(sigma, 0.0, 1.0, 1.0);
    k.V_r *= V;
    k.V_s *= V;
    const BrushForces f = model.update(k, 0.01);
    expectSound(f, p);
    if (i > 0)
    {
      EXPECT_LT(forceDistance(f, previous, p), 0.02) << "step " << i << " V " << V;
    }
    previous = f;
    saw_transient |= model.lastModel() == BrushModelKind::Transient;
    saw_steady |= model.lastModel() != BrushModelKind::Transient;
  }
  EXPECT_TRUE(saw_transient && saw_steady);
}

TEST(BrushExtremes, TiltingRadiusAcrossThePatchRadius)
{
  // |R_gamma| from 4a down to a/4: the steady model flags the inner-disc case, auto and transient stay
  // sound through it.
  const BrushParameters p = figure4Parameters(true, 16);
  BrushTransient transient(p);
  BrushAuto automatic(p);
  for (double ratio : { 4.0, 2.0, 1.1, 1.0, 0.9, 0.5, 0.25 })
  {
    const double phi_gamma = 1.0 / (ratio * p.a);
    const BrushForces s = BrushSteady(p).evaluate({ 0.02, 0.01 }, phi_gamma, phi_gamma, 0.0);
    EXPECT_EQ(static_cast<bool>(s.flags & brush_flags::kNoSteadyStateTilt), ratio < 1.0) << ratio;
    const ContactKinematics k = ContactKinematics::fromSlips({ 0.02, 0.01 }, phi_gamma, 1.0, 1.0);
    expectSound(transient.update(k, 0.05), p);
    const BrushForces a = automatic.update(k, 0.05);
    expectSound(a, p);
    if (ratio < 1.0)
    {
      EXPECT_EQ(automatic.lastModel(), BrushModelKind::Transient) << ratio;
    }
  }
}

// Without load there is no friction to give: every model answers exactly zero (fuzz_brush once found a transient
// force of 3.7e-186 N against mu F_z = 0 at a = 1.8e-4 m, k = 1e-3, mu = 0.126, tilt, resolution 2, V_r = 0).
TEST(BrushExtremes, NoLoadNoForce)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto kind : { BrushModelKind::Linear, BrushModelKind::Steady, BrushModelKind::Transient, BrushModelKind::Auto })
    for (bool tilt : { false, true })
    {
      BrushParameters p;
      p.a = 1.8e-4;
      p.k = 1e-3;
      p.mu = 0.126;
      p.F_z = 0.0;
      p.tilt = tilt;
      p.resolution = 2;
      const auto model = makeBrushModel(kind, p);
      for (int i = 0; i < 2000; ++i)
      {
        ContactKinematics k;
        k.V_r = Eigen::Vector2d(u(rng), u(rng)) * (i % 3 == 0 ? 0.0 : std::pow(10.0, 3.0 * u(rng)));
        k.V_s = Eigen::Vector2d(u(rng), u(rng)) * std::pow(10.0, 3.0 * u(rng));
        k.omega_z = u(rng) * std::pow(10.0, 4.0 * u(rng));
        k.psi_dot = k.omega_z * u(rng);
        const BrushForces f = model->update(k, 0.005 * (1.0 + u(rng)));
        ASSERT_EQ(f.F_x, 0.0) << toString(kind) << " tilt " << tilt << " step " << i;
        ASSERT_EQ(f.F_y, 0.0) << toString(kind) << " tilt " << tilt << " step " << i;
        ASSERT_EQ(f.M_z, 0.0) << toString(kind) << " tilt " << tilt << " step " << i;
      }
    }
}

}  // namespace
}  // namespace sphere_contact_estimator
