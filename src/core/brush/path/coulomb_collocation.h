#pragma once

// Package
#include "coulomb_sliding.h"

namespace sphere_contact_estimator::path
{
/// Eq. (4b) along a sliding piece by stiff collocation: the default stepper (CoulombStepper::Collocation).
///
/// A sliding bristle stays on the bound, u = f e^{i theta}, its direction obeying (coulomb_sliding.h)
///     theta' = K + Im(W e^{-i theta}),   W = (g / f) w,  K = g kappa   (' = d/ds, s the pressure law's map variable),
/// the law pulling it towards the drive w at the rate Re(W e^{-i theta}). Over each step, in the frame of the bristle's
/// own direction at the step's start, t = tan((theta - theta_0) / 2) obeys the Riccati equation
///     t' = (K + Im W') / 2 - Re(W') t + (K - Im W') / 2 t^2,   W' = W e^{-i theta_0},
/// rational (e^{i (theta - theta_0)} = (1 - t^2 + 2 i t) / (1 + t^2): no trigonometry), small over a step whatever the
/// drive does, and defined where the drive vanishes (a spin pole) or reverses. It is solved by the three-stage Radau IIA
/// collocation (order 5, L-stable and stiffly accurate: where the pull is strong its stages lie on the slow manifold, so
/// the steps follow the inputs' scale, not the pull's), Newton's method on the stages from the previous step's
/// collocation cubic, steps chosen by the embedded estimate of Hairer and Wanner's RADAU5 scaled to the fifth-order
/// solution's error (coulomb_collocation.cpp: how, and how it was checked).
///
/// The forces: where the drive is resolved over a step, the rigid field f w / |w| integrated by the rigid law's own rules
/// over each run of such steps plus the small correction f (e - w / |w|) by the collocation's quadrature over the stages
/// (the quadrature components of the ODE system); where it is not (it swings by up to pi beside a pole), the whole
/// stress f e. A direction error decays at the pull, so it errs the forces of the travel after it, carried from step to
/// step. Where the bound vanishes at the edges (f ~ t) the stretches too short for any force to count are bounded, not
/// integrated: there |Delta| <= (pi / 2) sup |Kd| / W in the drive's frame.
///
/// Re-adhesion (eq. 4a): the first point where the bristle, once pushed outward, no longer is (the sliding speed
/// Re(w e*) - df/dtau < 0), sought at the stages and where the cubic through the sliding speeds at the step's points dips
/// between them, located by regula falsi on the collocation cubic, and the step up to it collocated on its own.
///
/// Returns true when the piece ended, at the trailing edge or a re-adhesion: `end` holds it, ctx.out the piece's force,
/// moment, sliding travel and error bound. Returns false, having added what it integrated, where it stopped short: where
/// a step would have to be tiny (a stiff turn it cannot resolve), the work budget, or a trailing stretch that cannot be
/// bounded (the drive vanishing at the trailing edge). `resume` then holds the state there for the general stepper
/// (slideCoulomb) to continue the piece from.
bool slideCollocation(PathContext& ctx, const SlideStart& start, SlideEnd& end, SlideStart& resume);

}  // namespace sphere_contact_estimator::path
