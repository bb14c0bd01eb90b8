#include "sphere_contact_estimator/core/brush/steady_rows.h"

// STL
#include <cmath>

// Package
#include "sphere_contact_estimator/core/brush/patch_integral.h"

namespace sphere_contact_estimator
{
SteadyRows evaluateSteadyRows(const BristleField& field, double y_first, double spacing, int count, double tolerance,
                              long max_work)
{
  SteadyRows out;
  const PatchIntegral whole = integratePatch(field, tolerance, max_work);
  out.integral_force = whole.force;
  out.integral_moment = whole.moment;
  out.integral_error = whole.error;
  out.converged = whole.converged;
  out.work = whole.work;
  // each row's integral to a tolerance that keeps their sum within the integral's
  const double row_tolerance = tolerance / 2.0;
  for (int r = 0; r < count; ++r)
  {
    const double y0 = y_first + r * spacing;
    if (!(std::abs(y0) < 1.0))
      continue;
    const PathIntegrals row = solvePath(field, BristlePath::across(field, std::asin(y0)), row_tolerance);
    out.work += row.work;
    const double w = std::abs(spacing);  // dA = dy0 dtau on straight paths
    out.rows_force[0] += w * row.force;
    out.rows_moment[0] += w * row.moment;
    out.rows_force[1 + (r & 1)] += 2.0 * w * row.force;
    out.rows_moment[1 + (r & 1)] += 2.0 * w * row.moment;
    out.rows_error += w * row.error;
    if (row.truncated)
      out.converged = false;
  }
  return out;
}

}  // namespace sphere_contact_estimator
