#include "rim_entry.h"

// Package
#include "rim_integral.h"

// STL
#include <algorithm>
#include <cmath>

// Eigen
#include <Eigen/LU>

namespace sphere_contact_estimator::lattice
{
namespace
{
constexpr int kN = 5;
// Chebyshev-Lobatto points on [0, 1], (1 - cos(k pi / 4)) / 2: 0, 1/2 and 1 among them (the cruder interpolant's)
constexpr double kX[kN] = { 0.0, 0.14644660940672624, 0.5, 0.85355339059327376, 1.0 };

// The interpolant's monomial coefficients from its values (the Vandermonde matrix's inverse), and x_i^(k + 1) for the
// partial integrals int_0^x_i x^(kappa + k) dx = x_i^(kappa + k + 1) / (kappa + k + 1), whose x_i^kappa the kernel's
// own value at x_i cancels
struct Tables
{
  double V_inv[kN][kN];
  double X_pow[kN][kN];
};

const Tables& tables()
{
  static const Tables t = [] {
    Tables r;
    Eigen::Matrix<double, kN, kN> V;
    for (int i = 0; i < kN; ++i)
      for (int k = 0; k < kN; ++k)
        V(i, k) = std::pow(kX[i], k);
    const Eigen::Matrix<double, kN, kN> inv = V.inverse();
    for (int k = 0; k < kN; ++k)
      for (int j = 0; j < kN; ++j)
        r.V_inv[k][j] = inv(k, j);
    for (int i = 0; i < kN; ++i)
      for (int k = 0; k < kN; ++k)
        r.X_pow[i][k] = std::pow(kX[i], k + 1);
    return r;
  }();
  return t;
}

// omega's poles at least this many steps' lengths from [0, d]: phi's interpolants converge as rho^-n, rho the
// Bernstein ellipse's through its nearest singularity, here rho of about 4 or more, so that the quartic's error stands
// about rho^-2 below the quadratic's, whose difference from it the bound takes
constexpr double kPoleDistance = 1.0;
// Psi's least over the step against its largest (below): e^-2
constexpr double kPsiLeast = 0.135;
}  // namespace

bool RimEntry::step(double c, const Eigen::Vector2d& w0, const Eigen::Vector2d& w_dot, double t0, double t1, double t2,
                    double d, Result& out)
{
  out.reach = 1.0;
  if (!(c > 0.0 && t1 > 0.0 && t2 < 0.0 && d > 0.0 && std::abs(t0) <= 1e-3 * t1 * d))
    return false;
  const double s_b = -t1 / t2;  // t = t2 s (s - s_b)
  if (!(d <= 0.5 * s_b))
    return false;  // the crossing ahead, where 1 / t has its other pole, within a step's length
  const Tables& tb = tables();
  // The drive's turn omega = (w x w') / |w|^2 has its poles where |w|^2 = |w0 + s w'|^2 vanishes, at the vertex s_v
  // +- i |w0 x w'| / |w'|^2: that far from [0, d] at least, and |w| least there (or at an end)
  const double cross = w0.x() * w_dot.y() - w0.y() * w_dot.x();
  const double wd2 = w_dot.squaredNorm();
  const double s_v = wd2 > 0.0 ? -w0.dot(w_dot) / wd2 : 0.0;
  const double beyond = s_v < 0.0 ? -s_v : (s_v > d ? s_v - d : 0.0);
  const double h_pole = wd2 > 0.0 ? std::abs(cross) / wd2 : INFINITY;
  if (wd2 > 0.0 && !(h_pole * h_pole + beyond * beyond >= kPoleDistance * kPoleDistance * d * d))
    return false;
  double wn[kN], om[kN], b_dot[kN];
  for (int i = 0; i < kN; ++i)
  {
    const double s = kX[i] * d;
    const Eigen::Vector2d w = w0 + s * w_dot;
    const double w2 = w.squaredNorm();
    if (!(w2 > 0.0))
      return false;
    wn[i] = std::sqrt(w2);
    om[i] = cross / w2;
    b_dot[i] = c * (t1 + 2.0 * t2 * s);
  }
  const double kappa = wn[0] / (c * t1);  // |w| / b' at the rim
  if (!(kappa > 1.0))
    return false;  // it adheres as it enters (or only just slides)
  const double w_least = s_v > 0.0 && s_v < d ? std::abs(cross) / std::sqrt(wd2) : std::min(wn[0], wn[4]);
  if (!(w_least > 0.0))
    return false;  // (|w| vanishes within the step: driveNormThird's least |w|, below)
  // Lambda(d) - Lambda(s) = (1 / c) int_s^d W / t, W = w0 + a1 s + a2 s^2 through |w| at 0, d / 2, d: by partial
  // fractions W / t = a2 / t2 + A / s + B / (s - s_b), A = W(0) / t1 = kappa c, B = -W(s_b) / t1 (eq. 4b's decay
  // integrated as nearRim does, the crossing behind at 0):
  //   Lambda(d) - Lambda(s) = kappa ln(d / s) + (a2 (d - s) / t2 + B ln((s_b - d) / (s_b - s))) / c,
  // e^{-that} = (s / d)^kappa Psi(s), Psi(d) = 1
  const double a2 = 2.0 * (wn[0] - 2.0 * wn[2] + wn[4]) / (d * d), a1 = (wn[4] - wn[0]) / d - a2 * d;
  const double B = -(wn[0] + s_b * (a1 + a2 * s_b)) / t1;
  double Psi[kN];
  double Psi_lo = 1.0, Psi_hi = 1.0;
  for (int i = 0; i < kN; ++i)
  {
    const double gap = (1.0 - kX[i]) * d;  // d - s
    Psi[i] = i == kN - 1 ? 1.0 : std::exp(-(a2 * gap / t2 + B * std::log1p(-gap / (s_b - kX[i] * d))) / c);
    Psi_lo = std::min(Psi_lo, Psi[i]);
    Psi_hi = std::max(Psi_hi, Psi[i]);
  }
  // Psi, of the drive's change and the far crossing, is as steep as e^{-kappa (1 - x) d / s_b} where kappa is large:
  // there its interpolant neither converges nor sees its error (with Psi ranging over 1e-10, the error stood a fifth
  // above the cruder interpolant's difference; over 1e3, 0.37 of it with the answer a third off), which a shorter step
  // keeps within a factor e^2 (test RimEntry.ItsBoundHoldsFromTheRimOverEveryStepLength: error / bound at most 0.28
  // over 13 seeds' 16 700 entries, kappa to 3e5)
  if (!(Psi_lo >= kPsiLeast * Psi_hi))
  {
    out.reach = Psi_lo > 0.0 ? std::log(kPsiLeast) / std::log(Psi_lo / Psi_hi) : 0.0;
    return false;
  }
  double inv[kN];  // 1 / (kappa + k + 1)
  for (int k = 0; k < kN; ++k)
    inv[k] = 1.0 / (kappa + k + 1.0);
  // A Picard pass: phi at the nodes from T there, its interpolant's integrals against x^kappa to each node (T there,
  // T[kN - 1] at d) and, from the three at 0, 1/2, 1, the cruder one's to d
  double I3 = 0.0, phi_max = 0.0;
  const auto pass = [&](const double T[kN], double T_next[kN]) {
    double phi[kN], coef[kN];
    phi_max = 0.0;
    for (int i = 0; i < kN; ++i)
    {
      phi[i] = Psi[i] * 0.5 * om[i] * (1.0 + T[i] * T[i]);
      phi_max = std::max(phi_max, std::abs(phi[i]));
    }
    for (int k = 0; k < kN; ++k)
    {
      double sum = 0.0;
      for (int j = 0; j < kN; ++j)
        sum += tb.V_inv[k][j] * phi[j];
      coef[k] = sum * inv[k];
    }
    T_next[0] = 0.0;
    for (int i = 1; i < kN; ++i)
    {
      double sum = 0.0;
      for (int k = 0; k < kN; ++k)
        sum += coef[k] * tb.X_pow[i][k];
      T_next[i] = -d * sum / Psi[i];
    }
    const double q2 = 2.0 * (phi[0] - 2.0 * phi[2] + phi[4]), q1 = phi[4] - phi[0] - q2;
    I3 = d * (phi[0] * inv[0] + q1 * inv[1] + q2 * inv[2]);
  };
  const double zero[kN] = { 0.0, 0.0, 0.0, 0.0, 0.0 };
  double Ta[kN], Tb[kN];
  pass(zero, Ta);
  pass(Ta, Tb);
  // The error of T(d):
  // - the quadrature's: the cruder interpolant's difference;
  const double quad = std::abs(-Tb[kN - 1] - I3);
  // - the Picard passes': the map T -> -int K (omega / 2) (1 + T^2) has Lipschitz constant L <= max|omega| max|T|
  //   max_s int_0^s K(sigma, s) d sigma, the last at most d / (kappa + 1) Psi_hi / Psi_lo ((sigma / s)^kappa against
  //   Psi's ratio); its fixed point lies within L / (1 - L) |Tb - Ta| of Tb;
  double T_max = 0.0, change = 0.0;
  for (int i = 0; i < kN; ++i)
  {
    T_max = std::max({ T_max, std::abs(Ta[i]), std::abs(Tb[i]) });
    change = std::max(change, std::abs(Tb[i] - Ta[i]));
  }
  T_max += quad;
  const double om_max = std::abs(cross) / (w_least * w_least);
  const double L = om_max * T_max * d * inv[0] * Psi_hi / Psi_lo;
  if (!(L < 0.5))
    return false;
  const double picard = L / (1.0 - L) * (change + quad);
  // - the fit of |w|: nearRim's bound on Lambda's error, |W - |w|| <= |w|''' / 12 d^2 min(s, d - s) (driveNormThird),
  //   against int_0^d s / (c t) = ln(1 - d / s_b) / (c t2); through the kernel, (e^{dLambda} - 1) int K |phi|,
  //   int K |phi| <= d max|phi| / (kappa + 1) with phi's nodes' largest doubled (between the nodes)
  const double third = driveNormThird(w0, w_dot, std::sqrt(wd2), d, wn[0], wn[4]);
  const double dLambda = third / 12.0 * d * d * std::log1p(-d / s_b) / (c * t2);
  const double kernel = std::expm1(dLambda) * 2.0 * phi_max * d * inv[0];
  // - t0's (the header), doubled for the first order's
  const double rim = 2.0 * std::abs(t0) / t1 * 2.0 * phi_max;
  out.T = Tb[kN - 1];
  out.error = quad + picard + kernel + rim;
  out.pushed = true;
  for (int i = 0; i < kN; ++i)
  {
    const double T2 = Tb[i] * Tb[i];
    out.pushed = out.pushed && wn[i] * (1.0 - T2) - (1.0 + T2) * b_dot[i] >= 0.0;
  }
  return std::isfinite(out.T) && std::isfinite(out.error);
}

}  // namespace sphere_contact_estimator::lattice
