#pragma once

// STL
#include <array>
#include <cstdint>
#include <string>

// Package
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

namespace sphere_contact_estimator
{
/// Brush answers flagged brush_flags::kAccuracyNotMet (the target not reached within the work budget), and the largest
/// of their error estimates over the target: bag_analyze's summary and the node's diagnostic count them alike.
struct AccuracyMisses
{
  std::uint64_t count = 0;
  double worst = 0.0;  ///< largest error_estimate / target [-]
  /// of them, cut short (brush_flags::kSubstepsTruncated: the transient model's sliding steps or substeps past the
  /// budget), which a larger work_budget buys
  std::uint64_t cut_short = 0;
  /// of them, auto's answers the budget held back (brush_flags::kBudgetLimited: a coarser lattice, a shorter warm start
  /// or a looser steady answer than the target asks), where a larger work_budget lets auto refine
  std::uint64_t budget_limited = 0;
  /// of them, neither and at standstill (slips undefined: auto refines its lattice only while the patch rolls, and a
  /// parked robot's lattice keeps what it rolled in with)
  std::uint64_t standstill = 0;
  void add(const ContactEstimateData& e);
  /// The three counts above with what held them back and what would help, worded once for bag_analyze's summary and
  /// the node's diagnostic
  struct Reason
  {
    std::uint64_t count;
    const char* what;
    const char* hint;
  };
  std::array<Reason, 3> reasons() const;
};

/// What a run did, accumulated over its estimates (bag_analyze's summary). Integrals use the trapezoid rule
/// over each estimate's own dt, so the intervals the estimator did not advance over (a gap longer than
/// max_step, a time jump, a duplicate stamp) count nothing.
class RunSummary
{
public:
  /// Adds one estimate (the next in time).
  void add(const ContactEstimateData& e);

  std::uint64_t estimates() const { return estimates_; }
  double duration() const { return duration_; }            ///< time integrated over [s]
  double distance() const { return distance_; }            ///< rolled, integral of V_r [m]
  double rollingResistanceEnergy() const { return rr_energy_; }  ///< integral of F_R L V_r [J]
  double brushEnergy() const { return brush_energy_; }     ///< integral of -(F . V_s + M_z omega_z) [J]
  /// Share of the time with more than `threshold` of the patch sliding, for threshold 1 % and 50 %.
  double slidingShareAny() const { return duration_ > 0.0 ? sliding_any_ / duration_ : 0.0; }
  double slidingShareMostly() const { return duration_ > 0.0 ? sliding_mostly_ / duration_ : 0.0; }
  double peakForce() const { return peak_force_; }          ///< largest |F_t| [N]
  double peakMoment() const { return peak_moment_; }        ///< largest |M_z| [N m]
  double peakUtilisation() const { return peak_utilisation_; }  ///< largest |F_t| / (mu F_z) [-]
  double peakBristleUtilisation() const { return peak_bristle_; }  ///< largest |q| / (mu q_z) [-]
  double peakRollingResistance() const { return peak_rr_; }  ///< largest F_R L [N]
  /// Estimates per brush model that ran (indexed by BrushModelKind: off, linear, steady, transient).
  const std::array<std::uint64_t, 4>& brushModelsUsed() const { return models_used_; }
  std::uint64_t invalid() const { return invalid_; }       ///< estimates outside a model's assumptions
  std::uint64_t resets() const { return resets_; }         ///< time jumps and gaps
  std::uint64_t faults() const { return faults_; }         ///< estimates whose model threw (kModelFault): a defect
  /// Brush answers flagged brush_flags::kAccuracyNotMet (the target not reached within the work budget), and the
  /// largest of their error estimates over the target.
  std::uint64_t accuracyMissed() const { return accuracy_.count; }
  std::uint64_t accuracyMissedCutShort() const { return accuracy_.cut_short; }  ///< of them, cut short
  std::uint64_t accuracyMissedBudgetLimited() const { return accuracy_.budget_limited; }  ///< of them, budget-held
  std::uint64_t accuracyMissedStandstill() const { return accuracy_.standstill; }  ///< of the rest, at standstill
  double worstAccuracyRatio() const { return accuracy_.worst; }

  /// A few lines for people: distance, energies, sliding, peaks, the models auto chose.
  std::string report() const;

private:
  std::uint64_t estimates_ = 0, invalid_ = 0, resets_ = 0, faults_ = 0;
  AccuracyMisses accuracy_;
  std::array<std::uint64_t, 4> models_used_{};
  double duration_ = 0.0, distance_ = 0.0, rr_energy_ = 0.0, brush_energy_ = 0.0;
  double sliding_any_ = 0.0, sliding_mostly_ = 0.0;
  double peak_force_ = 0.0, peak_moment_ = 0.0, peak_utilisation_ = 0.0, peak_bristle_ = 0.0, peak_rr_ = 0.0;
  bool have_last_ = false;
  double last_speed_ = 0.0, last_rr_power_ = 0.0, last_brush_power_ = 0.0, last_sliding_ = 0.0;
};

}  // namespace sphere_contact_estimator
