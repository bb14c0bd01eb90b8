// The numerical building blocks of the solvers: real-root isolation of polynomials on an interval, the Gauss-Legendre
// and Gauss-Kronrod rules, and the Magnus step of a traceless 2x2 linear system (the lattice's sliding direction).

// STL
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <stdexcept>
#include <vector>

// Eigen
#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

// GTest
#include <gtest/gtest.h>

// Package
#include "sphere_contact_estimator/core/numerics/magnus_sl2.h"
#include "sphere_contact_estimator/core/numerics/polynomial_roots.h"
#include "sphere_contact_estimator/core/numerics/quadrature_rules.h"

namespace sphere_contact_estimator::numerics
{
namespace
{
// Coefficients of c * prod (s - r_i) * prod ((s - z_j)(s - conj z_j)), ascending powers.
std::vector<double> fromRoots(double c, const std::vector<double>& real, const std::vector<std::pair<double, double>>& complex)
{
  std::vector<double> p{ c };
  const auto times = [&p](const std::vector<double>& q) {
    std::vector<double> r(p.size() + q.size() - 1, 0.0);
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = 0; j < q.size(); ++j)
        r[i + j] += p[i] * q[j];
    p = r;
  };
  for (double r : real)
    times({ -r, 1.0 });
  for (const auto& [re, im] : complex)
    times({ re * re + im * im, -2.0 * re, 1.0 });
  return p;
}

TEST(PolynomialRoots, FindsEveryRealRootOfRandomPolynomials)
{
  // Degrees 1 to 12: simple real roots inside and outside the interval, complex pairs, random scale and sign.
  // (Higher degrees over a whole interval lose digits in the change of basis; the solver's polynomials of higher
  // degree are Taylor series expanded at the interval's start, tested below.)
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 400; ++trial)
  {
    const int n_real = 1 + trial % 6, n_complex = trial % 4;
    std::vector<double> real;
    std::vector<std::pair<double, double>> complex;
    for (int i = 0; i < n_real; ++i)
      real.push_back(1.5 * u(rng));
    for (int i = 0; i < n_complex; ++i)
      complex.emplace_back(u(rng), 0.01 + std::abs(u(rng)));
    std::sort(real.begin(), real.end());
    if (std::adjacent_find(real.begin(), real.end(), [](double a, double b) { return b - a < 1e-3; }) != real.end())
      continue;  // well separated: the expected list is then unambiguous
    const std::vector<double> c = fromRoots(std::pow(10.0, 4.0 * u(rng)), real, complex);
    const int n = static_cast<int>(c.size()) - 1;
    double roots[64];
    const int k = signChanges(c.data(), n, -1.0, 1.0, roots, 64);
    std::vector<double> expected;
    for (double r : real)
      if (r > -1.0 && r < 1.0)
        expected.push_back(r);
    ASSERT_EQ(k, static_cast<int>(expected.size())) << "trial " << trial << " degree " << n;
    // multiplied-out coefficients carry rounding that moves clustered roots by up to ~1e-9 (Wilkinson)
    for (int i = 0; i < k; ++i)
      EXPECT_NEAR(roots[i], expected[i], 1e-8) << "trial " << trial << " degree " << n;
    if (k > 0)  // max_roots = 1 gives the first
    {
      double first;
      ASSERT_EQ(signChanges(c.data(), n, -1.0, 1.0, &first, 1), 1);
      EXPECT_NEAR(first, expected.front(), 1e-8);
    }
  }
}

TEST(PolynomialRoots, TouchesAreNoSignChanges)
{
  // (s - 0.3)^2 (s + 0.5): one sign change (at -0.5), the double root is a touch; so is (s - 0.1)^2 + 0.
  const std::vector<double> c = fromRoots(2.0, { 0.3, 0.3, -0.5 }, {});
  double roots[4];
  ASSERT_EQ(signChanges(c.data(), 3, -1.0, 1.0, roots, 4), 1);
  EXPECT_NEAR(roots[0], -0.5, 1e-12);
  const std::vector<double> q = fromRoots(1.0, { 0.1, 0.1 }, {});
  EXPECT_EQ(signChanges(q.data(), 2, -1.0, 1.0, roots, 4), 0);
  const std::vector<double> quartic = fromRoots(1.0, { 0.1, 0.1, 0.7, 0.7 }, {});
  EXPECT_EQ(signChanges(quartic.data(), 4, -1.0, 1.0, roots, 4), 0);
}

