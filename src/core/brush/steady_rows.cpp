#include "steady_rows.h"

// STL
#include <cmath>

// Package
#include "patch_integral.h"

namespace sphere_contact_estimator
{
SteadyRows evaluateSteadyRows(const BristleField& field, double y_first, double spacing, int count, double tolerance,
                              long max_work)
{
  SteadyRows out;
  // half the budget for the integral, the rest for the rows; rows the budget cannot finish leave it incomplete
  const PatchIntegral whole = integratePatch(field, tolerance, max_work / 2);
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
    if (out.work >= max_work)
    {
      out.complete = false;
      break;
    }
    const PathIntegrals row =
        solvePath(field, BristlePath::across(field, std::asin(y0)), row_tolerance, false, max_work - out.work);
    out.work += row.work;
    const double w = std::abs(spacing);  // dA = dy0 dtau on straight paths
    out.rows_force[0] += w * row.force;
    out.rows_moment[0] += w * row.moment;
    out.rows_force[1 + (r & 1)] += 2.0 * w * row.force;
    out.rows_moment[1 + (r & 1)] += 2.0 * w * row.moment;
    out.rows_error += w * row.error;
    if (row.truncated)
    {
      out.converged = false;
      out.complete = false;
    }
  }
  return out;
}

}  // namespace sphere_contact_estimator
