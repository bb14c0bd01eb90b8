#pragma once

// Package
#include "path_context.h"

namespace sphere_contact_estimator::path
{
/// A stretch [lo, hi] of travel.
struct Interval
{
  double lo, hi;
};

/// How an adhesion piece starts.
enum class AdhesionStart
{
  Free,     ///< from a deflection inside the bound (the leading edge, u = 0)
  OnBound,  ///< from the bound, the bristle turning inward: a re-adhesion, where |u|^2 - f^2 has a double root
};

/// Adheres from (tau_s, u_s) by eqs. 15c / 35c, exactly (the path's series), to the first point where |u| reaches the
/// bound f outside `quiet` (stretches where |u| <= f is known to hold: the rigid law's G), or to the trailing edge.
/// Integrates u and its moment over the piece into ctx.out, records the onset in the signature, and returns the
/// deflection where it ended, `end` that travel. With AdhesionStart::OnBound, the double root at the start is
/// skipped; if the bristle does not turn inward there (|u|^2 - f^2 has no negative second derivative: a touch,
/// not a re-adhesion) it returns at once with end = tau_s.
cd adhere(PathContext& ctx, double tau_s, cd u_s, AdhesionStart start, const Interval* quiet, int quiet_count,
          double& end);

}  // namespace sphere_contact_estimator::path