TEST(PolynomialRoots, ClusteredRootsAndWideScales)
{
  // Roots 1e-6 apart (between them the cubic is ~1e-13, well above rounding), and a polynomial whose
  // coefficients span 1e-12 to 1e12 (huge slips make such ones).
  const std::vector<double> c = fromRoots(1.0, { 0.2, 0.2 + 1e-6, -0.7 }, {});
  double roots[4];
  ASSERT_EQ(signChanges(c.data(), 3, -1.0, 1.0, roots, 4), 3);
  EXPECT_NEAR(roots[1], 0.2, 1e-10);  // a pair 1e-6 apart: each to ~eps / 1e-6
  EXPECT_NEAR(roots[2], 0.2 + 1e-6, 1e-10);
  // 1e12 s^2 - 2e-12 s... : roots at 0 and 2e-24 are below any interval here; 1e12 (s - 1e-6)(s - 3e-6)
  const std::vector<double> d = fromRoots(1e12, { 1e-6, 3e-6 }, {});
  ASSERT_EQ(signChanges(d.data(), 2, 0.0, 1.0, roots, 4), 2);
  EXPECT_NEAR(roots[0], 1e-6, 1e-19);
  EXPECT_NEAR(roots[1], 3e-6, 1e-19);
}

TEST(PolynomialRoots, EventSearchesOfLowDegreeFromARootAtTheStart)
{
  // As the lattice's onset search meets them: |u|^2 - f^2 along a step, degree 4 or less, starting on the bound (a
  // root of multiplicity k at s = 0, the interval's end) or inside it. Cubics and quartics with one sign change go
  // straight to the root, with more through the monotone pieces, and a root at 0 outside the open interval is
  // divided out: every case must give the same sign changes as the roots it was built from.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial)
  {
    const int k = trial % 3;                    // multiplicity of the root at s = 0
    const int n_real = trial / 3 % (5 - k);     // further real roots: degree k + n_real (+ 2 with a complex pair)
    const bool pair = k + n_real <= 2 && trial % 2;
    std::vector<double> real(k, 0.0);
    std::vector<double> others;
    for (int i = 0; i < n_real; ++i)
      others.push_back(0.02 + 1.2 * (0.5 + 0.5 * u(rng)));  // in (0.02, 1.22): inside [0, 1] or past it
    std::sort(others.begin(), others.end());
    if (std::adjacent_find(others.begin(), others.end(), [](double a, double b) { return b - a < 1e-3; }) !=
        others.end())
      continue;
    real.insert(real.end(), others.begin(), others.end());
    std::vector<std::pair<double, double>> complex;
    if (pair)
      complex.emplace_back(u(rng), 0.01 + std::abs(u(rng)));
    const std::vector<double> c = fromRoots(std::pow(10.0, 3.0 * u(rng)), real, complex);
    const int n = static_cast<int>(c.size()) - 1;
    if (n < 1)
      continue;
    std::vector<double> expected;
    for (double r : others)
      if (r < 1.0)
        expected.push_back(r);
    double roots[8];
    const int found = signChanges(c.data(), n, 0.0, 1.0, roots, 8);
    ASSERT_EQ(found, static_cast<int>(expected.size())) << "trial " << trial << " degree " << n << " k " << k;
    for (int i = 0; i < found; ++i)
      EXPECT_NEAR(roots[i], expected[i], 1e-9) << "trial " << trial << " degree " << n << " k " << k;
    if (!expected.empty())
    {
      double first;
      ASSERT_EQ(signChanges(c.data(), n, 0.0, 1.0, &first, 1), 1);
      EXPECT_NEAR(first, expected.front(), 1e-9);
    }
    ++checked;
  }
  EXPECT_GT(checked, 2000);
  // inside the interval the root at 0 is a sign change where its multiplicity is odd, and is not divided out
  double roots[4];
  const std::vector<double> odd = fromRoots(1.0, { 0.0, 0.5 }, {}), even = fromRoots(1.0, { 0.0, 0.0, 0.5 }, {});
  ASSERT_EQ(signChanges(odd.data(), 2, -1.0, 1.0, roots, 4), 2);
  EXPECT_NEAR(roots[0], 0.0, 1e-15);
  EXPECT_NEAR(roots[1], 0.5, 1e-15);
  ASSERT_EQ(signChanges(even.data(), 3, -1.0, 1.0, roots, 4), 1);
  EXPECT_NEAR(roots[0], 0.5, 1e-15);
  // and beside it, on (-1, 0), the root at 0 is the interval's end: p = s (s - 0.5) changes sign nowhere inside
  EXPECT_EQ(signChanges(odd.data(), 2, -1.0, 0.0, roots, 4), 0);
}

