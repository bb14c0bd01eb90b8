#include "sphere_contact_estimator/core/brush/bristle_path.h"

// STL
#include <algorithm>
#include <cmath>
#include <limits>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/numerics/polynomial_roots.h"
#include "sphere_contact_estimator/core/numerics/quadrature_rules.h"

namespace sphere_contact_estimator
{
namespace
{
using cd = std::complex<double>;

constexpr int kMaxDegree = 30;          // of the Taylor series along a path
constexpr int kSize = kMaxDegree + 2;   // the position series carries one more term (for d(r^2)/dtau)
constexpr int kMaxSegments = 64;        // per path; beyond, the path is flagged truncated
constexpr double kSeriesTolerance = 1e-17;
constexpr int kMaxGIntervals = 8;
constexpr int kMaxAdhesionSteps = 4096;  // stretches of a radian of turn one adhesion piece may take
constexpr double kGaussRadius = 6.0;  // graded rules split where the pole's ellipse is closer than this
constexpr double kClosedFormRadius = 60.0;
constexpr double kFoldFloor = 1e-12;  // |u|^2 - f^2 (of order 1) within this of 0 is rounding's  // straight sliding pieces in closed form while the pole's is closer

cd timesI(double a, cd z) { return { -a * z.imag(), a * z.real() }; }  // i a z
// phi_2(i x) = (e^{ix} - 1 - ix) / (ix)^2 = ((1 - cos x) + i (x - sin x)) / x^2, without cancellation
cd phi2(double x)
{
  const double x2 = x * x;
  if (std::abs(x) < 0.1)  // the series to x^8: below 1e-17 of the value
    return { 0.5 - x2 / 24.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0)), x / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))) };
  double sh, ch;
  ::sincos(0.5 * x, &sh, &ch);
  return { 2.0 * sh * sh / x2, (x - 2.0 * sh * ch) / x2 };
}

double dot(cd a, cd b) { return a.real() * b.real() + a.imag() * b.imag(); }  // Re(a conj(b))
double cross(cd a, cd b) { return a.real() * b.imag() - a.imag() * b.real(); }  // Im(conj(a) b)

// phi_1(i x) = (e^{ix} - 1) / (ix), without cancellation (one sincos of x / 2)
cd phi1(double x)
{
  if (std::abs(x) < 1e-4)
    return { 1.0 - x * x / 6.0, 0.5 * x * (1.0 - x * x / 12.0) };
  double sh, ch;
  ::sincos(0.5 * x, &sh, &ch);
  return { 2.0 * sh * ch / x, 2.0 * sh * sh / x };
}

// Degree of the series along a path stretch on which the fastest turn is rate * length = x radians. Each
// series is an exact polynomial of low degree (position 1, drive 1, deflection 2, r^2 2, f^2 and |u|^2 4) plus a
// tail in powers of the turn that decays like x^n / n!; the products the events need (f^2, |u|^2, the margin
// of G) carry a factor's O(1) low-order terms times the other's tail, so they keep 4 degrees beyond the
// degree where the tail falls below 1e-17.
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

// Truncated Cauchy products of series a, b of degree n.
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

// Integral over [lo, hi] of a series in s.
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

// One stretch of a path with the Taylor series of everything the events need, about its midpoint.
struct Segment
{
  double t0 = 0.0, t1 = 0.0, tm = 0.0;
  int n = 4;
  cd Z[kSize], W[kSize];  // position z, drive w
  double B2[kSize];       // f^2: polynomial for all three pressures
  double H[kSize];        // re-adhesion margin: >= 0 (in the front half) where df/dtau >= |w|
  long work = 0;          // what building it took

  // Series about `centre` (the midpoint by default; an adhesion piece expands about its own start, where its
  // event polynomial is small and its low-order coefficients exact).
  void build(const BristleField& f, const BristlePath& p, double a, double b, int degree, double centre = NAN)
  {
    work = (degree + 2) * (degree + 2);  // the Cauchy products dominate
    t0 = a;
    t1 = b;
    tm = std::isnan(centre) ? 0.5 * (a + b) : centre;
    n = degree;
    // z' = -1 + i omega z: Z_1 = z'(tm), Z_{k+1} = i omega Z_k / (k + 1)
    Z[0] = p.position(tm);
    Z[1] = cd(-1.0, 0.0) + timesI(f.omega, Z[0]);
    for (int k = 1; k <= n; ++k)
      Z[k + 1] = timesI(f.omega, Z[k]) / static_cast<double>(k + 1);
    W[0] = f.drive(Z[0]);
    for (int k = 1; k <= n; ++k)
      W[k] = timesI(f.phi, Z[k]);
    double R2[kSize], Q[kSize], D[kSize], DD[kSize], WW[kSize];
    dotSeries(Z, Z, n + 1, R2);  // r^2
    for (int k = 0; k <= n; ++k)
    {
      Q[k] = -R2[k];              // 1 - r^2 ...
      D[k] = (k + 1) * R2[k + 1];  // d(r^2)/dtau = -2 x
    }
    Q[0] = p.edgeDistance(tm);  // ... whose constant term would cancel near the edges
    switch (f.pressure)
    {
      case PressureDistribution::Parabolic:  // f = 1 - r^2, df/dtau = -D: G where D^2 >= |w|^2 (front half)
        multiply(Q, Q, n, B2);
        multiply(D, D, n, DD);
        dotSeries(W, W, n, WW);
        for (int k = 0; k <= n; ++k)
          H[k] = DD[k] - WW[k];
        break;
      case PressureDistribution::Hertzian:  // f = sqrt(1 - r^2), df/dtau = -D / (2 f): G where D^2 >= 4 Q |w|^2
      {
        for (int k = 0; k <= n; ++k)
          B2[k] = Q[k];
        double QW[kSize];
        multiply(D, D, n, DD);
        dotSeries(W, W, n, WW);
        multiply(Q, WW, n, QW);
        for (int k = 0; k <= n; ++k)
          H[k] = DD[k] - 4.0 * QW[k];
        break;
      }
      case PressureDistribution::Uniform:  // df/dtau = 0: no re-adhesion
        for (int k = 0; k <= n; ++k)
        {
          B2[k] = k == 0 ? 1.0 : 0.0;
          H[k] = k == 0 ? -1.0 : 0.0;
        }
        break;
    }
  }
};

