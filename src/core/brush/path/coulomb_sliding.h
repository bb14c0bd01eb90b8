#pragma once

// Package
#include "path_context.h"

namespace sphere_contact_estimator::path
{
/// How a Coulomb sliding piece starts.
struct SlideStart
{
  double tau = 0.0;   ///< travel where it starts
  cd direction{ 1.0, 0.0 };  ///< unit direction of u there (ignored from the rim)
  /// The bristle enters sliding where the bound vanishes (the leading edge, tau = 0): it takes the direction the
  /// law makes it take there, that of the drive.
  bool from_rim = false;
  /// Re-adhesion may be found only after the piece has seen the bristle pushed outward (after a touch that did not
  /// re-adhere, the event function starts at zero).
  bool armed = true;
};

/// Where a Coulomb sliding piece ended.
struct SlideEnd
{
  double tau = 0.0;            ///< travel: a re-adhesion, or the trailing edge (the path's length)
  cd direction{ 1.0, 0.0 };    ///< unit direction of u there
  bool re_adheres = false;     ///< ended by re-adhesion before the trailing edge
};

/// The paper's sliding law, eq. (4b) with the micro-sliding velocity of eq. (1), along a path in the steady state.
///
/// A sliding bristle stays on the bound, u = f e^{i theta}, and eq. (4b) asks its full sliding velocity
/// v_s = du/dtau - (w + i kappa u) (eqs. 11, 32, dimensionless) to point along -u. Its component across u gives the
/// direction equation
///     f theta' = Im(w e^{-i theta}) + kappa f,
/// the bristle turning towards the drive at a rate inversely proportional to the bound; its component along u gives
/// the sliding speed, lambda f^2 = f Re(w e^{-i theta}) - f f' >= 0, which vanishes where the drive stops pushing the
/// bristle outward faster than the bound grows: there it re-adheres (eq. 4a).
///
/// The direction equation is a Riccati equation: the half-angle vector v = (cos theta/2, sin theta/2) obeys the
/// linear system v' = B v, B = (1/2) [[W_x, W_y - K], [W_y + K, -W_x]] with W = w / f and K = kappa, whose growing
/// mode is the drive's direction (the rigid law is its stiff limit). It is stiff where f is small (near the edges,
/// where f vanishes): in the variable s of the pressure law's map (tau = L / (1 + e^-s) for f ~ t, tau = L sin^2(s/2)
/// for f ~ sqrt t, tau itself for a constant f) the factor 1/f becomes bounded, and each step applies the exact
/// exponential of a sixth-order Magnus approximation of the system over it, stable for any step. The step size is
/// chosen by the difference to the fourth-order approximation from the same three Gauss nodes; the forces are
/// integrated by the same nodes, the direction there from a Hermite interpolant of v. Where the bound vanishes at
/// the trailing edge, the part beyond where it is negligible is bounded, not integrated.
///
/// With CoulombStepper::Collocation (the default) the piece is first stepped by the stiff collocation
/// (coulomb_collocation.h), 3-5 times cheaper a step; the Magnus steps here take over only where it stops short, and
/// are the whole solution with CoulombStepper::General (an independent check of the collocation's).
///
/// Adds the piece's force, moment and sliding travel to ctx.out, and a bound on its error to out.error.
SlideEnd slideCoulomb(PathContext& ctx, const SlideStart& start);

/// The direction of the sliding bristle at travel tau within a piece that starts at `start` (for drawing).
cd coulombDirectionAt(const BristleField& field, const BristlePath& path, const SlideStart& start, double tau);

}  // namespace sphere_contact_estimator::path