TEST(PolynomialRoots, NeverWritesMoreRootsThanAsked)
{
  // A quadratic with two roots and a cubic with three, asked for one: the first only, and nothing past it
  // (the quadratic's closed form once wrote its second root one past the caller's single double)
  const std::vector<double> q = fromRoots(1.0, { 0.25, 0.5 }, {});
  const std::vector<double> c = fromRoots(1.0, { -0.5, 0.25, 0.5 }, {});
  for (const auto* p : { &q, &c })
  {
    double out[3] = { -7.0, -7.0, -7.0 };
    ASSERT_EQ(signChanges(p->data(), static_cast<int>(p->size()) - 1, -1.0, 1.0, out, 1), 1);
    EXPECT_NEAR(out[0], p == &q ? 0.25 : -0.5, 1e-14);
    EXPECT_EQ(out[1], -7.0);
    EXPECT_EQ(out[2], -7.0);
  }
}

TEST(PolynomialRoots, TaylorSeriesOfHighDegree)
{
  // As the path solver builds them: the series of cos(3 s) - 0.3 and of sin(5 s) e^(-s) - 0.1 to degree 30 about
  // s = 0, on [0, 1.2]: roots acos(0.3) / 3, and the sign changes of the second found by bisection on the exact
  // function.
  double c[31], d[31];
  for (int k = 0; k <= 30; ++k)
  {
    double fact = 1.0;
    for (int i = 2; i <= k; ++i)
      fact *= i;
    c[k] = (k % 2 ? 0.0 : ((k / 2) % 2 ? -1.0 : 1.0)) * std::pow(3.0, k) / fact - (k == 0 ? 0.3 : 0.0);
    // Im((i 5 - 1)^k) / k!: the series of Im(e^{(5i - 1) s})
    const std::complex<double> z = std::pow(std::complex<double>(-1.0, 5.0), k);
    d[k] = z.imag() / fact - (k == 0 ? 0.1 : 0.0);
  }
  double roots[8];
  ASSERT_EQ(signChanges(c, 30, 0.0, 1.2, roots, 8), 1);
  EXPECT_NEAR(roots[0], std::acos(0.3) / 3.0, 1e-13);
  const auto g = [](double s) { return std::sin(5.0 * s) * std::exp(-s) - 0.1; };
  const int k = signChanges(d, 30, 0.0, 1.2, roots, 8);
  ASSERT_EQ(k, 2);  // the third change, past 1.2, is outside
  for (int i = 0; i < k; ++i)
    EXPECT_NEAR(g(roots[i]), 0.0, 1e-12);
}