// The adhering bristle's series on a segment from its deflection u_s at travel tau_s:
// u' = w + i kappa u  ->  U_{k+1} = (i kappa U_k + W_k) / (k + 1), with U_0 from u(tau_s) = u_s.
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

struct Interval
{
  double lo, hi;
};

class PathSolver
{
public:
  PathSolver(const BristleField& f, const BristlePath& p, double tolerance, bool keep, long work_limit, PathIntegrals& out)
    : f_(f), p_(p), tolerance_(tolerance), keep_(keep), work_limit_(work_limit), out_(out)
  {
    // the series of up to kMaxSegments segments (about 100 kB): built once per thread, overwritten per path
    thread_local std::array<Segment, kMaxSegments> storage;
    seg_ = storage.data();
  }

  void run()
  {
    findG();
    // Leading edge: undeformed (eq. 8). It adheres if the bound grows faster than the drive there (in G), and
    // always with the Hertzian pressure (df/dtau is infinite at the edge) or the uniform one (f = 1 there).
    bool adhering = f_.pressure != PressureDistribution::Parabolic || (ng_ > 0 && g_[0].lo <= 0.0);
    signature(adhering ? 1 : 2);
    signature(static_cast<unsigned>(std::min(ng_, 7)));
    double tau = 0.0;
    cd u = 0.0;
    int guard = 0;
    while (tau < p_.length && guard++ < 4 * kMaxGIntervals + 4)
    {
      if (adhering)
      {
        double end;
        u = adhere(tau, u, end);
        tau = end;
      }
      else
      {
        // slides until it enters G (re-adheres from the capped deflection) or leaves the patch
        double end = p_.length;
        int which = 7;
        for (int i = 0; i < ng_; ++i)
          if (g_[i].lo > tau)
          {
            end = g_[i].lo;
            which = i;
            break;
          }
        slide(tau, end);
        // a slide to the trailing edge adds no structure: its onset said it all
        if (which < 7)
          signature(8u + static_cast<unsigned>(which));
        tau = end;
        if (tau < p_.length)
          u = capped(tau);
      }
      adhering = !adhering;
    }
  }

private:
  void signature(unsigned v) { out_.signature = out_.signature * 31u + v + 1u; }

  // The path's segments carry the geometry (position, drive, bound, the margin of G): they turn at |omega|
  // per unit travel, at most 1 in a steady state (Assumption 4.1), so a few segments hold any path. The
  // adhering deflection also turns at kappa; adhere() steps through its own stretches for that.
  void buildSegments()
  {
    const double rate = std::abs(f_.omega);
    rate_ = std::max(rate, std::abs(f_.kappa));
    const int count = std::clamp(static_cast<int>(std::ceil(rate * p_.length)), 1, kMaxSegments);
    const double h = p_.length / count;
    const int degree = seriesDegree(rate * h);  // about each segment's start
    out_.truncated = degree == kMaxDegree && rate * h > 2.0;
    ns_ = count;
    for (int i = 0; i < count; ++i)
    {
      seg_[i].build(f_, p_, i * h, i + 1 == count ? p_.length : (i + 1) * h, degree, i * h);
      out_.work += seg_[i].work;
    }
  }

  // G: where a sliding bristle re-adheres, H >= 0 in the front half (tau <= L/2, where df/dtau >= 0).
  // With the parabolic pressure G needs |w| <= |d(r^2)/dtau| = 2|x| <= 2, and |w| = |phi| |z - z_pole| (|sigma|
  // without spin): a path that stays further from the pole than 2 / |phi| crosses no G.
  bool clearOfG() const
  {
    if (f_.pressure != PressureDistribution::Parabolic)
      return f_.pressure == PressureDistribution::Uniform;
    if (f_.phi == 0.0)
      return std::norm(f_.sigma) > 4.0;
    const cd zp = f_.pole();
    double distance;
    if (f_.omega == 0.0)
      distance = std::abs(zp.imag() - p_.entry.imag());
    else
    {
      const cd centre(0.0, f_.tiltingCentre());
      distance = std::abs(std::sqrt(std::norm(zp - centre)) - std::sqrt(std::norm(p_.entry - centre)));
    }
    return std::abs(f_.phi) * distance > 2.0 * (1.0 + 1e-9);
  }

