#pragma once

// Package
#include "path_events.h"
#include "series.h"

namespace sphere_contact_estimator::path
{
constexpr int kMaxSegments = 64;  // per path; beyond, the path is flagged truncated

/// What the pieces of one path share while it is solved: the problem, the output it accumulates into, its event
/// signature, and the path's segments (built once, when a piece first needs them).
struct PathContext
{
  PathContext(const BristleField& field, const BristlePath& path, double tolerance, bool keep, long work_limit,
              PathIntegrals& out, CoulombStepper stepper = CoulombStepper::Collocation);

  const BristleField& field;
  const BristlePath& path;
  double tolerance;  ///< bound on the along-path quadrature error of the sliding pieces
  bool keep;         ///< record the pieces (PathIntegrals::piece) for drawing
  long work_limit;
  CoulombStepper stepper;  ///< how eq. (4b)'s sliding pieces are stepped
  PathIntegrals& out;  // the caller's: returned in place (it holds the pieces, most of a kilobyte)
  Signature signature;

  // The path's segments carry the geometry (position, drive, bound): they turn at |omega| per unit travel, at most
  // 1 in a steady state (Assumption 4.1), so a few segments hold any path.
  Segment* segments = nullptr;
  int segment_count = 0;
  double rate = 0.0;  ///< the fastest turn along the path, max(|omega|, |kappa|)

  bool adhered = false;          ///< an adhesion piece was solved (folds are sought on the first)
  int maxima_before_onset = 0;   ///< on the first adhesion piece

  void buildSegments();
  int segmentOf(double tau) const;
  bool overBudget() const { return out.work > work_limit; }
  /// Records a piece for drawing (with keep); returns its index or -1.
  int addPiece(double begin, double end, bool adhering, cd u_begin);
};

}  // namespace sphere_contact_estimator::path
