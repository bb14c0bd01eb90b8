#pragma once

// STL
#include <cstdint>
#include <string>
#include <vector>

namespace sphere_contact_estimator
{
/// Bit flags qualifying a brush evaluation. Those in kInvalidatingFlags make it invalid.
namespace brush_flags
{
constexpr std::uint32_t kStandstill = 1u << 0;           ///< V_r below the standstill speed: slip form undefined
constexpr std::uint32_t kNoSteadyStateTilt = 1u << 1;    ///< |R_gamma| < a: no steady state on an inner disc (Fig. 2)
constexpr std::uint32_t kLinearSaturated = 1u << 2;      ///< linear model beyond mu F_z: force scaled back
constexpr std::uint32_t kSubstepsTruncated = 1u << 3;    ///< transient: step too long, fewer substeps than accuracy wants
constexpr std::uint32_t kAccuracyNotMet = 1u << 4;       ///< error_estimate above the accuracy target (every model)
/// The model failed (threw: a defect, not an input it refuses): no forces (zero), the model's state reset;
/// ContactEstimator::lastFault says what.
constexpr std::uint32_t kModelFault = 1u << 5;
/// auto, with kAccuracyNotMet: the work budget held the answer back in this update (the finer lattice a missed target
/// asks for does not fit what it leaves, or the lattice was coarsened or a finer one dropped for it; a warm start
/// short of its roll; a steady answer short of its tolerance). A larger work_budget lets auto refine: a promise of a
/// finer answer, not of the target (a finer lattice answers once it has rolled the longest path, and may still miss).
constexpr std::uint32_t kBudgetLimited = 1u << 6;
constexpr std::uint32_t kInvalidatingFlags = kStandstill | kNoSteadyStateTilt | kLinearSaturated | kModelFault;

std::vector<std::string> describe(std::uint32_t flags);
}  // namespace brush_flags

/// What a brush model returns: forces and moment on the sphere, in the paper frame (Romano et al.,
/// Sect. 6), and how much of the patch slides.
struct BrushForces
{
  double F_x = 0.0;               ///< [N]
  double F_y = 0.0;               ///< [N]
  double M_z = 0.0;               ///< about the patch centre, integral of (x q_y - y q_x) [N m]
  double sliding_fraction = 0.0;  ///< share of the patch area where the bristles slide [-]
  double max_utilisation = 0.0;   ///< largest |q_t| / (mu q_z) over the patch [-]
  /// Bound on the error of this answer against the model's exact solution, as a fraction of mu F_z: it covers
  /// each of F_x, F_y and M_z / a [-]
  double error_estimate = 0.0;
  std::uint32_t flags = 0;        ///< brush_flags bits
  /// The work this answer took, counted, not timed (series terms, rule nodes, solver steps, bristle substeps), so that
  /// a replay counts the same on every machine: about 10 ns a unit on this machine kind (docs/benchmarks.md).
  long work = 0;

  bool valid() const { return (flags & brush_flags::kInvalidatingFlags) == 0; }
  /// kAccuracyNotMet where the estimate passes `target`, what the flag says for every model (it only sets it: the steady
  /// solver also sets it where its integral did not converge)
  void flagAbove(double target)
  {
    if (error_estimate > target)
      flags |= brush_flags::kAccuracyNotMet;
  }
};

}  // namespace sphere_contact_estimator
