#include "path_context.h"

// STL
#include <algorithm>
#include <array>

namespace sphere_contact_estimator::path
{
PathContext::PathContext(const BristleField& f, const BristlePath& p, double tol, bool k, long limit, PathIntegrals& o,
                         CoulombStepper s)
  : field(f), path(p), tolerance(tol), keep(k), work_limit(limit), stepper(s), out(o), signature(o.signature)
{
  // the series of up to kMaxSegments segments (about 100 kB): built once per thread, overwritten per path
  thread_local std::array<Segment, kMaxSegments> storage;
  segments = storage.data();
}

void PathContext::buildSegments()
{
  const double turn = std::abs(field.omega);
  rate = std::max(turn, std::abs(field.kappa));
  const int count = std::clamp(static_cast<int>(std::ceil(turn * path.length)), 1, kMaxSegments);
  const double h = path.length / count;
  const int degree = seriesDegree(turn * h);  // about each segment's start
  out.truncated = degree == kMaxDegree && turn * h > 2.0;
  segment_count = count;
  for (int i = 0; i < count; ++i)
  {
    segments[i].build(field, path, i * h, i + 1 == count ? path.length : (i + 1) * h, degree, i * h);
    out.work += segments[i].work;
  }
}

int PathContext::segmentOf(double tau) const
{
  int i = 0;
  while (i + 1 < segment_count && tau >= segments[i].t1)
    ++i;
  return i;
}

int PathContext::addPiece(double begin, double end, bool adhering, cd u_begin)
{
  if (!keep || out.pieces >= PathIntegrals::kMaxPieces)
    return -1;
  out.piece[out.pieces] = { begin, end, adhering, u_begin };
  return out.pieces++;
}

}  // namespace sphere_contact_estimator::path