TEST(PolynomialRoots, NearTouchAtAnEndIsFoundThere)
{
  // As the path solver meets them with tiny deflections: |u|^2 - f^2 with f vanishing at the trailing edge
  // (parabolic pressure), -(1 - s)^2 q(s) + e with e at rounding level, so that the interval's ends differ in sign
  // or not depending on rounding. Whatever is reported must be a root up to rounding: near s = 1, never far from
  // both ends (the midpoint was once reported, which made a bristle slide over half its path).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int reported = 0;
  for (int trial = 0; trial < 2000; ++trial)
  {
    const int n = 4 + trial % 19;  // degrees 4 .. 22
    std::vector<double> q(n - 1);
    for (std::size_t i = 0; i < q.size(); ++i)
      q[i] = (2.0 * u(rng) - 1.0) / static_cast<double>(i + 1);  // a perturbation of 3 that stays positive on [0, 1]
    q[0] = 3.0;
    std::vector<double> c(n + 1, 0.0);  // -(1 - s)^2 q(s)
    for (int i = 0; i + 1 < n; ++i)
    {
      c[i] -= q[i];
      c[i + 1] += 2.0 * q[i];
      c[i + 2] -= q[i];
    }
    c[0] += (2.0 * u(rng) - 1.0) * 1e-16;
    // the interval is the second half of a path, as the solver sees it
    const double lo = 0.5 + 0.2 * u(rng);
    double roots[64];
    const int k = signChanges(c.data(), n, lo, 1.0, roots, 64);
    for (int i = 0; i < k; ++i, ++reported)
      EXPECT_NEAR(roots[i], 1.0, 1e-6) << "trial " << trial << " degree " << n;
  }
  EXPECT_GT(reported, 0);  // the near-touches do get reported, so the check above has something to check
}

TEST(QuadratureRules, GaussLegendreIsExactToDegree2mMinus1)
{
  for (int m = 1; m <= GaussLegendre::kMaxPoints; ++m)
  {
    const GaussLegendre& g = gaussLegendre(m);
    for (int degree = 0; degree <= 2 * m - 1; ++degree)
    {
      double sum = 0.0;
      for (int i = 0; i < m; ++i)
        sum += g.w[i] * std::pow(g.x[i], degree);
      const double exact = degree % 2 ? 0.0 : 2.0 / (degree + 1);
      EXPECT_NEAR(sum, exact, 1e-14) << "m " << m << " degree " << degree;
    }
    const double missed = [&] {  // and not beyond: x^(2m) is integrated with an error
      double sum = 0.0;
      for (int i = 0; i < m; ++i)
        sum += g.w[i] * std::pow(g.x[i], 2 * m);
      return std::abs(sum - 2.0 / (2 * m + 1));
    }();
    if (m <= 20)  // beyond, x^(2m) is integrated to within rounding anyway
    {
      EXPECT_GT(missed, 1e-15) << m;
    }
    EXPECT_TRUE(std::is_sorted(g.x.begin(), g.x.begin() + m));
  }
  EXPECT_THROW(gaussLegendre(0), std::invalid_argument);
  EXPECT_THROW(gaussLegendre(GaussLegendre::kMaxPoints + 1), std::invalid_argument);
}

// A rule's sum of x^degree over [-1, 1] minus the exact integral.
template <std::size_t N>
double momentError(const std::array<double, N>& w, const std::array<double, N>& x, int degree)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < N; ++i)
    sum += w[i] * std::pow(x[i], degree);
  return sum - (degree % 2 ? 0.0 : 2.0 / (degree + 1));
}

TEST(QuadratureRules, KronrodAndItsGaussRule)
{
  // The 15-point Kronrod rule is exact to degree 22, its embedded 7-point Gauss rule to degree 13.
  const GaussKronrod15& r = gaussKronrod15();
  for (int degree = 0; degree <= 22; ++degree)
  {
    EXPECT_NEAR(momentError(r.wk, r.x, degree), 0.0, 1e-14) << degree;
    if (degree <= 13)
    {
      EXPECT_NEAR(momentError(r.wg, r.x, degree), 0.0, 1e-14) << degree;
    }
  }
  int gauss_nodes = 0;
  for (double w : r.wg)
    gauss_nodes += w != 0.0;
  EXPECT_EQ(gauss_nodes, 7);
}

