#include "sphere_contact_estimator/core/brush/brush_forces.h"

namespace sphere_contact_estimator::brush_flags
{
std::vector<std::string> describe(std::uint32_t flags)
{
  std::vector<std::string> out;
  if (flags & kStandstill)
    out.emplace_back("rolling speed below the standstill threshold: slips (eq. 12) are undefined, the steady "
                     "models do not apply; use the transient model");
  if (flags & kNoSteadyStateTilt)
    out.emplace_back("tilting radius |R_gamma| < a: no steady state on an inner disc of the patch (Assumption 4.1, "
                     "Fig. 2); use the transient model");
  if (flags & kLinearSaturated)
    out.emplace_back("linear model beyond the friction limit: |F_t| scaled back to mu F_z; the linear theory "
                     "assumes vanishing sliding, use the steady or transient model");
  if (flags & kAccuracyNotMet)
    out.emplace_back("the error estimate is above the accuracy target (within the work budget, or at the model's own "
                     "limit: a fixed transient resolution, the linear theory): see error_estimate");
  if (flags & kSubstepsTruncated)
    out.emplace_back("transient update cut short by the work budget (or the substeps' limit): sliding steps or "
                     "substeps coarser than accuracy wants, which error_estimate covers (coarser substeps: the "
                     "friction circle's, until the bristles then inside have left the patch)");
  if (flags & kBudgetLimited)
    out.emplace_back("auto missed the accuracy target where the work budget held it back (a coarser lattice, a shorter "
                     "warm start or a looser steady answer than the target asks): a larger work_budget lets it "
                     "refine");
  if (flags & kModelFault)
    out.emplace_back("the brush model failed (a defect: please report it with the input): no forces, its state reset");
  return out;
}
}  // namespace sphere_contact_estimator::brush_flags
