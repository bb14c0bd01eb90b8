#include "sphere_contact_estimator/core/numerics/quadrature_rules.h"

// STL
#include <cmath>
#include <stdexcept>
#include <vector>

// Boost
#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

namespace sphere_contact_estimator::numerics
{
namespace
{
GaussLegendre build(int m)
{
  GaussLegendre g;
  g.m = m;
  for (int i = 0; i < m; ++i)
  {
    // Newton on P_m from the Chebyshev-like guess; P_m and P_m' by the three-term recurrence
    double x = std::cos(boost::math::double_constants::pi * (i + 0.75) / (m + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it)
    {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= m; ++k)
      {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = m * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16)
        break;
    }
    g.x[i] = -x;  // ascending
    g.w[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return g;
}
}  // namespace

const GaussLegendre& gaussLegendre(int m)
{
  static const std::vector<GaussLegendre> rules = [] {
    std::vector<GaussLegendre> r(GaussLegendre::kMaxPoints + 1);
    for (int k = 1; k <= GaussLegendre::kMaxPoints; ++k)
      r[k] = build(k);
    return r;
  }();
  if (m < 1 || m > GaussLegendre::kMaxPoints)
    throw std::invalid_argument("gaussLegendre: number of points out of range");
  return rules[m];
}

const GaussKronrod15& gaussKronrod15()
{
  static const GaussKronrod15 rule = [] {
    // Boost lists the non-negative half: Kronrod nodes at every index, Gauss nodes at the even ones
    const auto& kx = boost::math::quadrature::gauss_kronrod<double, 15>::abscissa();
    const auto& kw = boost::math::quadrature::gauss_kronrod<double, 15>::weights();
    const auto& gw = boost::math::quadrature::gauss<double, 7>::weights();
    GaussKronrod15 r;
    for (int i = 0; i < 8; ++i)
    {
      const double g = i % 2 == 0 ? gw[i / 2] : 0.0;
      r.x[7 + i] = kx[i];
      r.wk[7 + i] = kw[i];
      r.wg[7 + i] = g;
      r.x[7 - i] = -kx[i];
      r.wk[7 - i] = kw[i];
      r.wg[7 - i] = g;
    }
    return r;
  }();
  return rule;
}

namespace
{
// Weights of the interpolatory rule on the nodes where wg is 0 (the Kronrod-only ones), 0 at the others.
template <std::size_t N>
std::array<double, N> complement(const std::array<double, N>& x, const std::array<double, N>& wg)
{
  std::array<double, N> w{};
  for (std::size_t j = 0; j < N; ++j)
  {
    if (wg[j] != 0.0)
      continue;
    // the Lagrange polynomial of node j over the other Kronrod-only nodes, integrated term by term over [-1, 1]
    double c[N] = { 1.0 };  // ascending coefficients
    int degree = 0;
    for (std::size_t k = 0; k < N; ++k)
    {
      if (k == j || wg[k] != 0.0)
        continue;
      const double scale = 1.0 / (x[j] - x[k]);
      for (int d = degree + 1; d >= 0; --d)  // c <- c (x - x_k) / (x_j - x_k)
        c[d] = ((d > 0 ? c[d - 1] : 0.0) - x[k] * (d <= degree ? c[d] : 0.0)) * scale;
      ++degree;
    }
    for (int d = 0; d <= degree; d += 2)
      w[j] += 2.0 * c[d] / (d + 1);
  }
  return w;
}
}  // namespace

const std::array<double, 15>& kronrodComplement()
{
  static const std::array<double, 15> weights = complement(gaussKronrod15().x, gaussKronrod15().wg);
  return weights;
}

const GaussKronrod7& gaussKronrod7()
{
  static const GaussKronrod7 rule = [] {
    // the non-negative half (Boost has no 7-point pair): Kronrod's extension of the 3-point Gauss rule, nodes and
    // weights to 30 digits (exact to degree 11, test QuadratureRules.Kronrod7AndItsGaussRule)
    const double x[4] = { 0.0, 0.434243749346802558002071502844628, 0.774596669241483377035853079956480,
                          0.960491268708020283423507092629080 };
    const double wk[4] = { 0.450916538658474142345110087045571, 0.401397414775962222905051818618432,
                           0.268488089868333440728569280666710, 0.104656226026467265193823857192073 };
    const double wg[4] = { 8.0 / 9.0, 0.0, 5.0 / 9.0, 0.0 };
    GaussKronrod7 r;
    for (int i = 0; i < 4; ++i)
    {
      r.x[3 + i] = x[i];
      r.wk[3 + i] = wk[i];
      r.wg[3 + i] = wg[i];
      r.x[3 - i] = -x[i];
      r.wk[3 - i] = wk[i];
      r.wg[3 - i] = wg[i];
    }
    return r;
  }();
  return rule;
}

const std::array<double, 7>& kronrod7Complement()
{
  static const std::array<double, 7> weights = complement(gaussKronrod7().x, gaussKronrod7().wg);
  return weights;
}

}  // namespace sphere_contact_estimator::numerics