  void findG()
  {
    ng_ = 0;
    if (clearOfG())
      return;
    buildSegments();
    const double half = 0.5 * p_.length;
    bool inside = numerics::evaluatePolynomial(seg_[0].H, seg_[0].n, -seg_[0].tm) >= 0.0;
    double start = 0.0;
    for (int i = 0; i < ns_ && seg_[i].t0 < half; ++i)
    {
      const Segment& g = seg_[i];
      double roots[2 * kMaxDegree];
      const int k = numerics::signChanges(g.H, g.n, g.t0 - g.tm, std::min(g.t1, half) - g.tm, roots, 2 * kMaxDegree);
      for (int j = 0; j < k; ++j)
      {
        const double t = roots[j] + g.tm;
        if (inside)
          addG(start, t);
        else
          start = t;
        inside = !inside;
      }
    }
    if (inside)
      addG(start, half);
  }
  void addG(double lo, double hi)
  {
    if (ng_ > 0 && lo - g_[ng_ - 1].hi < 1e-13)  // segment seams: one interval
    {
      g_[ng_ - 1].hi = hi;
      return;
    }
    if (hi > lo && ng_ < kMaxGIntervals)
      g_[ng_++] = { lo, hi };
  }

  int segmentOf(double tau) const
  {
    int i = 0;
    while (i + 1 < ns_ && tau >= seg_[i].t1)
      ++i;
    return i;
  }

  // The capped deflection f w / |w| at travel tau (the sliding bristle's, and the re-adhering one's start).
  cd capped(double tau) const
  {
    const cd w = f_.drive(p_.position(tau));
    const double n = std::sqrt(std::norm(w));
    return n > 0.0 ? f_.bound(1.0 - p_.edgeDistance(tau)) * w / n : cd(0.0);
  }

  // Adheres from (tau_s, u_s) to the first point where |u| reaches f outside G (or the trailing edge);
  // returns the deflection there.
  cd adhere(double tau_s, cd u_s, double& end)
  {
    if (ns_ == 0)
      buildSegments();
    if (keep_ && out_.pieces < PathIntegrals::kMaxPieces)
      out_.piece[out_.pieces++] = { tau_s, p_.length, true, u_s };
    cd U[kSize];
    double PP[kSize], UU[kSize];
    int subrange = 0, steps = 0;
    const bool first_piece = !adhered_;
    adhered_ = true;
    Segment g;  // a stretch of the path from the piece's start on, expanded about its own start
    const double stride = rate_ > 0.0 ? 1.0 / rate_ : INFINITY;  // at most a radian of turn per stretch
    for (int i = segmentOf(tau_s); i < ns_; ++i)
      for (double lo = std::max(tau_s, seg_[i].t0); lo < seg_[i].t1;)
      {
        if (++steps > kMaxAdhesionSteps || out_.work > work_limit_)
        {
          out_.truncated = true;  // a deflection turning faster than the budget follows: not resolved
          end = p_.length;
          return u_s;
        }
        const double stretch_end = std::min(seg_[i].t1, lo + stride);
        g.build(f_, p_, lo, stretch_end, seriesDegree(rate_ * (stretch_end - lo)), lo);
        out_.work += g.work;
        adhesionSeries(f_, g, lo, u_s, U);
        dotSeries(U, U, g.n, UU);
        for (int k = 0; k <= g.n; ++k)
          PP[k] = UU[k] - g.B2[k];
        while (lo < g.t1)
        {
          // inside G |u| <= f holds (it held on entry, and |u| grows no faster than |w| <= df/dtau): no event
          int j = 0;
          while (j < ng_ && g_[j].hi <= lo)
            ++j;
          if (j < ng_ && g_[j].lo <= lo)
          {
            const double hi = std::min(g_[j].hi, g.t1);
            accumulateAdhesion(U, g, lo - g.tm, hi - g.tm);
            lo = hi;
            continue;
          }
          const double hi = j < ng_ ? std::min(g_[j].lo, g.t1) : g.t1;
          ++subrange;
          const double s_lo = lo - g.tm, s_hi = hi - g.tm;
          sampleUtilisation(U, g, s_lo, s_hi);
          double crossing = -1.0;
          int roots_after = 0;
          if (numerics::evaluatePolynomial(PP, g.n, s_lo) > 0.0)
            crossing = lo;
          else
          {
            double roots[2 * kMaxDegree];
            const int k = numerics::signChanges(PP, g.n, s_lo, s_hi, roots, 2 * kMaxDegree);
            if (k > 0)
            {
              crossing = roots[0] + g.tm;
              roots_after = k - 1;
            }
          }
          if (f_.pressure == PressureDistribution::Uniform && tau_s == 0.0)
            out_.onset_margin = peak(PP, g.n, s_lo, s_hi);
          if (first_piece)
            localMaxima(PP, g.n, s_lo, s_hi, crossing >= 0.0 ? crossing - g.tm : s_hi);
          if (crossing >= 0.0)
          {
            accumulateAdhesion(U, g, s_lo, crossing - g.tm);
            end = crossing;
            signature(16u + static_cast<unsigned>(std::min(subrange, 15)) * 8u +
                      static_cast<unsigned>(std::min(roots_after, 7)));
            if (first_piece)
              signature(200u + static_cast<unsigned>(std::min(maxima_before_onset_, 3)));
            if (keep_ && out_.pieces > 0)
              out_.piece[out_.pieces - 1].end = end;
            return evaluate(U, g.n, crossing - g.tm);
          }
          accumulateAdhesion(U, g, s_lo, s_hi);
          lo = hi;
        }
        u_s = evaluate(U, g.n, g.t1 - g.tm);
      }
    // No onset before the trailing edge. Where the bound vanishes there (parabolic, Hertzian) an onset exists up
    // to rounding (|u| - f > 0 at the edge unless u = 0): the same structure as an onset in the last stretch with
    // no root after it. With the uniform pressure the onset really leaves through the edge: a kink across paths.
    end = p_.length;
    signature(f_.pressure == PressureDistribution::Uniform ? 15u : 16u + static_cast<unsigned>(std::min(subrange, 15)) * 8u);
    if (first_piece)
      signature(200u + static_cast<unsigned>(std::min(maxima_before_onset_, 3)));
    return u_s;
  }

