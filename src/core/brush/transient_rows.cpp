#include "transient_rows.h"

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "pressure_law.h"
#include "rolling_frame.h"

namespace sphere_contact_estimator
{
namespace
{
// For inputs that change at every update (noisy odometry), the field is re-evaluated once the lattice rolled this many
// patch radii since the last: its state is the inputs' history over a transit (2 a), and the field of any inputs from
// within it is as good a control variate. With 1 (the first choice), Fig. 4's 10-ms message at 1 m/s and resolution 64
// spent 28 % of its instructions on the rows; with 2, 17 % fewer in all. model_accuracy --robot-histories 404 300 and 606
// 400: 0 estimates below the error, the same worst ratio as with 1. The recorded streams are unchanged: there the
// rows are re-evaluated as the lattice turns with the rolling direction. With 4, Fig. 4's message at 64 took 7.9 % less
// counted work (4.0 % at 128); the same histories gave the same worst ratios (0.48, 0.55), and the 96 sweep streams of
// seeds 1168-1263 0 unflagged answers over the target at 1 % and 0.1 % (their flags within 12 of 60 365).
constexpr double kRefreshTravel = 4.0;
}  // namespace

long TransientRows::update(const BrushParameters& p, const Slips& s, const Lattice& lattice, bool held, double travel,
                           double fill_travel, long max_work)
{
  active_ = false;
  if (p.tilt)
    return 0;  // the paths are arcs about the tilting centre, not the lattice's rows
  if (!s.defined)
    return 0;  // no steady field at standstill
  const RollingFrame frame(s.epsilon);
  // the rows follow the rolling direction when it lies along a lattice axis
  const Eigen::Vector2d along = lattice.R.transpose() * frame.toPatch(Eigen::Vector2d(1.0, 0.0));
  int axis;
  if (std::abs(along.y()) <= 1e-12)
    axis = 0;
  else if (std::abs(along.x()) <= 1e-12)
    axis = 1;
  else
    return 0;
  // the rows' place across the patch, in the rolling frame and units of a
  const double y_first = frame.toRolling(lattice.first).y() / p.a;
  const double spacing =
      frame.toRolling(lattice.R * (axis == 0 ? Eigen::Vector2d(0.0, lattice.h) : Eigen::Vector2d(lattice.h, 0.0))).y() /
      p.a;
  const Eigen::Vector2d sigma = frame.toRolling(s.sigma);
  const bool same = sigma == sigma_ && s.phi == phi_ && params_ == p;
  // (to rounding: the rolling direction's last bits change from one update to the next, and each such change had
  // re-evaluated the field, two in three of its evaluations along the 1 kHz recording)
  const Eigen::Vector2d e = frame.toPatch(Eigen::Vector2d(1.0, 0.0));
  const bool moved = !(std::abs(y_first - y_first_) <= 1e-12 && std::abs(spacing - spacing_) <= 1e-12 &&
                       std::abs(e.x() - c_) <= 1e-12 && std::abs(e.y() - s_) <= 1e-12);
  travel_ += travel;
  long work = 0;
  // re-evaluated where it moved; for other inputs or parameters only in a step that rolls (not at a duplicate stamp
  // after a retune: no jump), once they held over it or kRefreshTravel was rolled since
  if (moved || (!same && travel > 0.0 && (held || travel_ >= kRefreshTravel * p.a)))
  {
    BristleField field;
    if (!makeBristleField(p, { sigma.x(), sigma.y() }, s.phi, 0.0, 0.0, field))
    {
      phi_ = NAN;
      return 0;  // no load or no friction: no force to correct
    }
    // a twentieth of the lattice's error scale (about 1 / n^2 of mu F_z at resolution n, docs/benchmarks.md)
    const double scale = peakFactor(p.pressure) / boost::math::double_constants::pi;  // -> fractions of mu F_z
    const double tolerance = 0.05 / (static_cast<double>(p.resolution) * p.resolution);
    // not started where the work left cannot pay for as much a row as the last evaluation took (or kMinRowsWork)
    if (max_work < std::max(kMinRowsWork, work_per_row_) * lattice.width)
    {
      phi_ = NAN;  // no correction this time (the streaks' bound says what is missed)
      return 0;
    }
    rows_ = evaluateSteadyRows(field, y_first, spacing, lattice.width, tolerance / scale,
                               std::min(BrushSteady::kMaxWork, max_work));
    work = rows_.work;
    if (!rows_.complete || !rows_.converged)
    {
      // the budget could not buy every row, or the field's integral to its tolerance: no correction (an unconverged
      // integral would correct by its own error; the streaks' bound says what is missed), and more asked of the budget
      // before the next try
      phi_ = NAN;
      work_per_row_ = std::max(work_per_row_, 2 * rows_.work / lattice.width + 1);
      return work;
    }
    work_per_row_ = rows_.work / lattice.width;
    sigma_ = sigma;
    phi_ = s.phi;
    params_ = p;
    y_first_ = y_first;
    spacing_ = spacing;
    c_ = e.x();
    s_ = e.y();
    scale_ = p.mu * p.F_z * scale;
    travel_ = 0.0;
  }
  if (std::isnan(phi_))
    return work;
  // the same rows' exact integrals of q_z [N] (the strip of width spacing along the chord at y0), always of the
  // current parameters: the lattice's normalisation
  const double q0_a2 = peakFactor(p.pressure) * p.F_z / boost::math::double_constants::pi;  // q_z(0) a^2
  std::fill(std::begin(load_), std::end(load_), 0.0);
  for (int r = 0; r < lattice.width; ++r)
  {
    const double y0 = y_first + r * spacing, c2 = 1.0 - y0 * y0;
    if (!(c2 > 0.0))
      continue;
    const double strip = PressureLaw(p.pressure).chordIntegral(std::sqrt(c2));  // of q_z / q_z(0), units of a
    load_[0] += q0_a2 * std::abs(spacing) * strip;
    load_[1 + (r & 1)] += 2.0 * q0_a2 * std::abs(spacing) * strip;
  }
  // The correction is for the steady field; a lattice that has not yet rolled a transit holds mostly nothing (or the
  // state it was reset to), where it would only add that field's quadrature error: it enters in proportion to the
  // share of the longest path rolled since the lattice started, so that an empty patch gives exactly nothing and the
  // forces stay continuous.
  weight_ = std::min(1.0, fill_travel / (2.0 * p.a));
  axis_ = axis;
  active_ = true;
  return work;
}

bool TransientRows::of(const Slips& s, const BrushParameters& p) const
{
  return active_ && s.defined && phi_ == s.phi && sigma_ == RollingFrame(s.epsilon).toRolling(s.sigma) && params_ == p;
}

int TransientRows::rowSet(int k) const
{
  return k == 0 ? 0 : 1 + (axis_ == 0 ? ((k - 1) >> 1) & 1 : (k - 1) & 1);
}

Eigen::Vector3d TransientRows::correction(int k, double a) const
{
  if (!active_)
    return Eigen::Vector3d::Zero();
  const int r = rowSet(k);  // the rows the sum runs over: all, or those of one parity
  const std::complex<double> F = rows_.integral_force - rows_.rows_force[r];
  const double M = rows_.integral_moment - rows_.rows_moment[r];
  // rolling frame -> patch frame
  const double scale = weight_ * scale_;
  const double F_x = scale * F.real(), F_y = scale * F.imag();
  return { c_ * F_x - s_ * F_y, s_ * F_x + c_ * F_y, scale * a * M };
}

double TransientRows::load(int k, double F_z) const
{
  return active_ ? weight_ * load_[rowSet(k)] + (1.0 - weight_) * F_z : F_z;
}

double TransientRows::error(PressureDistribution pressure) const
{
  return active_ ? weight_ * (rows_.integral_error + rows_.rows_error) * peakFactor(pressure) /
                       boost::math::double_constants::pi :
                   0.0;
}

}  // namespace sphere_contact_estimator
