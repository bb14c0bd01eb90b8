#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "sphere_contact_estimator/core/brush/contact_kinematics.h"
#include "steady_rows.h"

namespace sphere_contact_estimator
{
/// The transient lattice's control variate across its rows (SteadyRows; without tilt, while the lattice's rows follow
/// the rolling direction). The lattice sum is a midpoint rule across the rows; the steady field of the inputs, whose
/// integral and row integrals are known exactly, corrects it by that rule's error on the field, so that at held inputs
/// re-adhering streaks narrower than a spacing cancel. The field is re-evaluated where the rows moved, or for other
/// inputs once they held over an update or a patch diameter was rolled since (between, the last field is a control
/// variate as good as any: the correction stays exact for whatever field it uses), within the work it is given; an
/// evaluation that does not converge within it corrects nothing.
class TransientRows
{
public:
  /// Where the lattice stands: x = o + R l, the position of its first point (l = 0), spacing, width in points.
  struct Lattice
  {
    Eigen::Matrix2d R;
    Eigen::Vector2d first;
    double h;
    int width;
  };

  /// After the lattice's step under slips s: re-evaluates the field where needed (held: the inputs were those of the
  /// last step; travel: rolled in this one; fill_travel: since the lattice started), within max_work. Returns the
  /// work spent.
  long update(const BrushParameters& p, const Slips& s, const Lattice& lattice, bool held, double travel,
              double fill_travel, long max_work);

  /// No correction until the next evaluation (the lattice turned or was coarsened).
  void invalidate() { phi_ = NAN; }
  void reset()
  {
    active_ = false;
    phi_ = NAN;
  }

  bool active() const { return active_; }
  /// The correction is of the steady field of these slips and parameters.
  bool of(const Slips& s, const BrushParameters& p) const;
  /// Sub-lattice k's correction (0: the full lattice; 1-4 the parities of twice the spacing) in the patch frame
  /// [N, N, N m].
  Eigen::Vector3d correction(int k, double a) const;
  /// What sub-lattice k's sum of q_z is normalised to [N]: the same rows' exact integrals of q_z, in the share the
  /// correction has, F_z for the rest.
  double load(int k, double F_z) const;
  /// The correction's own error bound, a fraction of mu F_z.
  double error(PressureDistribution pressure) const;

  /// Work a row is at least expected to take (BrushForces::work units).
  static constexpr long kMinRowsWork = 400;

private:
  int rowSet(int k) const;  // the rows sub-lattice k's sum runs over (0: all; 1, 2: even, odd)

  bool active_ = false;
  int axis_ = 0;                   // rows of constant j (motion along the lattice's x) or of constant i (along y)
  SteadyRows rows_;                // of sigma_, phi_ at the rows' place y_first_
  Eigen::Vector2d sigma_ = Eigen::Vector2d::Constant(NAN);
  double phi_ = NAN, y_first_ = NAN, spacing_ = NAN, travel_ = 0.0;
  double c_ = 1.0, s_ = 0.0;       // the rolling direction in the patch frame
  double scale_ = 0.0;             // dimensionless integrals -> [N]
  double load_[3] = {};            // the rows' exact integrals of q_z [N] (all rows, even, odd)
  BrushParameters params_;         // the parameters rows_ was evaluated with
  double weight_ = 0.0;            // share of the correction in force: the share of a transit rolled since reset
  long work_per_row_ = 0;          // what the last complete evaluation took a row
};

}  // namespace sphere_contact_estimator