  void accumulateAdhesion(const cd* U, const Segment& g, double s_lo, double s_hi)
  {
    if (!(s_hi > s_lo))
      return;
    double re[kSize], im[kSize], M[kSize];
    for (int k = 0; k <= g.n; ++k)
    {
      re[k] = U[k].real();
      im[k] = U[k].imag();
      double m = 0.0;
      for (int i = 0; i <= k; ++i)
        m += cross(g.Z[i], U[k - i]);
      M[k] = m;
    }
    out_.force += cd(integrate(re, g.n, s_lo, s_hi), integrate(im, g.n, s_lo, s_hi));
    out_.moment += integrate(M, g.n, s_lo, s_hi);
  }

  // The largest value of a polynomial on [lo, hi]: at an end or where its derivative changes sign.
  static double peak(const double* c, int n, double lo, double hi)
  {
    double d[kSize], cuts[2 * kMaxDegree];
    for (int k = 1; k <= n; ++k)
      d[k - 1] = k * c[k];
    const int nc = numerics::signChanges(d, n - 1, lo, hi, cuts, 2 * kMaxDegree);
    double best = std::max(numerics::evaluatePolynomial(c, n, lo), numerics::evaluatePolynomial(c, n, hi));
    for (int k = 0; k < nc; ++k)
      best = std::max(best, numerics::evaluatePolynomial(c, n, cuts[k]));
    return best;
  }

  // The interior local maxima of |u|^2 - f^2 on (lo, hi) (its derivative changes sign from + to -): the value at the
  // first one becomes the fold (PathIntegrals::fold), and those before `onset` are counted. The count changes where
  // the onset jumps past a maximum (the fold reaches 0), which the signature then shows on a band of paths as wide as
  // the maximum's existence before the onset, not only on the narrow dip after it. Stationary points at the ends
  // (where the bound and the deflection both vanish) are rounding's, not folds.
  void localMaxima(const double* c, int n, double lo, double hi, double onset)
  {
    double d[kSize], cuts[2 * kMaxDegree];
    for (int k = 1; k <= n; ++k)
      d[k - 1] = k * c[k];
    const int nc = numerics::signChanges(d, n - 1, lo, hi, cuts, 2 * kMaxDegree);
    const double margin = 1e-9 * (hi - lo);
    for (int k = 0; k < nc; ++k)
    {
      if (cuts[k] - lo < margin || hi - cuts[k] < margin)
        continue;
      // the derivative just before the change: positive at a maximum
      const double before = k > 0 ? 0.5 * (cuts[k - 1] + cuts[k]) : 0.5 * (lo + cuts[k]);
      if (!(numerics::evaluatePolynomial(d, n - 1, before) > 0.0))
        continue;
      // a maximum within rounding of the bound (where both vanish, at the edges) tells nothing: its sign is noise
      const double value = numerics::evaluatePolynomial(c, n, cuts[k]);
      if (!(std::abs(value) > kFoldFloor))
        continue;
      if (std::isnan(out_.fold))
        out_.fold = value;
      maxima_before_onset_ += cuts[k] < onset;
    }
  }

  void sampleUtilisation(const cd* U, const Segment& g, double s_lo, double s_hi)
  {
    for (double s : { s_lo, 0.5 * (s_lo + s_hi), s_hi })
    {
      const double b2 = numerics::evaluatePolynomial(g.B2, g.n, s);
      if (b2 > 0.0)
        out_.utilisation2 = std::max(out_.utilisation2, std::min(1.0, std::norm(evaluate(U, g.n, s)) / b2));
    }
  }

  // The sliding stress f w / |w| and its moment at travel tau.
  void sliding(double tau, cd& q, double& m) const
  {
    const cd z = p_.position(tau);
    const cd w = f_.drive(z);
    const double n = std::sqrt(std::norm(w));
    // only the Hertzian bound, sqrt(1 - r^2), needs 1 - r^2 without cancellation at the edges
    const double r2 = f_.pressure == PressureDistribution::Hertzian ? 1.0 - p_.edgeDistance(tau) : std::norm(z);
    q = n > 0.0 ? f_.bound(r2) * w / n : cd(0.0);
    m = cross(z, q);
  }

