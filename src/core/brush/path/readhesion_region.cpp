#include "readhesion_region.h"

// STL
#include <algorithm>
#include <cmath>

// Package
#include "sphere_contact_estimator/core/numerics/polynomial_roots.h"

namespace sphere_contact_estimator::path
{
void reAdhesionSeries(const BristleField& field, const Segment& g, double* H)
{
  const int m = field.pressure.squaredExponent();
  if (m == 0)  // df/dtau = 0: no re-adhesion
  {
    for (int k = 0; k <= g.n; ++k)
      H[k] = k == 0 ? -1.0 : 0.0;
    return;
  }
  // f = t^(m/2), df/dtau = -(m/2) t^(m/2 - 1) D: G where D^2 >= (4 / m^2) t^(2 - m) |w|^2 (front half)
  double DD[kSize], WW[kSize], TW[kSize];
  multiply(g.D, g.D, g.n, DD);
  dotSeries(g.W, g.W, g.n, WW);
  const double* scaled = WW;
  if (m == 1)
  {
    multiply(g.T, WW, g.n, TW);
    scaled = TW;
  }
  const double c = 4.0 / (m * m);
  for (int k = 0; k <= g.n; ++k)
    H[k] = DD[k] - c * scaled[k];
}

namespace
{
// With the parabolic pressure G needs |w| <= |d(r^2)/dtau| = 2|x| <= 2, and |w| = |phi| |z - z_pole| (|sigma|
// without spin): a path that stays further from the pole than 2 / |phi| crosses no G. The Hertzian's G holds a band
// along the whole leading edge; the uniform pressure has none.
bool clearOfG(const BristleField& f, const BristlePath& p)
{
  const int m = f.pressure.squaredExponent();
  if (m != 2)
    return m == 0;
  if (f.phi == 0.0)
    return std::norm(f.sigma) > 4.0;
  const cd zp = f.pole();
  double distance;
  if (f.omega == 0.0)
    distance = std::abs(zp.imag() - p.entry.imag());
  else
  {
    const cd centre(0.0, f.tiltingCentre());
    distance = std::abs(std::sqrt(std::norm(zp - centre)) - std::sqrt(std::norm(p.entry - centre)));
  }
  return std::abs(f.phi) * distance > 2.0 * (1.0 + 1e-9);
}

void addG(Interval* g, int& n, double lo, double hi)
{
  if (n > 0 && lo - g[n - 1].hi < 1e-13)  // segment seams: one interval
  {
    g[n - 1].hi = hi;
    return;
  }
  if (hi > lo && n < kMaxGIntervals)
    g[n++] = { lo, hi };
}
}  // namespace

int findReAdhesionRegion(PathContext& ctx, Interval* g)
{
  int n = 0;
  if (clearOfG(ctx.field, ctx.path))
    return 0;
  ctx.buildSegments();
  const double half = 0.5 * ctx.path.length;
  double H[kSize];
  reAdhesionSeries(ctx.field, ctx.segments[0], H);
  bool inside = numerics::evaluatePolynomial(H, ctx.segments[0].n, -ctx.segments[0].tm) >= 0.0;
  double start = 0.0;
  for (int i = 0; i < ctx.segment_count && ctx.segments[i].t0 < half; ++i)
  {
    const Segment& s = ctx.segments[i];
    if (i > 0)
      reAdhesionSeries(ctx.field, s, H);
    ctx.out.work += kRootWork(s.n);
    double roots[2 * kMaxDegree];
    const int k = numerics::signChanges(H, s.n, s.t0 - s.tm, std::min(s.t1, half) - s.tm, roots, 2 * kMaxDegree);
    for (int j = 0; j < k; ++j)
    {
      const double t = roots[j] + s.tm;
      if (inside)
        addG(g, n, start, t);
      else
        start = t;
      inside = !inside;
    }
  }
  if (inside)
    addG(g, n, start, half);
  return n;
}

}  // namespace sphere_contact_estimator::path

