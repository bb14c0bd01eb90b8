#pragma once

// Package
#include "adhesion.h"

namespace sphere_contact_estimator::path
{
constexpr int kMaxGIntervals = 8;

/// The rigid law's re-adhesion margin along a segment, as a series: (df/dtau)^2 - |w|^2 times a positive factor
/// (4 t^(2-m) / m^2 of PressureLaw's f^2 = t^m); >= 0 in the front half exactly where a bristle sliding along w would
/// re-adhere (G). Identically -1 where the bound never grows (uniform pressure).
void reAdhesionSeries(const BristleField& field, const Segment& g, double* H);

/// The stretches of the path's front half inside G (at most kMaxGIntervals), in travel order; builds the path's
/// segments unless the path provably misses G. Returns how many.
int findReAdhesionRegion(PathContext& ctx, Interval* g);

}  // namespace sphere_contact_estimator::path
