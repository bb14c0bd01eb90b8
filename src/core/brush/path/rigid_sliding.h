#pragma once

// Package
#include "path_context.h"

namespace sphere_contact_estimator::path
{
/// The rigid law (Sect. 6's approximation): a sliding bristle lies on the bound along the drive, u = f w / |w|.
/// Integrates it over [a, b] into ctx.out: in closed form on straight paths while the spin pole is near, else by
/// Gauss-Legendre rules graded towards the pole, whose error bound (within ctx.tolerance) is added to out.error.
void slideRigid(PathContext& ctx, double a, double b);

/// The integral of f w / |w| over [a, b] alone (force, moment and the error bound; no piece recorded), to `tolerance`:
/// the rigid part of a Coulomb sliding piece (coulomb_collocation.h, coulomb_sliding.h).
void integrateRigid(PathContext& ctx, double a, double b, double tolerance);

/// The rigid law's sliding deflection f w / |w| at travel tau (a re-adhering bristle starts from it).
cd rigidSlidingDeflection(const BristleField& field, const BristlePath& path, double tau);

}  // namespace sphere_contact_estimator::path