namespace sphere_contact_estimator
{
using path::cd;

double reAdhesionMargin(const BristleField& field, std::complex<double> z)
{
  const int m = field.pressure.squaredExponent();
  if (m == 0)
    return -1.0;
  const double ww = std::norm(field.drive(z)), D2 = 4.0 * z.real() * z.real();
  const double t = std::max(0.0, 1.0 - std::norm(z));
  return D2 - 4.0 / (m * m) * (m == 1 ? t : 1.0) * ww;
}

namespace
{
// How reAdhesionPolynomials takes a path's front half: on a straight path one polynomial of `degree` (2 for the
// parabolic bound, 4 for the Hertzian), on a circle `count` segments of length h, each a Taylor series of `degree`
struct FrontHalf
{
  int count, degree;
  double half, h;
};
FrontHalf frontHalf(const BristleField& field, const BristlePath& path)
{
  const double half = 0.5 * path.length;
  if (field.omega == 0.0)
    return { 1, field.pressure.squaredExponent() == 2 ? 2 : 4, half, half };
  const double rate = std::abs(field.omega);
  const int count = std::clamp(static_cast<int>(std::ceil(rate * half)), 1, path::kMaxSegments);
  const double h = half / count;
  return { count, path::seriesDegree(rate * h), half, h };
}

// The re-adhesion margin along the front half of a path, as polynomials: visit(H, n, lo, hi) for each piece (one
// polynomial in x on a straight path, Taylor series per segment on a circle).
template <class Visit>
void reAdhesionPolynomials(const BristleField& field, const BristlePath& path, const Visit& visit)
{
  const FrontHalf front = frontHalf(field, path);
  if (field.omega == 0.0)
  {
    // straight: H is a polynomial in x on [0, x_e] (y fixed), w = (A, B + phi x)
    const double y = path.entry.imag(), xe = path.entry.real();
    const double A = field.sigma.real() - field.phi * y, B = field.sigma.imag(), ph = field.phi;
    const double w0 = A * A + B * B, w1 = 2.0 * B * ph, w2 = ph * ph;  // |w|^2 = w0 + w1 x + w2 x^2
    double H[5];
    if (field.pressure.squaredExponent() == 2)  // 4 x^2 - |w|^2
    {
      H[0] = -w0, H[1] = -w1, H[2] = 4.0 - w2;
      visit(H, front.degree, 0.0, xe);
    }
    else  // 4 x^2 - 4 (1 - y^2 - x^2) |w|^2
    {
      const double q = 1.0 - y * y;
      H[0] = -4.0 * q * w0;
      H[1] = -4.0 * q * w1;
      H[2] = 4.0 - 4.0 * (q * w2 - w0);
      H[3] = 4.0 * w1;
      H[4] = 4.0 * w2;
      visit(H, front.degree, 0.0, xe);
    }
    return;
  }
  const double h = front.h;
  path::Segment g;
  double H[path::kSize];
  for (int i = 0; i < front.count; ++i)
  {
    g.build(field, path, i * h, i + 1 == front.count ? front.half : (i + 1) * h, front.degree, i * h);
    path::reAdhesionSeries(field, g, H);
    visit(H, g.n, g.t0 - g.tm, g.t1 - g.tm);
  }
}
}  // namespace

long reAdhesionWork(const BristleField& field, const BristlePath& path)
{
  if (!field.pressure.vanishesAtRim() || !(path.length > 0.0))
    return 0;
  const FrontHalf front = frontHalf(field, path);
  return front.count * kRootWork(front.degree);
}

double reAdhesionPeak(const BristleField& field, const BristlePath& path, long* work)
{
  if (!field.pressure.vanishesAtRim() || !(path.length > 0.0))
    return -1.0;
  double peak = -INFINITY;
  reAdhesionPolynomials(field, path, [&](const double* H, int n, double lo, double hi) {
    if (work)
      *work += kRootWork(n);
    double dH[path::kSize], cuts[2 * path::kMaxDegree];
    for (int k = 1; k <= n; ++k)
      dH[k - 1] = k * H[k];
    const int nc = numerics::signChanges(dH, n - 1, lo, hi, cuts, 2 * path::kMaxDegree);
    peak = std::max({ peak, numerics::evaluatePolynomial(H, n, lo), numerics::evaluatePolynomial(H, n, hi) });
    for (int k = 0; k < nc; ++k)
      peak = std::max(peak, numerics::evaluatePolynomial(H, n, cuts[k]));
  });
  return peak;
}

int reAdhesionCount(const BristleField& field, const BristlePath& path, long* work)
{
  if (!field.pressure.vanishesAtRim() || !(path.length > 0.0))
    return 0;
  int count = 0;
  bool first = true, inside = false;
  reAdhesionPolynomials(field, path, [&](const double* H, int n, double lo, double hi) {
    if (work)
      *work += kRootWork(n);
    if (first)
    {
      inside = numerics::evaluatePolynomial(H, n, lo) >= 0.0;
      count += inside;
      first = false;
    }
    double roots[2 * path::kMaxDegree];
    const int k = numerics::signChanges(H, n, lo, hi, roots, 2 * path::kMaxDegree);
    for (int j = 0; j < k; ++j)
    {
      inside = !inside;
      count += inside;
    }
  });
  return count;
}

}  // namespace sphere_contact_estimator