TEST(QuadratureRules, KronrodComplementIsInterpolatoryOnTheOtherEightNodes)
{
  // exact to degree 7 (the interpolatory rule on 8 nodes), not at degree 8, and zero at the Gauss nodes
  const GaussKronrod15& r = gaussKronrod15();
  const std::array<double, 15>& w = kronrodComplement();
  for (int i = 0; i < 15; ++i)
    if (r.wg[i] != 0.0)
    {
      EXPECT_EQ(w[i], 0.0);
    }
  for (int degree = 0; degree <= 8; ++degree)
  {
    const double error = momentError(w, r.x, degree);
    if (degree <= 7)
    {
      EXPECT_NEAR(error, 0.0, 1e-13) << degree;
    }
    else
    {
      EXPECT_GT(std::abs(error), 1e-6);
    }
  }
}

TEST(QuadratureRules, Kronrod7AndItsGaussRule)
{
  // The 7-point Kronrod rule is exact to degree 11 and not 12, its embedded 3-point Gauss rule to degree 5 and not 6;
  // its complement (the interpolatory rule on the 4 Kronrod-only nodes) to degree 3 and not 4, zero at the Gauss nodes;
  // nodes ascending and symmetric
  const GaussKronrod7& r = gaussKronrod7();
  const std::array<double, 7>& c = kronrod7Complement();
  for (int degree = 0; degree <= 12; ++degree)
  {
    const double k = momentError(r.wk, r.x, degree), g = momentError(r.wg, r.x, degree),
                 q = momentError(c, r.x, degree);
    if (degree <= 11)
    {
      EXPECT_NEAR(k, 0.0, 1e-14) << degree;
    }
    else
    {
      EXPECT_GT(std::abs(k), 1e-6);
    }
    if (degree <= 5)
    {
      EXPECT_NEAR(g, 0.0, 1e-14) << degree;
    }
    else if (degree == 6)
    {
      EXPECT_GT(std::abs(g), 1e-6);
    }
    if (degree <= 3)
    {
      EXPECT_NEAR(q, 0.0, 1e-14) << degree;
    }
    else if (degree == 4)
    {
      EXPECT_GT(std::abs(q), 1e-6);
    }
  }
  int gauss_nodes = 0;
  for (int i = 0; i < 7; ++i)
  {
    gauss_nodes += r.wg[i] != 0.0;
    if (r.wg[i] != 0.0)
    {
      EXPECT_EQ(c[i], 0.0);
    }
    EXPECT_EQ(r.x[i], -r.x[6 - i]);
  }
  EXPECT_EQ(gauss_nodes, 3);
  EXPECT_TRUE(std::is_sorted(r.x.begin(), r.x.end()));
}

// A rule's sum of y^degree minus its exact integral against the weight (1 - y^2)^(3/2) on [-1, 1]: B((k + 1) / 2, 5 / 2)
// for even k (substituting t = y^2), 0 for odd.
double jacobiMomentError(const JacobiKronrod& r, const std::array<double, 13>& w, int degree)
{
  double sum = 0.0;
  for (int i = 0; i < r.size; ++i)
    sum += w[i] * std::pow(r.y[i], degree);
  return sum - (degree % 2 ? 0.0 : std::beta(0.5 * (degree + 1), 2.5));
}

