#pragma once

// STL
#include <algorithm>

namespace sphere_contact_estimator::numerics
{
/// Where g turns negative within (lo, hi], given g(lo) = g_lo >= 0 > g(hi) = g_hi: regula falsi in its Illinois
/// variant (the end kept twice has its value halved, so that a convex g does not pin one end), each point clamped to
/// the bracket, until the bracket is narrower than `width` or after `max_iterations`. Returns the bracket's end where
/// g < 0 (a re-adhesion is at the latest there: the bristles' sliding speed, in the path solvers).
template <class G>
double illinoisNegativeEnd(const G& g, double lo, double hi, double g_lo, double g_hi, double width, int max_iterations)
{
  for (int it = 0; it < max_iterations && hi - lo > width; ++it)
  {
    const double y = std::clamp(g_lo - g_hi != 0.0 ? hi - g_hi * (hi - lo) / (g_hi - g_lo) : 0.5 * (lo + hi), lo, hi);
    const double gy = g(y);
    if (gy < 0.0)
    {
      hi = y, g_hi = gy;
      g_lo *= 0.5;
    }
    else
    {
      lo = y, g_lo = gy;
      g_hi *= 0.5;
    }
  }
  return hi;
}

}  // namespace sphere_contact_estimator::numerics