  void slide(double a, double b)
  {
    if (keep_ && out_.pieces < PathIntegrals::kMaxPieces)
      out_.piece[out_.pieces++] = { a, b, false, cd(0.0) };
    if (!(b > a))
      return;
    out_.sliding += b - a;
    out_.utilisation2 = 1.0;
    // the integrand's nearest complex singularity: where w(z(tau)) = 0 (its modulus has a branch point)
    cd star(1e300, 1e300);
    if (f_.phi != 0.0)
    {
      const cd zp = f_.pole();
      if (f_.omega == 0.0)
        star = p_.entry - zp;  // z_e - tau = z_p
      else
      {
        const cd centre(0.0, f_.tiltingCentre());
        // centre + e^{i omega tau}(z_e - centre) = z_p: the complex log, without the hypot std::log takes
        const cd ratio = (zp - centre) / (p_.entry - centre);
        star = cd(std::atan2(ratio.imag(), ratio.real()), -0.5 * std::log(std::norm(ratio))) / f_.omega;
      }
    }
    if (f_.omega == 0.0 && f_.pressure != PressureDistribution::Hertzian)
    {
      // straight, f a polynomial in x: the closed form while the pole is near enough that its differences keep
      // their digits (they lose about rho^4 eps), a short Gauss rule beyond (a degree-4 polynomial times a
      // function analytic out to rho: degree 4 exactly plus rho^-2 per further node)
      const double rho = f_.phi != 0.0 ? bernsteinRadius(a, b, star) : INFINITY;
      if (rho < kClosedFormRadius && slideStraight(a, b, rho))
        return;
      if (rho >= kClosedFormRadius)
      {
        const double half = 0.5 * (b - a), C = 64.0 / 15.0 * 8.0 * half;
        const int m = std::clamp(2 + static_cast<int>(std::ceil(std::log(std::max(C / tolerance_, 1.0)) / (2.0 * std::log(rho)))), 3,
                                 numerics::GaussLegendre::kMaxPoints);
        gauss(a, b, m, [&](double tau, cd& q, double& mm) { sliding(tau, q, mm); });
        out_.error += C * std::pow(rho, -2.0 * (m - 2));
        return;
      }
    }
    if (f_.pressure != PressureDistribution::Hertzian)
    {
      graded(a, b, star, [&](double tau, cd& q, double& m) { sliding(tau, q, m); });
      return;
    }
    // f = sqrt(1 - r^2) has square-root branch points at both edges, f ~ sqrt(tau (L - tau)) (times an
    // analytic factor on a circle): tau = L (1 - cos v) / 2 makes it analytic in v
    const double L = p_.length, h = 0.5 * L;
    const auto angle = [&](double tau) { return std::acos(std::clamp(1.0 - tau / h, -1.0, 1.0)); };
    const cd v_star = std::acos(cd(1.0, 0.0) - star / h);
    graded(angle(a), angle(b), v_star, [&](double v, cd& q, double& m) {
      sliding(h * (1.0 - std::cos(v)), q, m);
      const double jac = h * std::sin(v);
      q *= jac;
      m *= jac;
    }, h);
  }

  // The parameter of the Bernstein ellipse of [lo, hi] through `star`: its semi-axis sum, from the semi-major
  // axis A = (|t - 1| + |t + 1|) / 2 of the confocal ellipse through t (star mapped onto [-1, 1]).
  static double bernsteinRadius(double lo, double hi, cd star)
  {
    const cd t = (2.0 * star - (lo + hi)) / (hi - lo);
    const double A = 0.5 * (std::sqrt(std::norm(t - 1.0)) + std::sqrt(std::norm(t + 1.0)));
    return A + std::sqrt(std::max(0.0, A * A - 1.0));
  }

