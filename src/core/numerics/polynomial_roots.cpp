#include "sphere_contact_estimator/core/numerics/polynomial_roots.h"

// STL
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace sphere_contact_estimator::numerics
{
namespace
{
constexpr int kSize = kMaxPolynomialDegree + 1;
constexpr int kMaxDepth = 52;  // halvings: below that the interval is at the resolution of a double

// p and p' at t by Horner's rule; N >= 0: the degree, known at compile time (the loop unrolled), else n.
template <int N>
inline void horner(const double* c, int n, double t, double& f, double& df)
{
  const int m = N >= 0 ? N : n;
  f = c[m];
  df = 0.0;
  for (int j = m - 1; j >= 0; --j)
  {
    df = df * t + f;
    f = f * t + c[j];
  }
}

// The root of p in (a, b), where p(a) = fa and p(b) = fb have opposite signs: Newton's method from `start` (regula
// falsi where it is not inside) kept inside the shrinking bracket (bisection where a step would leave it). Quadratic at
// a simple root, and it never fails.
template <int N>
double newtonInBracket(const double* c, int n, double a, double b, double fa, double fb, double start)
{
  double t = start;
  if (!(t > a && t < b))
    t = a - fa * (b - a) / (fb - fa);
  if (!(t > a && t < b))
    t = 0.5 * (a + b);
  const bool fa_positive = fa > 0.0;
  for (int it = 0; it < 100; ++it)
  {
    double f, df;
    horner<N>(c, n, t, f, df);
    if (f == 0.0)
      return t;
    if ((f > 0.0) == fa_positive)
      a = t;
    else
      b = t;
    const double tol =
        4.0 * std::numeric_limits<double>::epsilon() * std::max(std::max(std::abs(a), std::abs(b)), 1e-300);
    if (b - a <= tol)
      return t;
    double next = 0.5 * (a + b);
    if (df != 0.0)
    {
      const double step = f / df;
      if (std::abs(step) <= tol)
        return t - step;
      if (t - step > a && t - step < b)
        next = t - step;
    }
    t = next;
  }
  return t;
}

double bracketedNewton(const double* c, int n, double a, double b, double fa, double fb, double start = NAN)
{
  switch (n)
  {
    case 3:
      return newtonInBracket<3>(c, n, a, b, fa, fb, start);
    case 4:
      return newtonInBracket<4>(c, n, a, b, fa, fb, start);
    default:
      return newtonInBracket<-1>(c, n, a, b, fa, fb, start);
  }
}

// The number of sign changes in b[0..n], zeros skipped.
int variations(const double* b, int n)
{
  int v = 0, last = 0;
  for (int k = 0; k <= n; ++k)
  {
    const int s = (b[k] > 0.0) - (b[k] < 0.0);
    if (s == 0)
      continue;
    if (last != 0 && s != last)
      ++v;
    last = s;
  }
  return v;
}

// The Bernstein coefficients on [lo, hi] of p(s) = sum c[i] s^i: q(t) = p(lo + d t) by a Taylor shift to lo
// (synthetic division) and a scaling by d = hi - lo, then b_k = sum_{j <= k} C(k, j) / C(n, j) q_j: q_j / C(n, j)
// (the reciprocals built up along j), and the binomial transform sum_j C(k, j) x_j as n passes of neighbour sums
// (Pascal's triangle), with no division in the O(n^2) part.
void bernstein(const double* c, int n, double lo, double hi, double* b)
{
  const double d = hi - lo;
  double a[kSize];
  std::copy(c, c + n + 1, a);
  if (lo != 0.0)
    for (int i = 0; i < n; ++i)
      for (int j = n - 1; j >= i; --j)
        a[j] += lo * a[j + 1];
  // 1 / C(n, j) for the degrees of the event searches, else built up along j
  static constexpr double kInverse[5][5] = {
    { 1.0 }, { 1.0, 1.0 }, { 1.0, 0.5, 1.0 }, { 1.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 }, { 1.0, 0.25, 1.0 / 6.0, 0.25, 1.0 }
  };
  double scale = 1.0, inverse = 1.0;  // d^j, 1 / C(n, j)
  for (int j = 0; j <= n; ++j, scale *= d)
  {
    b[j] = a[j] * scale * (n <= 4 ? kInverse[n][j] : inverse);
    if (n > 4 && j < n)
      inverse *= static_cast<double>(j + 1) / static_cast<double>(n - j);
  }
  for (int r = 0; r < n; ++r)
    for (int k = n; k > r; --k)
      b[k] += b[k - 1];
}

struct Isolation
{
  const double* c;  // monomial coefficients in s
  int n;
  double lo, d;     // s = lo + d t
  double* roots;
  int max_roots;
  int found = 0;

  double p(double t) const { return evaluatePolynomial(c, n, lo + d * t); }

  void record(double t)
  {
    if (found < max_roots)
      roots[found++] = lo + d * t;
  }

  // One root of q in (t0, t1), where q(t0) and q(t1) have opposite signs (or one is zero).
  double solve(double t0, double t1) const
  {
    const double f0 = p(t0), f1 = p(t1);
    if (f0 == 0.0)
      return t0;
    if (f1 == 0.0)
      return t1;
    // The Bernstein coefficients saw a sign change that direct evaluation does not: one end is within rounding of
    // zero (a near-touch there). That end is the root; the interval's midpoint, which may lie far from both, is not.
    if ((f0 > 0.0) == (f1 > 0.0))
      return std::abs(f0) <= std::abs(f1) ? t0 : t1;
    return (bracketedNewton(c, n, lo + d * t0, lo + d * t1, f0, f1) - lo) / d;
  }

  void isolate(const double* b, double t0, double t1, int depth)
  {
    if (found >= max_roots)
      return;
    const int v = variations(b, n);
    if (v == 0)
      return;
    const bool ends_differ = (b[0] > 0.0) != (b[n] > 0.0) && b[0] != 0.0 && b[n] != 0.0;
    if (v == 1 && ends_differ)
    {
      record(solve(t0, t1));
      return;
    }
    if (depth >= kMaxDepth)
    {
      if (ends_differ)
        record(0.5 * (t0 + t1));
      return;
    }
    // de Casteljau at t = 1/2: the left half's coefficients are the triangle's left edge, the right half's its
    // right edge
    double left[kSize], right[kSize], work[kSize];
    std::copy(b, b + n + 1, work);
    left[0] = work[0];
    right[n] = work[n];
    for (int r = 1; r <= n; ++r)
    {
      for (int k = 0; k <= n - r; ++k)
        work[k] = 0.5 * (work[k] + work[k + 1]);
      left[r] = work[0];
      right[n - r] = work[n - r];
    }
    const double tm = 0.5 * (t0 + t1);
    isolate(left, t0, tm, depth + 1);
    isolate(right, tm, t1, depth + 1);
  }
};
// Degree <= 4: the critical points split [lo, hi] into monotone pieces, each holding at most one root; the
// critical points are the derivative's roots, found the same way down to a quadratic's closed form.
constexpr int kLowDegree = 4;

// Real roots of a t^2 + b t + c in (lo, hi), ascending, without cancellation.
int quadraticRoots(double a, double b, double c, double lo, double hi, double* out)
{
  int k = 0;
  const auto keep = [&](double t) {
    if (t > lo && t < hi)
      out[k++] = t;
  };
  if (a == 0.0)
  {
    if (b != 0.0)
      keep(-c / b);
    return k;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc <= 0.0)  // no root, or a double one: no sign change
    return 0;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double r1 = q / a, r2 = q != 0.0 ? c / q : r1;
  if (r1 > r2)
    std::swap(r1, r2);
  keep(r1);
  if (r2 != r1)
    keep(r2);
  return k;
}

// All points in (lo, hi) where p of degree n <= 4 changes sign, or (all = true) every real root found by the
// monotone-piece scan (which for the derivative gives the critical points).
int monotoneRoots(const double* c, int n, double lo, double hi, double* out, int max_out)
{
  if (n <= 2)
  {
    // the closed form finds up to two roots: into a buffer of its own, out may hold fewer
    double q[2];
    const int nq = std::min(max_out, quadraticRoots(n == 2 ? c[2] : 0.0, n >= 1 ? c[1] : 0.0, c[0], lo, hi, q));
    std::copy(q, q + nq, out);
    return nq;
  }
  double d[kLowDegree];
  for (int i = 1; i <= n; ++i)
    d[i - 1] = i * c[i];
  double cuts[kLowDegree + 1];
  const int nc = monotoneRoots(d, n - 1, lo, hi, cuts, kLowDegree);
  int k = 0;
  double a = lo, fa = evaluatePolynomial(c, n, lo);
  for (int i = 0; i <= nc && k < max_out; ++i)
  {
    const double b = i < nc ? cuts[i] : hi, fb = evaluatePolynomial(c, n, b);
    if (fa != 0.0 && fb != 0.0 && (fa > 0.0) != (fb > 0.0))
    {
      const double t = bracketedNewton(c, n, a, b, fa, fb);  // p is monotone on [a, b]
      out[k++] = t;
    }
    else if (fb == 0.0 && b < hi && i < nc)  // a root exactly at a critical point: a sign change only if p crosses
    {
      const double next = i + 1 < nc ? cuts[i + 1] : hi;
      const double fn = evaluatePolynomial(c, n, next);
      if (fa != 0.0 && fn != 0.0 && (fa > 0.0) != (fn > 0.0))
        out[k++] = b;
    }
    a = b;
    fa = fb;
  }
  return k;
}

int lowDegreeSignChanges(const double* c, int n, double lo, double hi, double* roots, int max_roots)
{
  return monotoneRoots(c, n, lo, hi, roots, max_roots);
}
}  // namespace

double evaluatePolynomial(const double* c, int n, double s)
{
  double v = c[n];
  for (int i = n - 1; i >= 0; --i)
    v = v * s + c[i];
  return v;
}

int signChanges(const double* c, int n, double lo, double hi, double* roots, int max_roots)
{
  if (n < 0 || n > kMaxPolynomialDegree)
    throw std::invalid_argument("signChanges: degree out of range");
  if (!(hi > lo) || max_roots <= 0)
    return 0;
  while (n > 0 && c[n] == 0.0)
    --n;
  // a root at s = 0 outside the open interval (an event search from a start on the bound): p = s q with s of one sign
  // there, so q changes sign where p does
  while (n > 0 && c[0] == 0.0 && !(lo < 0.0 && hi > 0.0))
    ++c, --n;
  if (n == 0)
    return 0;
  if (n <= 2)
    return lowDegreeSignChanges(c, n, lo, hi, roots, max_roots);  // the closed form
  double b[kSize];
  bernstein(c, n, lo, hi, b);
  if (n <= kLowDegree)
  {
    // Descartes' rule on the Bernstein coefficients: no sign change among them, no root; exactly one, with the ends
    // of opposite signs, exactly one simple root, found in [lo, hi] at once (the common case of an event search).
    // Where an inner coefficient is within rounding of zero its sign, and so the count, is not to be trusted: the
    // monotone pieces.
    double largest = 0.0;
    for (int k = 0; k <= n; ++k)
      largest = std::max(largest, std::abs(b[k]));
    bool clear = true;
    for (int k = 1; k < n; ++k)
      clear = clear && std::abs(b[k]) > 1e-10 * largest;
    // (the end coefficients are the values at the ends: where direct evaluation gives another sign, rounding decides)
    const double f_lo = evaluatePolynomial(c, n, lo), f_hi = evaluatePolynomial(c, n, hi);
    const auto sign = [](double x) { return (x > 0.0) - (x < 0.0); };
    if (clear && f_lo != 0.0 && f_hi != 0.0 && sign(f_lo) == sign(b[0]) && sign(f_hi) == sign(b[n]))
    {
      const int v = variations(b, n);
      if (v == 0)
        return 0;
      if (v == 1)
      {
        // from where the control polygon crosses zero (the curve's subdivision limit: closer than the chord)
        int k = 0;
        while ((b[k] > 0.0) == (b[k + 1] > 0.0))
          ++k;
        const double t = (k + b[k] / (b[k] - b[k + 1])) / n;
        roots[0] = bracketedNewton(c, n, lo, hi, f_lo, f_hi, lo + (hi - lo) * t);
        return 1;
      }
    }
    return lowDegreeSignChanges(c, n, lo, hi, roots, max_roots);
  }
  Isolation iso{ c, n, lo, hi - lo, roots, max_roots };
  iso.isolate(b, 0.0, 1.0, 0);
  return iso.found;
}

}  // namespace sphere_contact_estimator::numerics
