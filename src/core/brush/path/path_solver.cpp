// solvePath: one bristle path from the leading edge to the trailing edge, as a sequence of adhesion and sliding
// pieces (eqs. 4a, 4b), each solved by its own room: adhesion.h, rigid_sliding.h with readhesion_region.h, or
// coulomb_sliding.h.

// STL
#include <algorithm>
#include <cmath>

// Package
#include "adhesion.h"
#include "coulomb_sliding.h"
#include "readhesion_region.h"
#include "rigid_sliding.h"

namespace sphere_contact_estimator
{
namespace
{
using path::AdhesionStart;
using path::cd;
using path::Interval;
using path::PathContext;
using path::PathEvent;

// Sect. 6's rigid law: a sliding bristle lies along the drive; it re-adheres only in G (fixed in the plane), from its
// capped deflection, and adheres there without reaching the bound.
void solveRigid(PathContext& ctx)
{
  Interval g[path::kMaxGIntervals];
  const int ng = path::findReAdhesionRegion(ctx, g);
  // Leading edge: undeformed (eq. 8). It adheres if the bound grows faster than the drive there (in G), and always
  // where the bound does not vanish at the rim or grows without limit there.
  bool adhering = !ctx.field.pressure.vanishesAtRim() || ctx.field.pressure.infiniteSlopeAtRim() ||
                  (ng > 0 && g[0].lo <= 0.0);
  ctx.signature.add(adhering ? PathEvent::EntersAdhering : PathEvent::EntersSliding);
  ctx.signature.add(PathEvent::ReAdhesionStretches, static_cast<unsigned>(ng));
  const double L = ctx.path.length;
  double tau = 0.0;
  cd u = 0.0;
  int guard = 0;
  while (tau < L && guard++ < 4 * path::kMaxGIntervals + 4)
  {
    if (adhering)
    {
      double end;
      u = path::adhere(ctx, tau, u, AdhesionStart::Free, g, ng, end);
      tau = end;
    }
    else
    {
      // slides until it enters G (re-adheres from the capped deflection) or leaves the patch
      double end = L;
      int which = -1;
      for (int i = 0; i < ng; ++i)
        if (g[i].lo > tau)
        {
          end = g[i].lo;
          which = i;
          break;
        }
      path::slideRigid(ctx, tau, end);
      // a slide to the trailing edge adds no structure: its onset said it all
      if (which >= 0)
        ctx.signature.add(PathEvent::ReAdhesion, static_cast<unsigned>(which));
      tau = end;
      if (tau < L)
        u = path::rigidSlidingDeflection(ctx.field, ctx.path, tau);
    }
    adhering = !adhering;
  }
}

// Eq. (4b) as written: a sliding bristle turns towards the drive no faster than its tip moves, and re-adheres where
// its sliding speed vanishes (coulomb_sliding.h); from there it adheres from the bound until it reaches it again.
void solveCoulomb(PathContext& ctx)
{
  const BristleField& f = ctx.field;
  const BristlePath& p = ctx.path;
  // Leading edge: undeformed (eq. 8), so the bristle adheres unless the bound vanishes there and grows slower than
  // the drive would deflect it: df/dtau = dt/dtau = 2 x_e against |w| (f = t).
  const bool adhering_at_entry =
      !f.pressure.vanishesAtRim() || f.pressure.infiniteSlopeAtRim() || 2.0 * p.entry.real() > std::abs(f.drive(p.entry));
  ctx.signature.add(adhering_at_entry ? PathEvent::EntersAdhering : PathEvent::EntersSliding);
  const double L = p.length;
  bool adhering = adhering_at_entry;
  double tau = 0.0;
  cd u = 0.0;
  path::SlideStart slide;
  slide.from_rim = !adhering;
  AdhesionStart start = AdhesionStart::Free;
  int readhesions = 0;
  for (int guard = 0; tau < L && guard < 64; ++guard)
  {
    if (adhering)
    {
      double end;
      const cd u_end = path::adhere(ctx, tau, u, start, nullptr, 0, end);
      const bool touch = start == AdhesionStart::OnBound && end == tau;  // turned out not to re-adhere
      tau = end;
      if (tau >= L)
        break;
      const double n = std::abs(u_end);
      slide = path::SlideStart{};
      slide.tau = tau;
      slide.direction = n > 0.0 ? u_end / n : (std::abs(u) > 0.0 ? u / std::abs(u) : cd(1.0, 0.0));
      slide.armed = !touch;
      u = u_end;
    }
    else
    {
      const path::SlideEnd end = path::slideCoulomb(ctx, slide);
      tau = end.tau;
      if (!end.re_adheres || tau >= L)
        break;
      ctx.signature.add(PathEvent::ReAdhesion, static_cast<unsigned>(++readhesions));
      u = f.bound(1.0 - p.edgeDistance(tau)) * end.direction;
      start = AdhesionStart::OnBound;
    }
    adhering = !adhering;
  }
  if (tau < L)
    ctx.out.truncated = true;  // more pieces than any path should have
}
}  // namespace

PathIntegrals solvePath(const BristleField& field, const BristlePath& path, double tolerance, bool keep_pieces,
                        long work_limit, CoulombStepper stepper)
{
  PathIntegrals out;  // returned in place
  if (!(path.length > 0.0))
    return out;
  PathContext ctx(field, path, tolerance, keep_pieces, work_limit, out, stepper);
  if (field.law == SlidingLaw::Rigid)
    solveRigid(ctx);
  else
    solveCoulomb(ctx);
  return out;
}

}  // namespace sphere_contact_estimator
