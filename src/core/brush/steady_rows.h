#pragma once

// STL
#include <complex>

// Package
#include "bristle_path.h"

namespace sphere_contact_estimator
{
/// The steady field across a family of straight rows (no tilt), for the transient lattice's control variate.
///
/// Without tilt the transient lattice's rows along the rolling direction are bristle paths (eq. 18a), and its sum is
/// a midpoint rule across them. A re-adhering streak narrower than the row spacing (Sect. 6, where a spin pole lies in
/// the front half) is then hit or missed, an error that does not fall steadily with the resolution. The steady field
/// v of the current inputs has the same streaks, and both its exact integral and its rows' exact integrals are known
/// (integratePatch, solvePath), so the lattice sum Q(u) can be corrected by the midpoint rule's error on v:
/// Q(u) + (int v - Q_rows(v)). Whatever v is, the error left is the rule's error on u - v: at held inputs u is v up
/// to the bristles' integration error, and the streaks cancel.
///
/// Dimensionless as BristleField (forces in units of mu q_z(0) a^2, rows in units of a, rolling frame).
struct SteadyRows
{
  std::complex<double> integral_force;  ///< the steady field's integral of u dA over the patch
  double integral_moment = 0.0;         ///< and of (x u_y - y u_x) dA
  double integral_error = 0.0;          ///< bound on the error of each of the three integrals
  /// The midpoint rule across the rows: the sum of spacing x (each row's exact integral of u along it) over all rows
  /// inside the patch [0], and over the rows of even [1] and odd [2] index with twice the spacing (the sub-lattices).
  std::complex<double> rows_force[3];
  double rows_moment[3] = {};
  double rows_error = 0.0;  ///< bound on the along-row quadrature error of rows_force[0] and rows_moment[0]
  bool converged = false;   ///< the integral met its tolerance within the work budget
  bool complete = true;     ///< every row was solved within the work budget (else no correction can be made)
  long work = 0;            ///< PathIntegrals::work over the rows and the integral
};

/// The steady field's integral over the patch to `tolerance`, and its rows at y0 = y_first + r * spacing for
/// r = 0 .. count - 1 (rows with |y0| >= 1 lie outside the patch and count for nothing), within `max_work`.
SteadyRows evaluateSteadyRows(const BristleField& field, double y_first, double spacing, int count, double tolerance,
                              long max_work);

}  // namespace sphere_contact_estimator
