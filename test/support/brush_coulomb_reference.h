#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_forces.h"
#include "sphere_contact_estimator/core/brush/brush_parameters.h"

namespace sphere_contact_estimator::test
{
/// Slow, independent reference for the steady brush model under the Coulomb law (tests only).
///
/// Romano et al. eq. (4b) as written: a sliding bristle's stress opposes the tip's full micro-sliding velocity of
/// eq. (1), in travelled distance v_s / V_r = du/ds - w, w = sigma + A_phi x [+ A_phi_psi u with tilt] (eqs. 11,
/// 12, 32), so on the bound u = b e the direction turns as de/ds = (w - (w.e) e) / b. Discretised along each path by
/// its backward-Euler step, the return mapping of FASTSIM: over a step the bristle is propagated exactly as if it
/// adhered (eqs. 17c, 39c) to a trial deflection; beyond the bound b = mu q_z / k at the step's end it is scaled back
/// onto it, b u_trial / |u_trial| (eq. 4); otherwise it adheres, so re-adhesion needs no event. Without spin w has
/// one direction and this is the rigid law of Sect. 6 (test::bruteForceSteady).
///
/// Paper frame, epsilon = (0, 1). n_paths bristle paths at the midpoints of equal intervals of theta in
/// (-pi/2, pi/2): lines y = a sin(theta) (eq. 18a) or, with p.tilt and phi_gamma != 0, circles of radius
/// |1/phi_gamma| + a sin(theta) about the tilting centre (0, 1/phi_gamma) (eqs. 39b, 44a), from the leading edge
/// (u = 0, eq. 8). Along each, n_steps steps equal in tau, s = L (1 - cos tau) / 2 for a path of travel L: equal
/// steps of s would leave a Hertzian square root of q_z at the rims and thin sliding bands along the trailing rim
/// under-resolved, and the along-path error of order 1.5 and erratic (measured), which breaks Richardson. Forces by
/// the trapezoid rule in tau on the step ends (first order, with a smooth coefficient, in 1 / n_steps), the midpoint
/// rule across: F_x, F_y = integral k u dA [N], M_z = integral (x q_y - y q_x) dA [N m]; sliding_fraction (area
/// whose step ends on the bound after a trial beyond it) and max_utilisation. error_estimate = 0.
/// flags = kNoSteadyStateTilt with zero forces when tilt is on and |phi_gamma| a > 1 (Assumption 4.1).
/// phi [1/m]; phi_gamma and phi_psi [1/m] are ignored with p.tilt false.
BrushForces marchCoulomb(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi, double phi_gamma,
                         double phi_psi, int n_paths, int n_steps);

/// marchCoulomb extrapolated, with an estimate of its own error.
struct CoulombReference
{
  BrushForces forces;  ///< extrapolated; forces.error_estimate = error
  /// Estimated error of forces as a fraction of mu F_z, covering each of F_x, F_y and M_z / a [-]
  double error = 0.0;
};

/// Along the paths: Richardson on the levels n_steps, 2 n_steps, 4 n_steps, R = 2 F(2n) - F(n) twice; the finer R is
/// returned and the difference of the two R is its error's share (measured: the R converge at second order at the
/// package's hard points, and the estimate is 3 to 8 times the true error at the defaults, up to ~40 times at
/// n_steps = 250). Across the paths the midpoint rule
/// is kept: beyond ~500 paths its error is ~1e-8 of mu F_z and of no steady order (the events' positions within the
/// steps change from path to path), so extrapolating does not help; its share is the whole difference to n_paths / 2
/// paths at n_steps. At the defaults the estimate is ~1e-8 of mu F_z, in ~3 s (straight paths) to ~12 s (tilt).
/// Cost: 7.5 marchCoulomb(n_paths, n_steps). Valid only once the steps resolve the shortest adhesion or sliding
/// stretch along a path (e.g. b / |sigma| at large slips): before that the levels can agree while all being wrong.
CoulombReference coulombReference(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi,
                                  double phi_gamma, double phi_psi, int n_paths = 2000, int n_steps = 4000);

}  // namespace sphere_contact_estimator::test
