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

namespace
{
// The non-negative halves of jacobiKronrod's rules, n = 3 ... 6: nodes, Kronrod, Gauss and complement weights (the
// node 0 once). Computed from the moments of (1 - y^2)^(3/2), B((k + 1) / 2, 5 / 2) for even k, in 60-digit arithmetic:
// the Gauss nodes as the roots of the weight's orthogonal polynomial p_n, the Kronrod-only ones as those of Stieltjes'
// polynomial E_{n+1} (orthogonal to every polynomial of degree <= n against the weight times p_n), every weight as the
// interpolatory rule's on its nodes.
struct JacobiHalf
{
  int n;
  double y[7], wk[7], wg[7], wr[7];
};
constexpr JacobiHalf kJacobiHalves[] = {
  { 3,
    { 0.0, 3.06460526793770390739e-1, 6.12372435695794524549e-1, 8.59892597276321523378e-1 },
    { 3.01069295969021852019e-1, 2.70062794683556341157e-1, 1.4199288829784376219e-1, 2.64582915821752028548e-2 },
    { 6.54498469497873591346e-1, 0.0, 2.61799387799149436539e-1, 0.0 },
    { 0.0, 5.22661861797558785309e-1, 0.0, 6.63867607505274469023e-2 } },
  { 4,
    { 0.0, 2.66216481931919458815e-1, 5.08991766267433496151e-1, 7.27412389740367290322e-1, 9.01307912591767818167e-1 },
    { 2.72112697015479565857e-1, 2.28985893372165430771e-1, 1.47391317802340905405e-1, 6.52391337758635128186e-2,
      1.13759290899766002885e-2 },
    { 0.0, 4.65912241485857500436e-1, 0.0, 1.23136381062228731775e-1, 0.0 },
    { 5.28358764467374317378e-1, 0.0, 2.99547592441534711687e-1, 0.0, 2.5321647872864361836e-2 } },
  { 5,
    { 0.0, 2.34863400647613934802e-1, 4.42930458136057122056e-1, 6.28790741059521586815e-1, 7.98214220988774342785e-1,
      9.28418756270065911893e-1 },
    { 2.40549437490776917339e-1, 2.05732526710232134528e-1, 1.39474307878100602807e-1, 8.45869668631197623581e-2,
      3.3715904186755540404e-2, 5.26419816448973344537e-3 },
    { 4.58148928648511513942e-1, 0.0, 2.97491234438742284635e-1, 0.0, 6.24829237850881906051e-2, 0.0 },
    { 0.0, 4.15773608786535906228e-1, 0.0, 1.58848305295246752148e-1, 0.0, 1.44267084663035738359e-2 } },
  { 6,
    { 0.0, 1.98187323325468024897e-1, 3.91036502198764761015e-1, 5.64399481003359485011e-1, 7.14189794978777699687e-1,
      8.44750603518456376201e-1, 9.44763963247901657283e-1 },
    { 1.98314245306752553856e-1, 1.85909965960527187764e-1, 1.44577390051900729567e-1, 9.0303327526018338084e-2,
      4.81946805876185573079e-2, 1.81222360755524945102e-2, 2.78389969309264805006e-3 },
    { 0.0, 3.68444376374489365679e-1, 0.0, 1.86608725297401668319e-1, 0.0, 3.39955208761951982146e-2, 0.0 },
    { 4.05515000005394339663e-1, 0.0, 2.83822607231588301335e-1, 0.0, 9.59072297085580852467e-2, 0.0,
      6.56128560524267579893e-3 } },
};

JacobiKronrod unfold(const JacobiHalf& h)
{
  JacobiKronrod r;
  r.n = h.n;
  r.size = 2 * h.n + 1;
  for (int i = 0; i <= h.n; ++i)
  {
    const int up = h.n + i, down = h.n - i;
    r.y[up] = h.y[i];
    r.y[down] = -h.y[i];
    r.wk[up] = r.wk[down] = h.wk[i];
    r.wg[up] = r.wg[down] = h.wg[i];
    r.wr[up] = r.wr[down] = h.wr[i];
  }
  return r;
}
}  // namespace

const JacobiKronrod& jacobiKronrod(int n)
{
  static const std::array<JacobiKronrod, 4> rules = { unfold(kJacobiHalves[0]), unfold(kJacobiHalves[1]),
                                                      unfold(kJacobiHalves[2]), unfold(kJacobiHalves[3]) };
  if (n < JacobiKronrod::kMinPoints || n > JacobiKronrod::kMaxPoints)
    throw std::invalid_argument("jacobiKronrod: number of Gauss points out of range");
  return rules[n - JacobiKronrod::kMinPoints];
}

void prepareQuadratureRules()
{
  gaussLegendre(1);
  kronrodComplement();
  kronrod7Complement();
  jacobiKronrod(JacobiKronrod::kMinPoints);
}

}  // namespace sphere_contact_estimator::numerics