  // Sliding on a straight path, parabolic or uniform pressure, in closed form: with t = w_y = sigma_y + phi x
  // along the path, f is a polynomial in t and the stress f (A, t) / sqrt(A^2 + t^2), A = w_x, integrates by
  // J_n = int t^n / sqrt(A^2 + t^2) dt = (t^(n-1) R - (n-1) A^2 J_(n-2)) / n. Used where the pole is near the
  // piece (its Gauss rule would be long); there the differences J_n(t_b) - J_n(t_a) lose little.
  bool slideStraight(double a, double b, double rho)
  {
    const double eta = p_.entry.imag(), phi = f_.phi;
    const double A = f_.sigma.real() - phi * eta;
    if (std::abs(A) < 1e-300)
      return false;
    const double t_a = f_.sigma.imag() + phi * (p_.entry.real() - a), t_b = f_.sigma.imag() + phi * (p_.entry.real() - b);
    const double alpha = 1.0 / phi, gamma = -f_.sigma.imag() / phi;  // x = alpha t + gamma
    double c0 = 1.0, c1 = 0.0, c2 = 0.0;                             // f = c0 + c1 t + c2 t^2
    if (f_.pressure == PressureDistribution::Parabolic)
    {
      c0 = 1.0 - eta * eta - gamma * gamma;
      c1 = -2.0 * alpha * gamma;
      c2 = -alpha * alpha;
    }
    double D[5];
    {
      const double A2 = A * A, absA = std::abs(A);
      double Ja[5], Jb[5];
      for (int side = 0; side < 2; ++side)
      {
        const double t = side == 0 ? t_a : t_b;
        double* J = side == 0 ? Ja : Jb;
        const double R = std::sqrt(A2 + t * t);
        J[0] = std::asinh(t / absA);
        J[1] = R;
        J[2] = (t * R - A2 * J[0]) / 2.0;
        J[3] = (t * t * R - 2.0 * A2 * J[1]) / 3.0;
        J[4] = (t * t * t * R - 3.0 * A2 * J[2]) / 4.0;
      }
      for (int n = 0; n < 5; ++n)
        D[n] = Jb[n] - Ja[n];
    }
    const double k = -alpha;  // d tau = -dx = -dt / phi
    const double fx = k * A * (c0 * D[0] + c1 * D[1] + c2 * D[2]);
    const double fy = k * (c0 * D[1] + c1 * D[2] + c2 * D[3]);
    // x q_y - y q_x = f (x t - eta A) / R with x t - eta A = -eta A + gamma t + alpha t^2
    const double e0 = -eta * A * c0, e1 = c0 * gamma - eta * A * c1, e2 = c0 * alpha + c1 * gamma - eta * A * c2,
                 e3 = c1 * alpha + c2 * gamma, e4 = c2 * alpha;
    const double m = k * (e0 * D[0] + e1 * D[1] + e2 * D[2] + e3 * D[3] + e4 * D[4]);
    if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(m)))
      return false;
    out_.force += cd(fx, fy);
    out_.moment += m;
    out_.error += 1e-15 * (1.0 + std::pow(rho, 4)) * (b - a);  // rounding: the differences lose about rho^4 eps
    return true;
  }

  // An m-point Gauss-Legendre rule on [a, b].
  template <class F>
  void gauss(double a, double b, int m, const F& g)
  {
    const numerics::GaussLegendre& rule = numerics::gaussLegendre(m);
    out_.work += 16 * m;  // a node: a sincos or a square root, a handful of products
    const double half = 0.5 * (b - a), mid = 0.5 * (b + a);
    cd sum = 0.0;
    double M_sum = 0.0;
    for (int i = 0; i < m; ++i)
    {
      cd q;
      double mm;
      g(mid + half * rule.x[i], q, mm);
      sum += rule.w[i] * q;
      M_sum += rule.w[i] * mm;
    }
    out_.force += half * sum;
    out_.moment += half * M_sum;
  }

  // Gauss-Legendre on [a, b] for an integrand analytic except near `star` (variable: travel, or the angle v
  // of the Hertzian map, whose Jacobian is at most `jacobian`): the rule on an interval is sized by the
  // classical bound for an integrand analytic in the Bernstein ellipse E_r, (64/15) M r^(-2m) / (r^2 - 1) times
  // the half-width, with r the geometric mean of 1 and the ellipse through the singularity, capped at 3 so
  // that the integrand's polynomial factors stay bounded on it (M from |z| <= 1 + r half-width). Intervals the
  // singularity is close to are split at its projection and graded geometrically.
  template <class F>
  void graded(double a, double b, cd star, const F& g, double jacobian = 1.0)
  {
    const double eps = tolerance_;
    const auto rho = [&](double lo, double hi) { return bernsteinRadius(lo, hi, star); };
    const auto apply = [&](double lo, double hi, double radius) {
      const double half = 0.5 * (hi - lo);
      const double r = std::clamp(std::sqrt(radius), 1.5, 3.0);
      const double R = 1.0 + r * half * jacobian, M = 2.0 * R * (1.0 + R * R) * jacobian;
      const double C = 64.0 / 15.0 * M * half / (r * r - 1.0);
      const double log_r = std::log(r);
      int m = static_cast<int>(std::ceil(std::log(std::max(C / eps, 1.0)) / (2.0 * log_r)));
      m = std::clamp(m, 2, numerics::GaussLegendre::kMaxPoints);
      gauss(lo, hi, m, g);
      out_.error += C * std::exp(-2.0 * m * log_r);
    };
    const double whole = rho(a, b);
    if (whole >= kGaussRadius)
    {
      apply(a, b, whole);
      return;
    }
    // split at the singularity's projection and grade outwards: widths delta, 2 delta, 4 delta, ...
    const double c = std::clamp(star.real(), a, b);
    const double delta = std::max(std::abs(star.imag()), 1e-12 * (b - a));
    for (int side = -1; side <= 1; side += 2)
    {
      const double end = side < 0 ? a : b;
      double from = c, width = delta;
      for (int k = 0; k < 60 && (end - from) * side > 0.0; ++k, width *= 2.0)
      {
        double to = from + side * width;
        if ((end - to) * side < 2.0 * width)  // the rest is short: take it in one
          to = end;
        const double lo = std::min(from, to), hi = std::max(from, to);
        apply(lo, hi, rho(lo, hi));
        from = to;
      }
    }
  }

  const BristleField& f_;
  const BristlePath& p_;
  double tolerance_;
  bool keep_;
  long work_limit_;
  PathIntegrals& out_;  // the caller's: returned in place (it holds the pieces, most of a kilobyte)
  Segment* seg_ = nullptr;
  int ns_ = 0;
  double rate_ = 0.0;  // the fastest turn along the path, max(|omega|, |kappa|)
  bool adhered_ = false;         // an adhesion piece was solved (folds are sought on the first)
  int maxima_before_onset_ = 0;  // on the first adhesion piece
  Interval g_[kMaxGIntervals];
  int ng_ = 0;
};

}  // namespace

