#pragma once

namespace sphere_contact_estimator
{
/// How the steady solver steps a sliding piece of a bristle path under eq. (4b) (SlidingLaw::Coulomb).
enum class CoulombStepper
{
  /// Stiff collocation in the frame of the bristle's own direction wherever it can go on, the general stepper beyond
  /// (near a spin pole where the collocation's steps would be tiny): the default.
  Collocation,
  /// The general stepper (Magnus steps of the half-angle system) on every piece: an independent solution to check the
  /// collocation's answers and estimates against.
  General,
};

}  // namespace sphere_contact_estimator
