// The closed-form contact integrals against Gauss-Kronrod quadrature, and eq. 17 against the energy
// that the surface actually dissipates.

// STL
#include <cmath>

// Boost
#include <boost/math/quadrature/gauss_kronrod.hpp>

// GTest
#include <gtest/gtest.h>

// Package
#include "cylinder_test_support.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_contact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"

namespace sphere_contact_estimator
{
namespace
{
using boost::math::quadrature::gauss_kronrod;
using test::paperParameters;
using test::variedParameters;

template <class F>
double integrate(F f, double a, double b)
{
  return gauss_kronrod<double, 31>::integrate(f, a, b, 10, 1e-14);
}

TEST(CylinderIntegrals, ClosedFormsMatchQuadrature)
{
  for (const CylinderParameters& p : variedParameters())
  {
    const CylinderScales sc = CylinderScales::of(p);
    for (double v : { 0.0, 1e-4, 0.1, 0.45, 2.0, 10.0 })
    {
      const double s_c = p.gamma > 0.0 ? p.m * v / p.gamma : 0.0;
      // front boundaries from well inside to just above the self-consistency limit, where the patch closes
      for (double s : { 3.0 * sc.xi0, sc.xi0, 0.3 * sc.xi0, s_c * (1.0 + 1e-3), s_c * (1.0 + 1e-7) })
      {
        if (!(s > s_c) || s <= 0.0)
          continue;
        const ContactPatch c = contactPatch(p, s, v);
        const auto f = [&](double xi) { return forceDensity(p, xi, s, v); };
        const double F_N = -integrate(f, c.xi_minus, s);
        const double M1 = -integrate([&](double xi) { return xi * f(xi); }, c.xi_minus, s);
        // f <= 0 on the patch, so F_N is the integral of |f|. Near closure the width w is conditioned by
        // s / w: the round-off of the boundaries themselves, not of the formulas.
        const double tol = 1e-11 + 1e-14 * s / c.width;
        EXPECT_NEAR(c.F_N, F_N, tol * F_N) << "v = " << v << " s = " << s;
        EXPECT_NEAR(c.first_moment, M1, tol * F_N * std::max(s, std::abs(c.xi_minus))) << "v = " << v << " s = " << s;
        EXPECT_GT(c.F_N, 0.0);
        EXPECT_NEAR(c.width, s - c.xi_minus, 1e-12 * s);
        // xi_- is where the force density vanishes (eq. 14), and f <= 0 on the patch (eq. 11)
        const double terms = (p.k * (s * s + c.xi_minus * c.xi_minus) + p.gamma * v * std::abs(c.xi_minus) +
                              p.m * v * v) / p.R;  // magnitude of the terms of eq. 12
        EXPECT_NEAR(f(c.xi_minus), 0.0, 1e-14 * terms);
        EXPECT_LE(f(0.5 * (c.xi_minus + s)), 0.0);
        EXPECT_LE(f(s), 1e-14 * terms);
      }
    }
  }
}

TEST(CylinderIntegrals, Eq17EqualsTheDissipatedPower)
{
  // An independent route to F_R. In the comoving frame the springs enter at xi_+, are hit by the
  // cylinder (a perfectly inelastic impact that loses m v ydot_+^2 / 2 per unit time), dissipate
  // gamma ydot^2 in the patch, and leave at xi_- carrying k y^2/2 + m ydot^2/2 per unit length.
  // The cylinder must supply all of it: v F_R = sum. This holds with the impact term of eq. 17
  // (m v^3 2h/R = m v ydot_+^2) and not with that of line 1 of eq. 16 (m ydot_+^2 v / 2), which
  // accounts for the kinetic energy given to the springs but not for the energy lost in the impact.
  for (const CylinderParameters& p : variedParameters())
  {
    const CylinderExact model(p);
    for (double v : { 1e-3, 0.2, 0.45, 1.0, 5.0, 15.0 })
    {
      const CylinderState s = model.solve(v);
      if (s.regime != CylinderRegime::ContactPatch)
        continue;
      const double h = s.h, R = p.R;
      const auto y = [&](double xi) { return xi * xi / (2.0 * R) - h; };  // eq. 4
      const auto ydot = [&](double xi) { return -v * xi / R; };           // eq. 5
      const double viscous = integrate([&](double xi) { return p.gamma * ydot(xi) * ydot(xi); }, s.xi_minus, s.xi_plus);
      const double carried = v * (0.5 * p.k * y(s.xi_minus) * y(s.xi_minus) + 0.5 * p.m * ydot(s.xi_minus) * ydot(s.xi_minus));
      const double impact_loss = 0.5 * p.m * v * ydot(s.xi_plus) * ydot(s.xi_plus);
      const double power = viscous + carried + impact_loss;
      EXPECT_NEAR(v * s.F_R, power, 1e-10 * power) << "v = " << v;
      const double F_R_line1 = s.F_R - 0.5 * s.F_R_impact;
      if (p.m > 0.0)
      {
        EXPECT_GT(std::abs(v * F_R_line1 - power), 1e3 * 1e-10 * power) << "v = " << v;
      }
    }
  }
}

TEST(CylinderIntegrals, TorqueIsTheMomentOfTheSupportForces)
{
  // The torque R F_R is the moment about the axis of the distributed support -f at lever xi plus the
  // impact force F'_N at lever xi_+ (eq. 8).
  const CylinderParameters p = paperParameters();
  const CylinderExact model(p);
  for (double v : { 0.1, 0.45, 2.0 })
  {
    const CylinderState s = model.solve(v);
    const double moment =
        -integrate([&](double xi) { return xi * forceDensity(p, xi, s.xi_plus, v); }, s.xi_minus, s.xi_plus) +
        s.xi_plus * s.F_N_impact;
    EXPECT_NEAR(s.torque, moment, 1e-11 * std::abs(moment)) << "v = " << v;
  }
}

}  // namespace
}  // namespace sphere_contact_estimator