TEST(QuadratureRules, JacobiKronrodIsExactForItsWeight)
{
  // Against the weight's own moments (not the tables' source): Kronrod exact to degree 3n + 1, Gauss to 2n - 1, the
  // complement to n, each failing at the first even degree beyond (odd ones vanish by symmetry); n Gauss nodes and
  // n + 1 others, interlaced; every Kronrod weight positive; nodes ascending, symmetric and inside (-1, 1).
  for (int n = JacobiKronrod::kMinPoints; n <= JacobiKronrod::kMaxPoints; ++n)
  {
    const JacobiKronrod& r = jacobiKronrod(n);
    ASSERT_EQ(r.n, n);
    ASSERT_EQ(r.size, 2 * n + 1);
    const auto firstEvenAbove = [](int d) { return d % 2 ? d + 1 : d + 2; };
    for (int degree = 0; degree <= firstEvenAbove(3 * n + 1); ++degree)
    {
      const double k = jacobiMomentError(r, r.wk, degree), g = jacobiMomentError(r, r.wg, degree),
                   q = jacobiMomentError(r, r.wr, degree);
      if (degree <= 3 * n + 1)
      {
        EXPECT_NEAR(k, 0.0, 1e-15) << n << " " << degree;
      }
      else if (degree == firstEvenAbove(3 * n + 1))
      {
        EXPECT_GT(std::abs(k), 1e-9) << n << " " << degree;
      }
      if (degree <= 2 * n - 1)
      {
        EXPECT_NEAR(g, 0.0, 1e-15) << n << " " << degree;
      }
      else if (degree == 2 * n)
      {
        EXPECT_GT(std::abs(g), 1e-9) << n << " " << degree;
      }
      if (degree <= n)
      {
        EXPECT_NEAR(q, 0.0, 1e-15) << n << " " << degree;
      }
      else if (degree == firstEvenAbove(n))
      {
        EXPECT_GT(std::abs(q), 1e-9) << n << " " << degree;
      }
    }
    int gauss_nodes = 0;
    for (int i = 0; i < r.size; ++i)
    {
      const bool gauss = r.wg[i] != 0.0;
      gauss_nodes += gauss;
      EXPECT_EQ(gauss, i % 2 == 1) << n << " " << i;  // interlaced: Kronrod-only nodes first and last
      EXPECT_EQ(gauss ? r.wr[i] : r.wg[i], 0.0);
      EXPECT_GT(r.wk[i], 0.0);
      EXPECT_EQ(r.y[i], -r.y[r.size - 1 - i]);
      EXPECT_LT(std::abs(r.y[i]), 1.0);
    }
    EXPECT_EQ(gauss_nodes, n);
    EXPECT_TRUE(std::is_sorted(r.y.begin(), r.y.begin() + r.size));
  }
  EXPECT_THROW(jacobiKronrod(2), std::invalid_argument);
  EXPECT_THROW(jacobiKronrod(7), std::invalid_argument);
}

}  // namespace
namespace
{
Eigen::Matrix2d matrixOf(const Sl2& X)
{
  Eigen::Matrix2d m;
  m << X.x, X.y + X.z, X.y - X.z, -X.x;
  return m;
}

// A smooth sliding bristle's generator along a step: M(s) = (-P H + Q S) / (2 b) with P, Q affine and b a bound that
// varies (drive over bound as the lattice's).
struct Generator
{
  double p0, p1, q0, q1, b0, b1, b2;
  Sl2 at(double s) const
  {
    const double b = b0 + b1 * s + b2 * std::sin(3.0 * s);
    return { -(p0 + p1 * s) / (2.0 * b), (q0 + q1 * s) / (2.0 * b), 0.0 };
  }
};

// y(d) from y(0) = (0, 1) by classical Runge-Kutta at n steps: the reference, independent of the Magnus formulas
Eigen::Vector2d rungeKutta(const Generator& g, double d, int n)
{
  Eigen::Vector2d y(0.0, 1.0);
  const double h = d / n;
  const auto f = [&](double s, const Eigen::Vector2d& v) { return Eigen::Vector2d(matrixOf(g.at(s)) * v); };
  for (int i = 0; i < n; ++i)
  {
    const double s = i * h;
    const Eigen::Vector2d k1 = f(s, y), k2 = f(s + 0.5 * h, y + 0.5 * h * k1), k3 = f(s + 0.5 * h, y + 0.5 * h * k2),
                          k4 = f(s + h, y + h * k3);
    y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return y;
}

double angleOf(const Eigen::Vector2d& y) { return std::atan2(y.x(), y.y()); }
}  // namespace

TEST(MagnusSl2, ExpColumnIsTheMatrixExponentialsAndItsAngleGradientTheDerivative)
{
  // Seeded random exponents across the series' three degrees and both closed forms (delta from -25 to 25): the
  // column against Eigen's matrix exponential, the angle's gradient against central differences.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst_column = 0.0, worst_gradient = 0.0;
  for (int n = 0; n < 2000; ++n)
  {
    const double scale = std::pow(10.0, -3.0 + 3.7 * (0.5 + 0.5 * unit(rng)));
    const Sl2 X{ scale * unit(rng), scale * unit(rng), scale * unit(rng) };
    double y1, y2, grad[3];
    expColumn2(X, y1, y2, grad);
    const Eigen::Vector2d reference = matrixOf(X).exp().col(1);
    worst_column = std::max(worst_column, (Eigen::Vector2d(y1, y2) - reference).norm() / reference.norm());
    for (int k = 0; k < 3; ++k)
    {
      const double eps = 1e-6 * std::max(1.0, scale);
      Sl2 plus = X, minus = X;
      (k == 0 ? plus.x : k == 1 ? plus.y : plus.z) += eps;
      (k == 0 ? minus.x : k == 1 ? minus.y : minus.z) -= eps;
      double a1, a2, b1, b2, unused[3];
      expColumn2(plus, a1, a2, unused);
      expColumn2(minus, b1, b2, unused);
      double difference = std::atan2(a1, a2) - std::atan2(b1, b2);
      difference -= 2.0 * M_PI * std::round(difference / (2.0 * M_PI));
      worst_gradient = std::max(worst_gradient, std::abs(difference / (2.0 * eps) - grad[k]) /
                                                    std::max(1.0, std::abs(grad[k])));
    }
  }
  std::printf("exp column: largest relative error %.3g; angle gradient: %.3g\n", worst_column, worst_gradient);
  EXPECT_LT(worst_column, 1e-13);
  EXPECT_LT(worst_gradient, 1e-6);
}

TEST(MagnusSl2, SixthOrderStepAndItsFourthOrderEstimate)
{
  // Seeded random generators: halving the step divides the sixth-order step's local error by 2^7 and the
  // fourth-order exponent's by 2^5 (their sums over the set, each at least 3/4 of that: one generator's error can
  // pass through zero between two steps), and the fourth's error, which the estimate stands on, exceeds the sixth's.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0, fourth_larger = 0;
  double sum6[2] = { 0.0, 0.0 }, sum4[2] = { 0.0, 0.0 };
  for (int n = 0; n < 200; ++n)
  {
    const Generator g{ 2.0 * unit(rng), 2.0 * unit(rng), 2.0 * unit(rng), 2.0 * unit(rng),
                       1.0 + 0.5 * unit(rng), 0.5 * unit(rng), 0.2 * unit(rng) };
    for (int half = 0; half < 2; ++half)
    {
      const double d = half ? 0.1 : 0.2;
      Sl2 A[3];
      for (int i = 0; i < 3; ++i)
        A[i] = d * g.at(kMagnusNodes[i] * d);
      const Sl2 simpson = (d / 6.0) * (g.at(0.0) + 4.0 * g.at(0.5 * d) + g.at(d));
      Sl2 fourth;
      const Sl2 omega = magnus6(A, gaussIntegral(A), simpson, fourth);
      double y1, y2, z1, z2, grad[3];
      expColumn2(omega, y1, y2, grad);
      expColumn2(fourth, z1, z2, grad);
      const double reference = angleOf(rungeKutta(g, d, 4000));
      const double error6 = std::abs(std::atan2(y1, y2) - reference), error4 = std::abs(std::atan2(z1, z2) - reference);
      sum6[half] += error6;
      sum4[half] += error4;
      ++compared;
      fourth_larger += error4 > error6;
    }
  }
  const double ratio6 = sum6[0] / sum6[1], ratio4 = sum4[0] / sum4[1];
  std::printf("%d steps: halving the step divides the errors by %.1f (sixth) and %.1f (fourth); the fourth's larger at "
              "%d\n", compared, ratio6, ratio4, fourth_larger);
  EXPECT_GT(ratio6, 0.75 * 128.0);
  EXPECT_GT(ratio4, 0.75 * 32.0);
  EXPECT_GE(fourth_larger, compared * 95 / 100);
}

}  // namespace sphere_contact_estimator::numerics
