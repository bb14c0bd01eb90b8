#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_forces.h"
#include "sphere_contact_estimator/core/brush/brush_parameters.h"

namespace sphere_contact_estimator::test
{
/// Slow, independent reference for the steady brush model (tests only).
///
/// Paper frame, epsilon = (0, 1) (Romano et al. 2022, Sects. 3, 4, 6). n_paths bristle paths at the midpoints of
/// equal intervals of theta in (-pi/2, pi/2): lines y = a sin(theta) (eq. 18a) or, with p.tilt and phi_gamma != 0,
/// circles of radius |1/phi_gamma| + a sin(theta) about the tilting centre (0, 1/phi_gamma) (eqs. 39b, 44a).
/// Along each, n_steps equal steps of travel s from the leading edge (u = 0, eq. 8): adhesion by
/// du/ds = sigma + A_phi x [+ A_phi_psi u with tilt] (eqs. 11, 32; without friction eq. 23 resp. 51), sliding at
/// |u| = mu q_z / k (eq. 4) along the rigid sliding field, re-adhesion from the capped deflection where d(mu q_z/k)/ds > |sigma + A_phi x|. Both events
/// are bisected inside the step; forces by Simpson's rule along the paths (split at events), midpoint rule across.
/// Along paths it converges fast; across paths only to first order, with an erratic sign, where paths grazing the
/// re-adhesion island around the spin centre make the per-path integral jump (~1e-4 mu F_z at the defaults there).
///
/// Returns F_x, F_y, M_z, sliding_fraction, max_utilisation; error_estimate = 0; flags = kNoSteadyStateTilt (and zero
/// forces) when tilt is on and |1/phi_gamma| < a. phi_gamma and phi_psi are ignored with p.tilt false.
BrushForces bruteForceSteady(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi, double phi_gamma,
                             double phi_psi, int n_paths = 2000, int n_steps = 4000);

}  // namespace sphere_contact_estimator::test