double deflectionUnit(const BrushParameters& p)
{
  return p.mu * peakFactor(p.pressure) * p.F_z / (boost::math::double_constants::pi * p.a * p.a) / p.k;
}

bool makeBristleField(const BrushParameters& p, const std::complex<double>& sigma, double phi, double phi_gamma,
                      double phi_psi, BristleField& f)
{
  const double beta = deflectionUnit(p) / p.a;  // the largest bound, in units of a
  if (!(beta > 0.0 && std::isfinite(beta)))
    return false;
  f.sigma = sigma / beta;
  f.phi = phi * p.a / beta;
  f.pressure = p.pressure;
  f.kappa = p.tilt ? phi_psi * p.a : 0.0;
  f.omega = p.tilt ? -phi_gamma * p.a : 0.0;
  if (std::abs(f.omega) < 1e-12)  // |R_gamma| > 1e12 a: straight
    f.omega = 0.0;
  return true;
}

double BristleField::deflectionBound() const
{
  return std::min(1.0, boost::math::double_constants::pi * (std::abs(sigma) + std::abs(phi)));
}

double BristleField::bound(double r2) const
{
  const double t = 1.0 - r2;
  if (t <= 0.0)
    return 0.0;
  switch (pressure)
  {
    case PressureDistribution::Parabolic:
      return t;
    case PressureDistribution::Hertzian:
      return std::sqrt(t);
    case PressureDistribution::Uniform:
      return 1.0;
  }
  return 0.0;
}

BristlePath BristlePath::across(const BristleField& field, double theta)
{
  BristlePath p;
  p.theta = theta;
  p.omega = field.omega;
  const double y0 = std::sin(theta), c = std::cos(theta);
  if (field.omega == 0.0)
  {
    p.entry = cd(c, y0);
    p.length = 2.0 * c;
    p.weight = c;
  }
  else
  {
    // the circle about (0, -1/omega) through (0, y0): entry y_e = (1 - rho^2 + c^2) / (2c), written without 1/omega
    const double w = field.omega;
    const double y_e = std::clamp(y0 - 0.5 * w * (1.0 - y0 * y0), -1.0, 1.0);
    const double x_e = std::sqrt(std::max(0.0, 1.0 - y_e * y_e));
    p.entry = cd(x_e, y_e);
    // half the angle the arc subtends at the centre, from (0, y0) to the entry, both scaled by omega
    const double half = std::atan2(x_e * std::abs(w) * std::abs(1.0 + w * y0), (1.0 + w * y_e) * (1.0 + w * y0));
    p.length = 2.0 * half / std::abs(w);
    p.weight = c * std::abs(1.0 + w * y0);  // rho |omega| d(rho) / d(theta)
  }
  p.velocity = cd(-1.0, 0.0) + timesI(field.omega, p.entry);
  return p;
}

std::complex<double> BristlePath::position(double tau) const
{
  return entry + tau * phi1(omega * tau) * velocity;
}

double BristlePath::edgeDistance(double tau) const
{
  // r^2 = |c + e^{i omega tau} (z_e - c)|^2 with r(0) = 1 gives 1 - r^2 = 2 tau (x_e + tau Re(phi_2(i omega tau) v_0)),
  // v_0 the velocity at the entry (the 1/omega parts cancel exactly); the path is symmetric about x = 0, so the
  // nearer edge's form is used
  const double t = std::min(tau, length - tau);
  if (!(t > 0.0))
    return 0.0;
  return 2.0 * t * (entry.real() + t * (phi2(omega * t) * velocity).real());
}

double reAdhesionMargin(const BristleField& field, std::complex<double> z)
{
  const double ww = std::norm(field.drive(z)), D2 = 4.0 * z.real() * z.real();
  switch (field.pressure)
  {
    case PressureDistribution::Parabolic:
      return D2 - ww;
    case PressureDistribution::Hertzian:
      return D2 - 4.0 * std::max(0.0, 1.0 - std::norm(z)) * ww;
    case PressureDistribution::Uniform:
      return -1.0;
  }
  return -1.0;
}

