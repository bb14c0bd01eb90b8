#include "series.h"

// STL
#include <algorithm>

namespace sphere_contact_estimator::path
{
cd phi1(double x)
{
  if (std::abs(x) < 1e-4)
    return { 1.0 - x * x / 6.0, 0.5 * x * (1.0 - x * x / 12.0) };
  double sh, ch;
  ::sincos(0.5 * x, &sh, &ch);
  return { 2.0 * sh * ch / x, 2.0 * sh * sh / x };
}

cd phi2(double x)
{
  const double x2 = x * x;
  if (std::abs(x) < 0.1)  // the series to x^8: below 1e-17 of the value
    return { 0.5 - x2 / 24.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0)),
             x / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))) };
  double sh, ch;
  ::sincos(0.5 * x, &sh, &ch);
  return { 2.0 * sh * sh / x2, (x - 2.0 * sh * ch) / x2 };
}

// Each series is an exact polynomial of low degree (position 1, drive 1, deflection 2, r^2 2, f^2 and |u|^2 4) plus a
// tail in powers of the turn that decays like x^n / n!; the products the events need (f^2, |u|^2, the margin of G)
// carry a factor's O(1) low-order terms times the other's tail, so they keep 4 degrees beyond the degree where the
// tail falls below 1e-17.
int seriesDegree(double x)
{
  if (x == 0.0)
    return 4;  // the straight, uncoupled path: every series is exactly a polynomial of degree <= 4
  double term = 1.0;
  int n = 1;
  for (; n <= kMaxDegree - 4; ++n)
  {
    term *= x / n;
    if (term < kSeriesTolerance)
      break;
  }
  return std::min(n + 4, kMaxDegree);
}

void multiply(const double* a, const double* b, int n, double* out)
{
  for (int k = 0; k <= n; ++k)
  {
    double s = 0.0;
    for (int i = 0; i <= k; ++i)
      s += a[i] * b[k - i];
    out[k] = s;
  }
}

void dotSeries(const cd* a, const cd* b, int n, double* out)
{
  for (int k = 0; k <= n; ++k)
  {
    double s = 0.0;
    for (int i = 0; i <= k; ++i)
      s += dot(a[i], b[k - i]);
    out[k] = s;
  }
}

double integrate(const double* c, int n, double lo, double hi)
{
  double s = 0.0, plo = lo, phi = hi;
  for (int k = 0; k <= n; ++k, plo *= lo, phi *= hi)
    s += c[k] * (phi - plo) / (k + 1);
  return s;
}

cd evaluate(const cd* c, int n, double s)
{
  cd v = c[n];
  for (int k = n - 1; k >= 0; --k)
    v = v * s + c[k];
  return v;
}

void Segment::build(const BristleField& f, const BristlePath& p, double a, double b, int degree, double centre)
{
  work = (degree + 2) * (degree + 2);  // the Cauchy products dominate
  t0 = a;
  t1 = b;
  tm = std::isnan(centre) ? 0.5 * (a + b) : centre;
  n = degree;
  // z' = -1 + i omega z (eqs. 15b, 35b): Z_1 = z'(tm), Z_{k+1} = i omega Z_k / (k + 1)
  Z[0] = p.position(tm);
  Z[1] = cd(-1.0, 0.0) + timesI(f.omega, Z[0]);
  for (int k = 1; k <= n; ++k)
    Z[k + 1] = timesI(f.omega, Z[k]) / static_cast<double>(k + 1);
  W[0] = f.drive(Z[0]);
  for (int k = 1; k <= n; ++k)
    W[k] = timesI(f.phi, Z[k]);
  double R2[kSize];
  dotSeries(Z, Z, n + 1, R2);  // r^2
  for (int k = 0; k <= n; ++k)
  {
    T[k] = -R2[k];
    D[k] = (k + 1) * R2[k + 1];
  }
  T[0] = p.edgeDistance(tm);  // 1 - r^2, whose constant term would cancel near the edges
  // f^2 = t^m
  const int m = f.pressure.squaredExponent();
  if (m == 0)
    for (int k = 0; k <= n; ++k)
      B2[k] = k == 0 ? 1.0 : 0.0;
  else if (m == 1)
    std::copy(T, T + n + 1, B2);
  else
    multiply(T, T, n, B2);
}

void adhesionSeries(const BristleField& f, const Segment& g, double tau_s, cd u_s, cd* U)
{
  // particular series (U_0 = 0), then the homogeneous part e^{i kappa s} U_0 fixes u(s_s) = u_s
  cd P[kSize];
  P[0] = 0.0;
  for (int k = 0; k < g.n; ++k)
    P[k + 1] = (timesI(f.kappa, P[k]) + g.W[k]) / static_cast<double>(k + 1);
  const double s_s = tau_s - g.tm;
  const cd rot = std::polar(1.0, -f.kappa * s_s);
  const cd U0 = rot * (u_s - evaluate(P, g.n, s_s));
  cd h = U0;  // (i kappa)^k U0 / k!
  for (int k = 0; k <= g.n; ++k)
  {
    U[k] = P[k] + h;
    h = timesI(f.kappa, h) / static_cast<double>(k + 1);
  }
}

}  // namespace sphere_contact_estimator::path
