#pragma once

// STL
#include <complex>
#include <functional>

// Package
#include "bristle_path.h"

namespace sphere_contact_estimator
{
/// The steady bristle field integrated over the unit patch (dimensionless as BristleField), with a bound on
/// its error.
struct PatchIntegral
{
  std::complex<double> force;  ///< integral of u dA
  double moment = 0.0;         ///< integral of (x u_y - y u_x) dA
  double sliding_area = 0.0;   ///< area where the bristles slide (the patch's is pi)
  double utilisation2 = 0.0;   ///< largest (|u| / f)^2 seen
  /// Bound on the error of each of force.real(), force.imag() and moment (the largest of the three).
  double error = 0.0;
  int paths = 0;               ///< paths solved
  long work = 0;               ///< their work (PathIntegrals::work)
  bool converged = false;      ///< error <= the tolerance asked for
};

/// Integrates the field over the patch to `tolerance` (in the units of the result, a bound on each of the
/// three integrals). Across the paths, theta in (-pi/2, pi/2) (y0 = sin theta), by 15-point Gauss-Kronrod
/// rules on sub-intervals (7-point ones on those narrow enough for the tolerance: kNarrowWidth; under the parabolic
/// pressure the whole patch, where the load goes as cos^4 theta, by the Gauss-Kronrod pairs of that weight in y0 with
/// 7-11 nodes, jacobiAcross): split first at the path through the spin pole, where the sliding direction reverses, and
/// where G's extent changes (structureBreakpoints), each such interval probed just inside its ends for a band of other
/// structure beside them; then wherever two samples of a rule see a different event structure along their paths
/// (signatures differ, or the onset's fold changes sign: PathIntegrals::fold), located by bisection on the structure,
/// so that no rule straddles a change of structure; then the sub-interval with the largest error estimate is halved
/// until the sum meets the tolerance. The estimate is |Kronrod - Gauss| where a third, lower-degree rule on the same
/// samples shows the rules converging, and twice the largest of the three differences where it does not. The
/// along-path quadrature's own bound (solvePath) is added. Every bound on an unresolved piece uses the field's own
/// bound on |u| (BristleField::deflectionBound), so tiny slips converge at once. Stops, unconverged, when the paths' work
/// reaches `max_work`: the paths left unsolved and the intervals left unrefined are bounded, never guessed. `stepper`:
/// how eq. (4b)'s sliding pieces are stepped (solvePath).
PatchIntegral integratePatch(const BristleField& field, double tolerance, long max_work,
                            CoulombStepper stepper = CoulombStepper::Collocation);

/// Builds the quadrature rules integratePatch draws on that are built on first use (numerics::prepareQuadratureRules
/// and the rules across the paths): once per process, about half a millisecond (BrushSteady::prepareRules).
void preparePatchRules();

/// Theta of the path through the spin pole, if the pole lies inside the patch.
bool polePath(const BristleField& field, double& theta);

/// How structureBreakpoints locates the ends of G's component around a front-half pole (the rigid law): to a bracket
/// of `precision` [rad] (0: as far as its searches go, 1e-12 or less), within `max_work` (PathIntegrals::work units;
/// each path's polynomials kRootWork). What it did: its work, the widest bracket it left a breakpoint in, and whether
/// the work stopped a search before its precision (`cut`; an end it had not yet reached is then missing). Its
/// searches evaluate about a hundred paths; on tilted (curved) paths under the Hertzian pressure that had been
/// 0.3-0.8 ms a message, uncounted (bench/work_units.cpp).
struct StructureSearch
{
  double precision = 0.0;
  long max_work = kUnlimitedWork;
  long work = 0;
  double bracket = 0.0;
  bool cut = false;
};

/// Where the event structure across the paths changes for reasons fixed in the plane, ascending: the pole's
/// path; the extent across the paths of G's component around a front-half pole; where G meets the leading
/// edge. Returns how many it wrote (at most max_count).
int structureBreakpoints(const BristleField& field, double* theta, int max_count, StructureSearch& search);

/// The ranges of theta where the paths cross a stretch of G that the paths beside them lack (G around a
/// front-half pole, G at the leading edge): each anchors a streak of re-adhering bristles as wide as itself (its ends
/// within search.bracket; where search.cut, none: not every band was found).
/// Returns how many it wrote (at most max_count).
int reAdhesionBands(const BristleField& field, double* lo, double* hi, int max_count, StructureSearch& search);

}  // namespace sphere_contact_estimator
