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

const std::array<double, 15>& kronrodComplement()
{
  static const std::array<double, 15> weights = [] {
    const GaussKronrod15& r = gaussKronrod15();
    std::array<double, 15> w{};
    for (int j = 0; j < 15; ++j)
    {
      if (r.wg[j] != 0.0)
        continue;
      // the Lagrange polynomial of node j over the other Kronrod-only nodes, integrated term by term over [-1, 1]
      double c[8] = { 1.0 };  // ascending coefficients
      int degree = 0;
      for (int k = 0; k < 15; ++k)
      {
        if (k == j || r.wg[k] != 0.0)
          continue;
        const double scale = 1.0 / (r.x[j] - r.x[k]);
        for (int d = degree + 1; d >= 0; --d)  // c <- c (x - x_k) / (x_j - x_k)
          c[d] = ((d > 0 ? c[d - 1] : 0.0) - r.x[k] * (d <= degree ? c[d] : 0.0)) * scale;
        ++degree;
      }
      for (int d = 0; d <= degree; d += 2)
        w[j] += 2.0 * c[d] / (d + 1);
    }
    return w;
  }();
  return weights;
}

}  // namespace sphere_contact_estimator::numerics
