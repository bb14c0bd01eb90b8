#include "sphere_contact_estimator/core/estimator/run_summary.h"

// STL
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace sphere_contact_estimator
{
void AccuracyMisses::add(const ContactEstimateData& e)
{
  if (!(e.brush.flags & brush_flags::kAccuracyNotMet))
    return;
  ++count;
  cut_short += (e.brush.flags & brush_flags::kSubstepsTruncated) != 0;
  budget_limited += (e.brush.flags & brush_flags::kBudgetLimited) != 0;
  standstill += !(e.brush.flags & (brush_flags::kSubstepsTruncated | brush_flags::kBudgetLimited)) && !e.slips_defined;
  if (e.brush_target > 0.0)
    worst = std::max(worst, e.brush.error_estimate / e.brush_target);
}

std::array<AccuracyMisses::Reason, 3> AccuracyMisses::reasons() const
{
  return { { { cut_short, "cut short by the work budget",
               " (BRUSH_FLAG_SUBSTEPS_TRUNCATED: a larger work_budget buys them)" },
             { budget_limited, "held back by the work budget",
               " (BRUSH_FLAG_BUDGET_LIMITED: a larger work_budget lets auto refine)" },
             { standstill, "at standstill", " (auto refines its lattice only while the patch rolls)" } } };
}

void RunSummary::add(const ContactEstimateData& e)
{
  ++estimates_;
  if (!e.valid())
    ++invalid_;
  if (e.flags & (estimate_flags::kTimeJumpReset | estimate_flags::kGapReset))
    ++resets_;
  if (e.modelFault())
    ++faults_;
  accuracy_.add(e);
  const auto used = static_cast<std::size_t>(e.brush_model_used);
  if (used < models_used_.size())
    ++models_used_[used];

  const double sliding = e.brush.sliding_fraction;
  if (have_last_ && e.dt > 0.0)
  {
    const double dt = e.dt;
    duration_ += dt;
    distance_ += 0.5 * (last_speed_ + e.rolling_speed) * dt;
    rr_energy_ += 0.5 * (last_rr_power_ + e.rolling_resistance_power) * dt;
    brush_energy_ += 0.5 * (last_brush_power_ + e.brush_power) * dt;
    // the interval counts as sliding by its mean sliding share
    const double mean_sliding = 0.5 * (last_sliding_ + sliding);
    sliding_any_ += mean_sliding > 0.01 ? dt : 0.0;
    sliding_mostly_ += mean_sliding > 0.5 ? dt : 0.0;
  }
  have_last_ = true;
  last_speed_ = e.rolling_speed;
  last_rr_power_ = e.rolling_resistance_power;
  last_brush_power_ = e.brush_power;
  last_sliding_ = sliding;

  const double force = std::hypot(e.brush.F_x, e.brush.F_y);
  peak_force_ = std::max(peak_force_, force);
  peak_moment_ = std::max(peak_moment_, std::abs(e.brush.M_z));
  const double limit = e.friction * e.load;
  if (limit > 0.0)
    peak_utilisation_ = std::max(peak_utilisation_, force / limit);
  peak_bristle_ = std::max(peak_bristle_, e.brush.max_utilisation);
  peak_rr_ = std::max(peak_rr_, e.rolling_resistance_force);
}

std::string RunSummary::report() const
{
  char buffer[1024];
  const std::uint64_t n = std::max<std::uint64_t>(estimates_, 1);
  const auto share = [n](std::uint64_t k) { return 100.0 * static_cast<double>(k) / static_cast<double>(n); };
  std::snprintf(buffer, sizeof(buffer),
                "  estimates             %llu over %.3f s (%llu outside a model's assumptions, %llu resets)\n"
                "  distance rolled       %.4g m\n"
                "  energy dissipated     rolling resistance %.4g J, brush (sliding and bristles) %.4g J\n"
                "  time sliding          %.1f %% with > 1 %% of the patch sliding, %.1f %% with more than half\n"
                "  peak brush force      %.4g N (utilisation |F_t|/(mu F_z) %.3f, bristles %.3f), moment %.4g N m\n"
                "  peak rolling resist.  %.4g N\n"
                "  brush models run      off %.1f %%, linear %.1f %%, steady %.1f %%, transient %.1f %%\n",
                static_cast<unsigned long long>(estimates_), duration_, static_cast<unsigned long long>(invalid_),
                static_cast<unsigned long long>(resets_), distance_, rr_energy_, brush_energy_,
                100.0 * slidingShareAny(), 100.0 * slidingShareMostly(), peak_force_, peak_utilisation_, peak_bristle_,
                peak_moment_, peak_rr_, share(models_used_[0]), share(models_used_[1]), share(models_used_[2]),
                share(models_used_[3]));
  std::string out = buffer;
  if (accuracy_.count > 0)
  {
    std::snprintf(buffer, sizeof(buffer),
                  "  brush accuracy        target missed at %llu estimates (%.1f %%; error estimate up to %.3g times it: "
                  "BRUSH_FLAG_ACCURACY_NOT_MET)\n",
                  static_cast<unsigned long long>(accuracy_.count), share(accuracy_.count), accuracy_.worst);
    out += buffer;
    for (const AccuracyMisses::Reason& r : accuracy_.reasons())
      if (r.count > 0)
        out += std::string("                        of them ") + r.what + " at " + std::to_string(r.count) + r.hint +
               "\n";
  }
  else if (models_used_[0] < estimates_)
    out += "  brush accuracy        target met at every estimate\n";
  if (faults_ > 0)
    out += "  MODEL FAULTS          " + std::to_string(faults_) +
           " estimates without forces: a model threw (a defect: please report it with the bag; the CSV's flags say "
           "which)\n";
  return out;
}

}  // namespace sphere_contact_estimator
