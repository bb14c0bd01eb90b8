// The linear theory (eqs. 61-62) and its coefficients, recovered by the numerical models at small slips.

// STL
#include <cmath>

// GTest
#include <gtest/gtest.h>

// Package
#include "brush_test_support.h"
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"

namespace sphere_contact_estimator
{
namespace
{
using test::figure4Parameters;

constexpr double kSmallSlip = 1e-4;  // deep in the linear range: the sliding band at the trailing edge is ~1e-5 a
constexpr double kSmallSpin = 2e-3;  // [1/m]

struct Coefficients
{
  double C_sigma, C_phi, C_Msigma_y, C_Mphi;
};

// Finite-slip secants of a model: F_y/sigma_y, F_y/phi, -M_z/sigma_y, M_z/phi.
template <class Evaluate>
Coefficients secants(Evaluate evaluate)
{
  const BrushForces s = evaluate(Eigen::Vector2d(0.0, kSmallSlip), 0.0);
  const BrushForces p = evaluate(Eigen::Vector2d::Zero(), kSmallSpin);
  return { s.F_y / kSmallSlip, p.F_y / kSmallSpin, -s.M_z / kSmallSlip, p.M_z / kSmallSpin };
}

TEST(BrushLinear, Eq62Coefficients)
{
  const BrushParameters p = figure4Parameters();
  const BrushLinear linear(p);
  const double a = p.a, k = p.k;
  EXPECT_DOUBLE_EQ(linear.C_sigma(), 8.0 / 3.0 * k * a * a * a);
  EXPECT_DOUBLE_EQ(linear.C_phi(), 3.0 * M_PI * a / 32.0 * linear.C_sigma());
  EXPECT_DOUBLE_EQ(linear.C_Msigma_y(), linear.C_phi());
}

TEST(BrushLinear, SpinMomentDerivedFromEq23)
{
  // Eq. 61b has no spin term. Integrating eq. 23 (the closed form, by independent quadrature) at a pure
  // spin gives M_z = 8/15 k a^5 phi, and no force beyond C_phi phi along y.
  const BrushParameters p = figure4Parameters();
  const double phi = kSmallSpin;
  const BrushForces f = test::integrateField(
      [&](const Eigen::Vector2d& x) { return brush_closed_form::steadyRolling(x, p.a, Eigen::Vector2d::Zero(), phi); },
      p.a, p.k);
  const BrushLinear linear(p);
  EXPECT_NEAR(f.M_z / phi, 8.0 / 15.0 * p.k * std::pow(p.a, 5), 1e-4 * linear.C_Mphi());
  EXPECT_NEAR(f.F_y / phi, linear.C_phi(), 1e-4 * linear.C_phi());
  EXPECT_NEAR(f.F_x / phi, 0.0, 1e-6 * linear.C_phi());
  // and the same for a lateral slip: eqs. 61a, 61b
  const double s = kSmallSlip;
  const BrushForces g = test::integrateField(
      [&](const Eigen::Vector2d& x) { return brush_closed_form::steadyRolling(x, p.a, Eigen::Vector2d(0.0, s), 0.0); },
      p.a, p.k);
  EXPECT_NEAR(g.F_y / s, linear.C_sigma(), 1e-4 * linear.C_sigma());
  EXPECT_NEAR(-g.M_z / s, linear.C_Msigma_y(), 1e-4 * linear.C_Msigma_y());
}

TEST(BrushLinear, SteadyModelRecoversTheCoefficients)
{
  for (bool tilt : { false, true })
  {
    const BrushSteady model(figure4Parameters(tilt));
    const BrushLinear linear(figure4Parameters());
    const Coefficients c = secants([&](const Eigen::Vector2d& sigma, double phi) {
      return model.evaluate(sigma, phi, 0.9 * phi, 0.1 * phi, 1e-10);
    });
    EXPECT_NEAR(c.C_sigma, linear.C_sigma(), 2e-3 * linear.C_sigma()) << "tilt " << tilt;
    EXPECT_NEAR(c.C_phi, linear.C_phi(), 2e-3 * linear.C_phi()) << "tilt " << tilt;
    EXPECT_NEAR(c.C_Msigma_y, linear.C_Msigma_y(), 2e-3 * linear.C_Msigma_y()) << "tilt " << tilt;
    EXPECT_NEAR(c.C_Mphi, linear.C_Mphi(), 2e-3 * linear.C_Mphi()) << "tilt " << tilt;
  }
}

TEST(BrushLinear, TransientModelRecoversTheCoefficients)
{
  const BrushLinear linear(figure4Parameters());
  BrushTransient model(figure4Parameters(false, 64));
  const Coefficients c = secants([&](const Eigen::Vector2d& sigma, double phi) {
    model.reset();
    return model.update(ContactKinematics::fromSlips(sigma, phi, 1.0), 4.0 * 0.05);  // 4a: steady
  });
  EXPECT_NEAR(c.C_sigma, linear.C_sigma(), 0.01 * linear.C_sigma());
  EXPECT_NEAR(c.C_phi, linear.C_phi(), 0.01 * linear.C_phi());
  EXPECT_NEAR(c.C_Msigma_y, linear.C_Msigma_y(), 0.01 * linear.C_Msigma_y());
  EXPECT_NEAR(c.C_Mphi, linear.C_Mphi(), 0.01 * linear.C_Mphi());
}

TEST(BrushLinear, AnyRollingDirection)
{
  // The isotropic patch: rotating every input rotates F_t and leaves M_z.
  BrushLinear linear(figure4Parameters());
  const ContactKinematics k = ContactKinematics::fromSlips(Eigen::Vector2d(0.002, -0.001), 0.05, 1.0, 1.5);
  const BrushForces f0 = linear.update(k, 0.0);
  for (double angle : { 0.3, 2.0, -2.5 })
  {
    const Eigen::Matrix2d R = (Eigen::Matrix2d() << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle)).finished();
    ContactKinematics r = k;
    r.V_r = R * k.V_r;
    r.V_s = R * k.V_s;
    const BrushForces f = linear.update(r, 0.0);
    const Eigen::Vector2d F = R * Eigen::Vector2d(f0.F_x, f0.F_y);
    EXPECT_NEAR(f.F_x, F.x(), 1e-9 * F.norm());
    EXPECT_NEAR(f.F_y, F.y(), 1e-9 * F.norm());
    EXPECT_NEAR(f.M_z, f0.M_z, 1e-9 * std::abs(f0.M_z));
  }
}

TEST(BrushLinear, AnAnswerWhoseBoundPassesTheTargetIsFlagged)
{
  // the linear theory's error bound (errorBound) is its estimate: where it passes accuracy_target the answer says so,
  // as every model's does (BRUSH_FLAG_ACCURACY_NOT_MET); below it, not (before, the linear answers never were)
  BrushParameters p = test::figure4Parameters();
  p.accuracy_target = 1e-3;
  BrushLinear model(p);
  int flagged = 0, answers = 0;
  for (double slip : { 1e-5, 1e-4, 1e-3, 3e-3, 1e-2, 0.05 })
    for (double spin : { 0.0, 0.3, 3.0 })
    {
      const BrushForces f = model.update(ContactKinematics::fromSlips({ slip, 0.5 * slip }, spin, 1.0, 1.0), 0.01);
      EXPECT_EQ(f.error_estimate > p.accuracy_target, (f.flags & brush_flags::kAccuracyNotMet) != 0)
          << "slip " << slip << ", spin " << spin << ": estimate " << f.error_estimate;
      flagged += (f.flags & brush_flags::kAccuracyNotMet) != 0;
      ++answers;
    }
  EXPECT_GT(flagged, 0);
  EXPECT_LT(flagged, answers);
}

TEST(BrushLinear, SaturatesOnTheFrictionCircle)
{
  BrushLinear linear(figure4Parameters());
  const BrushForces f = linear.evaluate(Eigen::Vector2d(0.5, 0.3), 0.0);
  EXPECT_NEAR(std::hypot(f.F_x, f.F_y), 3000.0, 1e-9);
  EXPECT_FALSE(f.valid());
  EXPECT_TRUE(linear.evaluate(Eigen::Vector2d(0.001, 0.0), 0.0).valid());
  // standstill: no slips, flagged
  const BrushForces s = linear.update(ContactKinematics{}, 0.01);
  EXPECT_TRUE(s.flags & brush_flags::kStandstill);
  EXPECT_EQ(s.F_x, 0.0);
}

}  // namespace
}  // namespace sphere_contact_estimator
