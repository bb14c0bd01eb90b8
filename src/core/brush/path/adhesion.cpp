#include "adhesion.h"

// STL
#include <algorithm>
#include <cmath>

// Package
#include "sphere_contact_estimator/core/numerics/polynomial_roots.h"

namespace sphere_contact_estimator::path
{
namespace
{
constexpr int kMaxAdhesionSteps = 4096;  // stretches of a radian of turn one adhesion piece may take
constexpr double kFoldFloor = 1e-12;     // |u|^2 - f^2 (of order 1) within this of 0 is rounding's

void accumulate(PathContext& ctx, const cd* U, const Segment& g, double s_lo, double s_hi)
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
  ctx.out.force += cd(integrate(re, g.n, s_lo, s_hi), integrate(im, g.n, s_lo, s_hi));
  ctx.out.moment += integrate(M, g.n, s_lo, s_hi);
}

// The largest value of a polynomial on [lo, hi]: at an end or where its derivative changes sign.
double peak(const double* c, int n, double lo, double hi)
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
void localMaxima(PathContext& ctx, const double* c, int n, double lo, double hi, double onset)
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
    if (std::isnan(ctx.out.fold))
      ctx.out.fold = value;
    ctx.maxima_before_onset += cuts[k] < onset;
  }
}

void sampleUtilisation(PathContext& ctx, const cd* U, const Segment& g, double s_lo, double s_hi)
{
  for (double s : { s_lo, 0.5 * (s_lo + s_hi), s_hi })
  {
    const double b2 = numerics::evaluatePolynomial(g.B2, g.n, s);
    if (b2 > 0.0)
      ctx.out.utilisation2 = std::max(ctx.out.utilisation2, std::min(1.0, std::norm(evaluate(U, g.n, s)) / b2));
  }
}
}  // namespace

cd adhere(PathContext& ctx, double tau_s, cd u_s, AdhesionStart start, const Interval* quiet, int quiet_count,
          double& end)
{
  const BristlePath& path = ctx.path;
  if (ctx.segment_count == 0)
    ctx.buildSegments();
  const int piece = ctx.addPiece(tau_s, path.length, true, u_s);
  const bool uniform = !ctx.field.pressure.vanishesAtRim();
  cd U[kSize];
  double PP[kSize], UU[kSize];
  int subrange = 0, steps = 0;
  const bool first_piece = !ctx.adhered;
  ctx.adhered = true;
  bool deflate = start == AdhesionStart::OnBound;
  Segment g;  // a stretch of the path from the piece's start on, expanded about its own start
  const double stride = ctx.rate > 0.0 ? 1.0 / ctx.rate : INFINITY;  // at most a radian of turn per stretch
  for (int i = ctx.segmentOf(tau_s); i < ctx.segment_count; ++i)
    for (double lo = std::max(tau_s, ctx.segments[i].t0); lo < ctx.segments[i].t1;)
    {
      if (++steps > kMaxAdhesionSteps || ctx.overBudget())
      {
        ctx.out.truncated = true;  // a deflection turning faster than the budget follows: not resolved
        end = path.length;
        return u_s;
      }
      const double stretch_end = std::min(ctx.segments[i].t1, lo + stride);
      g.build(ctx.field, path, lo, stretch_end, seriesDegree(ctx.rate * (stretch_end - lo)), lo);
      ctx.out.work += g.work;
      adhesionSeries(ctx.field, g, lo, u_s, U);
      dotSeries(U, U, g.n, UU);
      for (int k = 0; k <= g.n; ++k)
        PP[k] = UU[k] - g.B2[k];
      // On the bound at a re-adhesion, |u|^2 - f^2 = 0 with zero slope (eq. 4b's sliding speed vanishes there):
      // the roots searched are those of (|u|^2 - f^2) / s^2, s from the start. Without an inward turn (a touch),
      // the bristle keeps sliding.
      double Q[kSize];
      if (deflate)
      {
        if (!(PP[2] < 0.0))
        {
          end = tau_s;
          if (piece >= 0)
            ctx.out.piece[piece].end = tau_s;
          return u_s;
        }
        for (int k = 0; k + 2 <= g.n; ++k)
          Q[k] = PP[k + 2];
      }
      while (lo < g.t1)
      {
        // inside G |u| <= f holds (it held on entry, and |u| grows no faster than |w| <= df/dtau): no event
        int j = 0;
        while (j < quiet_count && quiet[j].hi <= lo)
          ++j;
        if (j < quiet_count && quiet[j].lo <= lo)
        {
          const double hi = std::min(quiet[j].hi, g.t1);
          accumulate(ctx, U, g, lo - g.tm, hi - g.tm);
          lo = hi;
          continue;
        }
        const double hi = j < quiet_count ? std::min(quiet[j].lo, g.t1) : g.t1;
        ++subrange;
        const double s_lo = lo - g.tm, s_hi = hi - g.tm;
        sampleUtilisation(ctx, U, g, s_lo, s_hi);
        double crossing = -1.0;
        int roots_after = 0;
        const double* event = deflate ? Q : PP;
        const int degree = deflate ? g.n - 2 : g.n;
        if (!deflate && numerics::evaluatePolynomial(PP, g.n, s_lo) > 0.0)
          crossing = lo;
        else
        {
          double roots[2 * kMaxDegree];
          const int k = numerics::signChanges(event, degree, s_lo, s_hi, roots, 2 * kMaxDegree);
          if (k > 0)
          {
            crossing = roots[0] + g.tm;
            roots_after = k - 1;
          }
        }
        if (uniform && tau_s == 0.0)
          ctx.out.onset_margin = peak(PP, g.n, s_lo, s_hi);
        if (first_piece)
          localMaxima(ctx, PP, g.n, s_lo, s_hi, crossing >= 0.0 ? crossing - g.tm : s_hi);
        if (crossing >= 0.0)
        {
          accumulate(ctx, U, g, s_lo, crossing - g.tm);
          end = crossing;
          ctx.signature.add(PathEvent::Onset, static_cast<unsigned>(subrange), static_cast<unsigned>(roots_after));
          if (first_piece)
            ctx.signature.add(PathEvent::FoldsBeforeOnset, static_cast<unsigned>(ctx.maxima_before_onset));
          if (piece >= 0)
            ctx.out.piece[piece].end = end;
          return evaluate(U, g.n, crossing - g.tm);
        }
        accumulate(ctx, U, g, s_lo, s_hi);
        lo = hi;
      }
      deflate = false;  // the next stretch starts inside the bound
      u_s = evaluate(U, g.n, g.t1 - g.tm);
    }
  // No onset before the trailing edge. Where the bound vanishes there (parabolic, Hertzian) an onset exists up to
  // rounding (|u| - f > 0 at the edge unless u = 0): the same structure as an onset in the last stretch with no root
  // after it. With the uniform pressure the onset really leaves through the edge: a kink across paths.
  end = path.length;
  if (uniform)
    ctx.signature.add(PathEvent::LeavesAdhering);
  else
    ctx.signature.add(PathEvent::Onset, static_cast<unsigned>(subrange), 0);
  if (first_piece)
    ctx.signature.add(PathEvent::FoldsBeforeOnset, static_cast<unsigned>(ctx.maxima_before_onset));
  return u_s;
}

}  // namespace sphere_contact_estimator::path