namespace
{
// The re-adhesion margin along the front half of a path, as polynomials: visit(H, n, lo, hi) for each piece
// (one polynomial in x on a straight path, Taylor series per segment on a circle).
template <class Visit>
void reAdhesionPolynomials(const BristleField& field, const BristlePath& path, const Visit& visit)
{
  if (field.omega == 0.0)
  {
    // straight: H is a polynomial in x on [0, x_e] (y fixed), w = (A, B + phi x)
    const double y = path.entry.imag(), xe = path.entry.real();
    const double A = field.sigma.real() - field.phi * y, B = field.sigma.imag(), ph = field.phi;
    const double w0 = A * A + B * B, w1 = 2.0 * B * ph, w2 = ph * ph;  // |w|^2 = w0 + w1 x + w2 x^2
    double H[5];
    if (field.pressure == PressureDistribution::Parabolic)  // 4 x^2 - |w|^2
    {
      H[0] = -w0, H[1] = -w1, H[2] = 4.0 - w2;
      visit(H, 2, 0.0, xe);
    }
    else  // 4 x^2 - 4 (1 - y^2 - x^2) |w|^2
    {
      const double q = 1.0 - y * y;
      H[0] = -4.0 * q * w0;
      H[1] = -4.0 * q * w1;
      H[2] = 4.0 - 4.0 * (q * w2 - w0);
      H[3] = 4.0 * w1;
      H[4] = 4.0 * w2;
      visit(H, 4, 0.0, xe);
    }
    return;
  }
  const double half = 0.5 * path.length, rate = std::abs(field.omega);
  const int count = std::clamp(static_cast<int>(std::ceil(rate * half)), 1, kMaxSegments);
  const double h = half / count;
  const int degree = seriesDegree(rate * h);
  Segment g;
  for (int i = 0; i < count; ++i)
  {
    g.build(field, path, i * h, i + 1 == count ? half : (i + 1) * h, degree, i * h);
    visit(g.H, g.n, g.t0 - g.tm, g.t1 - g.tm);
  }
}
}  // namespace

double reAdhesionPeak(const BristleField& field, const BristlePath& path)
{
  if (field.pressure == PressureDistribution::Uniform || !(path.length > 0.0))
    return -1.0;
  double peak = -INFINITY;
  reAdhesionPolynomials(field, path, [&](const double* H, int n, double lo, double hi) {
    double dH[kSize], cuts[2 * kMaxDegree];
    for (int k = 1; k <= n; ++k)
      dH[k - 1] = k * H[k];
    const int nc = numerics::signChanges(dH, n - 1, lo, hi, cuts, 2 * kMaxDegree);
    peak = std::max({ peak, numerics::evaluatePolynomial(H, n, lo), numerics::evaluatePolynomial(H, n, hi) });
    for (int k = 0; k < nc; ++k)
      peak = std::max(peak, numerics::evaluatePolynomial(H, n, cuts[k]));
  });
  return peak;
}

int reAdhesionCount(const BristleField& field, const BristlePath& path)
{
  if (field.pressure == PressureDistribution::Uniform || !(path.length > 0.0))
    return 0;
  int count = 0;
  bool first = true, inside = false;
  reAdhesionPolynomials(field, path, [&](const double* H, int n, double lo, double hi) {
    if (first)
    {
      inside = numerics::evaluatePolynomial(H, n, lo) >= 0.0;
      count += inside;
      first = false;
    }
    double roots[2 * kMaxDegree];
    const int k = numerics::signChanges(H, n, lo, hi, roots, 2 * kMaxDegree);
    for (int j = 0; j < k; ++j)
    {
      inside = !inside;
      count += inside;
    }
  });
  return count;
}

double pathThrough(const BristleField& field, std::complex<double> z)
{
  if (field.omega == 0.0)
    return z.imag();
  // the circle about (0, c), c = -1/omega, through z crosses the y axis at c - sgn(c) |z - i c|:
  // with t = x / (c - y), y0 = y - x t / (1 + sqrt(1 + t^2))
  const double t = -z.real() * field.omega / (1.0 + field.omega * z.imag());
  return z.imag() - z.real() * t / (1.0 + std::sqrt(1.0 + t * t));
}

PathIntegrals solvePath(const BristleField& field, const BristlePath& path, double tolerance, bool keep_pieces,
                        long work_limit)
{
  PathIntegrals out;  // returned in place
  if (path.length > 0.0)
    PathSolver(field, path, tolerance, keep_pieces, work_limit, out).run();
  return out;
}

std::complex<double> deflectionAt(const BristleField& field, const BristlePath& path, const PathIntegrals& solved,
                                  double tau, bool* sliding)
{
  for (int i = 0; i < solved.pieces; ++i)
  {
    const PathPiece& piece = solved.piece[i];
    if (tau < piece.begin || tau > piece.end)
      continue;
    if (sliding)
      *sliding = !piece.adhering;
    const cd z = path.position(tau);
    if (!piece.adhering)
    {
      const cd w = field.drive(z);
      const double n = std::sqrt(std::norm(w));
      return n > 0.0 ? field.bound(std::norm(z)) * w / n : cd(0.0);
    }
    // adhesion from the piece's start: a fresh single segment over [begin, tau] (closed form, as solvePath)
    BristlePath sub = path;
    sub.entry = path.position(piece.begin);
    sub.velocity = cd(-1.0, 0.0) + timesI(field.omega, sub.entry);
    sub.length = tau - piece.begin;
    if (!(sub.length > 0.0))
      return piece.u_begin;
    Segment g;
    const double rate = std::max(std::abs(field.omega), std::abs(field.kappa));
    g.build(field, sub, 0.0, sub.length, seriesDegree(rate * sub.length), 0.0);
    cd U[kSize];
    adhesionSeries(field, g, 0.0, piece.u_begin, U);
    return evaluate(U, g.n, sub.length - g.tm);
  }
  if (sliding)
    *sliding = false;
  return 0.0;
}

}  // namespace sphere_contact_estimator
