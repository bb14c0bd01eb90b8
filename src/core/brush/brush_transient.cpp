#include "sphere_contact_estimator/core/brush/brush_transient.h"

// STL
#include <algorithm>
#include <array>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// The brush library's private rooms
#include "bristle_path.h"
#include "lattice/bristle_advance.h"
#include "patch_integral.h"
#include "plane_rotation.h"
#include "rolling_frame.h"
#include "transient_rows.h"

namespace sphere_contact_estimator
{
namespace
{
bool sameInputs(const ContactKinematics& a, const ContactKinematics& b)
{
  return a.V_r == b.V_r && a.V_s == b.V_s && a.omega_z == b.omega_z && a.psi_dot == b.psi_dot;
}
}  // namespace

BrushTransient::BrushTransient(const BrushParameters& parameters)
  : BrushModel(parameters), rows_(std::in_place)
{
  allocate();
}

BrushTransient::~BrushTransient() = default;
BrushTransient::BrushTransient(const BrushTransient&) = default;
BrushTransient::BrushTransient(BrushTransient&&) noexcept = default;
BrushTransient& BrushTransient::operator=(const BrushTransient&) = default;
BrushTransient& BrushTransient::operator=(BrushTransient&&) noexcept = default;

bool BrushTransient::setParameters(const BrushParameters& parameters)
{
  parameters.validate();
  const bool lattice_changes = parameters.a != p_.a || parameters.resolution != p_.resolution;
  const bool changes = !(parameters == p_);
  p_ = parameters;
  if (lattice_changes)
    allocate();
  else if (changes)
  {
    // the bristles were deflected under other parameters: not the steady state of any inputs under these (the rows'
    // steady field stays a valid control variate until it is re-evaluated: no jump at a retune)
    held_travel_ = 0.0;
    clearSpreadWindow();  // spreads in fractions of another mu F_z
  }
  return lattice_changes;
}

void BrushTransient::renew(const BrushParameters& parameters)
{
  parameters.validate();
  p_ = parameters;
  // every member as the constructor leaves it; allocate() sizes the arrays within their storage and resets the rest
  work_budget_ = kUnlimitedBudget;
  stepping_ = TransientStepping::WholeStep;
  work_ = 0;
  last_steps_ = 0;
  last_travel_ = 0.0;
  streak_work_ = 0;
  streak_estimate_ = 0.0;
  last_kin_ = ContactKinematics{};
  *rows_ = TransientRows{};
  allocate();
}

void BrushTransient::swapStorage(BrushTransient& other)
{
  auto theirs = other.perPointArrays();
  perPointArrays().swap(theirs);  // a tuple of references: swaps what they refer to
  forces_kept_ = other.forces_kept_ = false;
}

void BrushTransient::rotateFrame(double alpha)
{
  if (std::all_of(u_.begin(), u_.end(), [](const Eigen::Vector2d& u) { return u.isZero(0.0); }))
  {
    reset();  // nothing to turn: keep the lattice's rows along the frame's axes (the rows' correction needs them)
    return;
  }
  held_travel_ = 0.0;
  have_last_kin_ = false;
  clearSpreadWindow();  // the phases were in the old axes
  rows_->invalidate();
  const Eigen::Matrix2d Q = rotation(-alpha);  // components in axes turned by alpha
  R_ = Q * R_;
  o_ = Q * o_;
  suspect_centre_ = Q * suspect_centre_;
  for (Eigen::Vector2d& u : u_)
    u = Q * u;
  for (Eigen::Vector2d& j : jump_)
    j = Q * j;
  V_r_ = Q * V_r_;
  recentre();
}

void BrushTransient::allocate()
{
  const int n = p_.resolution;
  h_ = 2.0 * p_.a / n;
  w_ = windowWidth(n);
  c0_ = 0.5 * (w_ - 1);
  const std::size_t size = points(n);  // w_ * w_
  resizeState(size, false);
  resizeState(size, true);
  reset();
}

void BrushTransient::reserve(int resolution)
{
  const std::size_t size = points(resolution);
  std::apply([size](auto&... v) { (v.reserve(size), ...); }, perPointArrays());
}

void BrushTransient::resizeState(std::size_t size, bool scratch)
{
  for (auto* v : scratch ? std::array{ &u_scratch_, &jump_scratch_ } : std::array{ &u_, &jump_ })
    v->resize(size);
  for (auto* v : scratch ? std::array{ &inside_scratch_, &sliding_scratch_ } : std::array{ &inside_, &sliding_ })
    v->resize(size);
  for (auto* v : scratch ? std::array{ &slip_travel_scratch_, &step_error_scratch_ } : std::array{ &slip_travel_, &step_error_ })
    v->resize(size);
  if (!scratch)
    arc_stepping_.resize(size);
}

bool BrushTransient::coarsen()
{
  const int n = p_.resolution;
  if (n % 2 != 0 || n / 2 < kMinCoarsened)
    return false;
  // the fine state into the scratch arrays (sized for the fine window), then the coarse window over it: coarse point
  // (i, j) is fine point (2 i - 2, 2 j - 2) when the pose moves by half a fine spacing along both lattice axes
  // (fine points lie at (I - c0) h, c0 = (n + 5) / 2; coarse ones at (i - c0') 2h + h / 2, c0' = (n / 2 + 5) / 2)
  const int w_fine = w_;
  std::copy(u_.begin(), u_.end(), u_scratch_.begin());
  std::copy(jump_.begin(), jump_.end(), jump_scratch_.begin());
  std::copy(inside_.begin(), inside_.end(), inside_scratch_.begin());
  std::copy(sliding_.begin(), sliding_.end(), sliding_scratch_.begin());
  std::copy(slip_travel_.begin(), slip_travel_.end(), slip_travel_scratch_.begin());
  std::copy(step_error_.begin(), step_error_.end(), step_error_scratch_.begin());
  o_ += R_ * Eigen::Vector2d(0.5 * h_, 0.5 * h_);
  p_.resolution = n / 2;
  h_ = 2.0 * p_.a / p_.resolution;
  w_ = windowWidth(p_.resolution);
  c0_ = 0.5 * (w_ - 1);
  const std::size_t size = static_cast<std::size_t>(w_) * w_;
  resizeState(size, false);  // the scratch arrays still hold the fine state
  for (int j = 0; j < w_; ++j)
    for (int i = 0; i < w_; ++i)
    {
      const std::size_t p = index(i, j);
      const int I = 2 * i - 2, J = 2 * j - 2;
      const bool kept = I >= 0 && J >= 0 && I < w_fine && J < w_fine;
      const std::size_t q = kept ? static_cast<std::size_t>(J) * w_fine + I : 0;
      u_[p] = kept ? u_scratch_[q] : Eigen::Vector2d::Zero();
      jump_[p] = kept ? jump_scratch_[q] : Eigen::Vector2d::Zero();
      inside_[p] = kept ? inside_scratch_[q] : 0;
      sliding_[p] = kept ? sliding_scratch_[q] : 0;
      slip_travel_[p] = kept ? slip_travel_scratch_[q] : INFINITY;
      step_error_[p] = kept ? step_error_scratch_[q] : 0.0;
    }
  // the scratch arrays the same size again (recentre swaps them in); shrinking keeps their storage
  resizeState(size, true);
  rows_->reset();  // the rows moved: the control variate is evaluated again
  clearSpreadWindow();  // the spreads were of the finer lattice
  // the sliding steps this lattice is predicted to take, as predictFinerWork relates a finer lattice's to its own (the
  // finer lattice's count had made this one's step look four times as dear: sweep seed 1253, its step not fitting at
  // 32, was cut to 8 where 16 fitted)
  last_steps_ = static_cast<long>(static_cast<double>(last_steps_) / kFinerSteps);
  recentre();
  return true;
}

void BrushTransient::reset()
{
  R_.setIdentity();
  o_.setZero();
  std::fill(u_.begin(), u_.end(), Eigen::Vector2d::Zero());
  std::fill(sliding_.begin(), sliding_.end(), 0);
  std::fill(slip_travel_.begin(), slip_travel_.end(), INFINITY);
  std::fill(step_error_.begin(), step_error_.end(), 0.0);
  std::fill(jump_.begin(), jump_.end(), Eigen::Vector2d::Zero());
  V_r_.setZero();
  omega_gamma_ = 0.0;
  arc_visit_share_ = 1.0;
  have_last_kin_ = false;
  held_travel_ = 0.0;
  fill_travel_ = 0.0;
  suspect_ = false;
  suspect_centre_.setZero();
  clearSpreadWindow();
  rows_->reset();
  const double a2 = p_.a * p_.a;
  for (int j = 0; j < w_; ++j)
    for (int i = 0; i < w_; ++i)
      inside_[index(i, j)] = position(i, j).squaredNorm() < a2;
}

BrushForces BrushTransient::update(const ContactKinematics& kin, const Slips& slips, double dt)
{
  checkInput(kin, slips, dt);
  work_ = 0;
  forces_kept_ = false;
  BrushForces f;
  bool short_of_work = false;
  if (dt > 0.0 && !p_.tilt && stepping_ == TransientStepping::WholeStep)
  {
    if (!advanceWhole(kin, dt))
      f.flags |= brush_flags::kSubstepsTruncated;
  }
  else if (dt > 0.0)
  {
    const int n = substeps(kin, dt);
    if (n < 0)
    {
      short_of_work = true;  // longer substeps than accuracy wants: no claim beyond the friction circle's
      f.flags |= brush_flags::kSubstepsTruncated;
    }
    int count = n < 0 ? kMaxSubsteps : n;
    if (p_.tilt && stepping_ == TransientStepping::WholeStep)
    {
      // bristle by bristle, within the budget: where it cannot pay for every substep, the bristles that need them share
      // fewer, longer ones, their error counted (advanceArcs)
      if (!advanceArcs(kin, dt, count))
        f.flags |= brush_flags::kSubstepsTruncated;
    }
    else
    {
      // fewer substeps than accuracy wants where the work budget cannot pay for them (a fixed lattice, or auto's at its
      // coarsest): the answer then makes no claim beyond the friction circle's, nor do the next ones (suspect_)
      const long point_work = static_cast<long>(w_) * w_ * kPointWork;
      const long affordable = (work_budget_ - afterStepsWork()) / point_work;
      if (count > affordable)
      {
        count = static_cast<int>(std::max(1L, affordable));
        short_of_work = true;
        f.flags |= brush_flags::kSubstepsTruncated;
      }
      for (int s = 0; s < count; ++s)
        substep(kin, dt / count);
      work_ += static_cast<long>(count) * w_ * w_ * kPointWork;
    }
  }
  if (short_of_work)
  {
    suspect_ = true;  // the bristles inside now carry it (suspect_centre_ follows them)
    suspect_centre_.setZero();
  }
  else if (suspect_ && suspect_centre_.norm() >= 2.0 * p_.a)
    suspect_ = false;
  const bool held = have_last_kin_ && sameInputs(kin, last_kin_);
  const double travel = kin.V_r.norm() * std::max(dt, 0.0);
  held_travel_ = held ? held_travel_ + travel : travel;
  fill_travel_ += travel;
  last_kin_ = kin;
  have_last_kin_ = true;
  // the rows' correction within what the work budget leaves after the lattice's steps and the sums
  work_ += rows_->update(p_, slips, { R_, position(0, 0), h_, w_ }, held, travel, fill_travel_,
                        work_budget_ - work_ - sumsWork());
  // the rows' correction holds the streaks once every bristle in the patch entered under the inputs it is of
  const bool corrected = held_travel_ >= 2.0 * p_.a && rows_->of(slips, p_);
  const long before_streaks = work_;
  streak_estimate_ = corrected ? 0.0 : streakBound(slips, std::max(0L, work_budget_ - work_ - sumsWork()), work_);
  streak_work_ = work_ - before_streaks;
  double fixed = 0.0, spread = 0.0;
  const BrushForces g = sums(fixed, spread);
  // the spreads of the window (kWindowSpacings): the phase moves with the roots' displacement and, with tilt, their
  // turn
  const double turn = p_.tilt ? kin.omegaGamma() * std::max(dt, 0.0) : 0.0;
  const Eigen::Vector3d step(kin.V_r.x() * std::max(dt, 0.0), kin.V_r.y() * std::max(dt, 0.0), p_.a * turn);
  const double window = kWindowSpacings * h_;
  phase_ += step;
  window_spread_ = 0.0;
  other_phases_ = false;
  // the updates since the last that rolled a spacing or more, each rolling less: dense enough to sample the error's
  // pattern over the phases, where one stood at another
  const bool dense = step.norm() < h_;
  for (int i = 0; i < spread_count_; ++i)
  {
    const Eigen::Vector3d moved = phase_ - phase_at_[i];
    const double travelled = moved.norm();
    const int age = (spread_next_ - 1 - i + kSpreadWindow) % kSpreadWindow;  // 0: the last update's
    if (travelled >= window && age >= kRecentUpdates)
      continue;  // the patch has moved on
    window_spread_ = std::max(window_spread_, spread_at_[i]);
    if (!dense || age >= dense_run_ || travelled >= h_)
      continue;
    // the lattice repeats every spacing along its axes: the phase is the displacement modulo a spacing
    Eigen::Vector2d l = R_.transpose() * moved.head<2>() / h_;
    l -= l.array().round().matrix();
    other_phases_ = other_phases_ || std::hypot(h_ * l.norm(), moved.z()) >= 0.25 * h_;
  }
  spread_at_[spread_next_] = spread;
  phase_at_[spread_next_] = phase_;
  spread_next_ = (spread_next_ + 1) % kSpreadWindow;
  spread_count_ = std::min(spread_count_ + 1, kSpreadWindow);
  dense_run_ = dense ? std::min(dense_run_ + 1, kSpreadWindow) : 0;
  f.F_x = g.F_x;
  f.F_y = g.F_y;
  f.M_z = g.M_z;
  f.sliding_fraction = g.sliding_fraction;
  f.max_utilisation = g.max_utilisation;
  f.error_estimate = estimate(fixed, spread) + cutShortError();
  kept_forces_ = g;  // forces() of this state, as it would sum them again
  kept_forces_.error_estimate = f.error_estimate;
  forces_kept_ = true;
  f.flagAbove(p_.accuracy_target);  // (at a fixed resolution; auto flags its answers against its own target)
  work_ += sumsWork();
  f.work = work_;
  return f;
}

long BrushTransient::predictWork(const ContactKinematics& kin, double dt) const
{
  return predictWorkFor(w_, h_, arc_visit_share_, kin, dt);
}

long BrushTransient::predictWorkAt(int resolution, const ContactKinematics& kin, double dt) const
{
  // as allocate() and reset() would leave it
  return predictWorkFor(windowWidth(resolution), 2.0 * p_.a / resolution, 1.0, kin, dt);
}

long BrushTransient::predictWorkFor(int w, double h, double share, const ContactKinematics& kin, double dt) const
{
  // the lattice's, and the last update's streak search (the rigid law's, reserved before the steps)
  long lattice;
  const long points = static_cast<long>(w) * w;
  if (!p_.tilt && stepping_ == TransientStepping::WholeStep)
  {
    // the closed forms of every bristle, the sums, and the sliding steps
    lattice = points * (kBristleWork + kSumWork) + static_cast<long>(predictStepsAt(kin, dt, h)) * kStepWork;
  }
  else if (stepping_ == TransientStepping::WholeStep)
    lattice = arcsWorkAt(dt > 0.0 ? substepsAt(kin, dt, h) : 0, w, share);
  else
    lattice = substepsWork(dt > 0.0 ? substepsAt(kin, dt, h) : 0, w);
  return lattice + streak_work_;
}

long BrushTransient::arcsWorkAt(int n, long w, double visit_share) const
{
  // every point's closed form (or its being outside), the sums, and the substeps at the last update's share of points
  // times substeps, with room for that share to grow by half (where they do not fit, the stepped bristles take fewer
  // substeps, their error counted), and never more than the lattice's loop would count: a point that closes after v
  // substeps counts v kPointWork + kBristleWork with v < n, at most n kPointWork
  const double share = std::min(1.0, 1.5 * visit_share + 0.05);
  const double visits = share * (n < 0 ? kMaxSubsteps : n) * static_cast<double>(w * w);
  return std::min(w * w * (kBristleWork + kSumWork) + static_cast<long>(std::ceil(visits)) * kPointWork,
                  substepsWork(n, w));
}

long BrushTransient::predictFinerWork(const ContactKinematics& kin, double dt) const
{
  // the finer lattice's, and the streak search (as predictWork's: it does not depend on the lattice)
  long lattice;
  if (!p_.tilt && stepping_ == TransientStepping::WholeStep)
  {
    const long w = 2L * w_;  // (the finer window, windowWidth(2 n), is a little less)
    lattice = w * w * (kBristleWork + kSumWork) + static_cast<long>(kFinerSteps * predictSteps(kin, dt)) * kStepWork;
  }
  else
  {
    // substeps (tilt): the finer lattice's own count (about twice this one's: half the spacing) over its window, as
    // predictWork counts them (8 times this one's prediction was 1.7 times a 16's step at 8, 66 k units against 39 k: a
    // lattice the budget had cut to 8 never came back); stepped bristle by bristle, the share of them this one's took
    const int n = dt > 0.0 ? substepsAt(kin, dt, 0.5 * h_) : 0;
    lattice = stepping_ == TransientStepping::WholeStep ? arcsWork(n, windowWidth(2 * p_.resolution))
                                                        : substepsWork(n, windowWidth(2 * p_.resolution));
  }
  return lattice + streak_work_;
}

bool BrushTransient::advanceWhole(const ContactKinematics& kin, double dt)
{
  // The roots move at -V_r (eq. 31 without tilt): the lattice's pose moves by -V_r dt, and the window is recentred on
  // the patch's new place first, so that it covers every bristle inside at the step's end.
  V_r_ = kin.V_r;
  omega_gamma_ = 0.0;
  o_ -= dt * kin.V_r;
  suspect_centre_ -= dt * kin.V_r;
  recentre();
  const double a2 = p_.a * p_.a, speed2 = kin.V_r.squaredNorm();
  const lattice::BristleAdvance advance(p_, kin, timeTolerance());
  // the sliding steps within what the budget leaves after every bristle's closed forms and the sums; past it, each
  // bristle's remainder in one step (its error counted in the estimate)
  long pool = work_budget_ - work_ - static_cast<long>(w_) * w_ * kBristleWork - afterStepsWork();
  bool enough = true;
  long steps = 0;
  const Eigen::Vector2d along = rowStep();
  for (int j = 0; j < w_; ++j)
  {
    const Eigen::Vector2d first = rowStart(j);
    const std::size_t row = index(0, j);
    double first_step = INFINITY;  // eq. (4b): the sliding steps' first try, handed along the row (advance())
    for (int i = 0; i < w_; ++i)
    {
      const std::size_t p = row + i;
      const Eigen::Vector2d x1 = first + i * along;
      if (x1.squaredNorm() >= a2)
      {
        leavePatch(p);
        continue;
      }
      Eigen::Vector2d x0 = x1 + dt * kin.V_r;
      if (inside_[p] && !sliding_[p] && advance.adhereThrough(u_[p], x0, dt))
        continue;  // most bristles: adhering, well inside their bound over the whole step (no event, no steps)
      double duration = dt;
      bool at_rim = false;
      lattice::BristleState s;
      if (inside_[p])
      {
        s.u = u_[p];
        s.sliding = sliding_[p];
        s.slip_travel = slip_travel_[p];
        s.jump = jump_[p];
        s.step_error = step_error_[p];
      }
      else
      {
        s.slip_travel = INFINITY;
        const double c = x0.squaredNorm() - a2;
        if (c > 0.0)
        {
          // it entered this step, where its path crosses the rim: the first root of |x0 - V_r tau|^2 = a^2
          const double b = x0.dot(kin.V_r), root = b + std::sqrt(std::max(0.0, b * b - speed2 * c));
          const double entry = root > 0.0 ? std::min(dt, c / root) : dt;
          x0 -= entry * kin.V_r;
          duration = dt - entry;
          at_rim = true;
        }
      }
      const int allowed = pool > 0 ? static_cast<int>(std::min<long>(kMaxBristleSteps, pool / kStepWork)) : 0;
      const int taken = advance.advance(s, x0, duration, at_rim, allowed, &first_step);
      steps += taken;
      pool -= taken * kStepWork;
      enough = enough && !s.cut;  // (its remainder in one step, or events it did not follow)
      u_[p] = s.u;
      sliding_[p] = s.sliding;
      slip_travel_[p] = s.slip_travel;
      jump_[p] = s.jump;
      step_error_[p] = s.step_error;
      inside_[p] = 1;
    }
  }
  work_ += static_cast<long>(w_) * w_ * kBristleWork + steps * kStepWork;
  last_steps_ = steps;
  last_travel_ = std::min(std::sqrt(speed2) * dt, 2.0 * p_.a);
  return enough;
}

double BrushTransient::timeTolerance() const
{
  // a fraction of the bound at the centre, mu q_z(0) / k: the deflection every bristle's error is measured against
  const double bound = p_.mu * peakFactor(p_.pressure) * p_.F_z / (boost::math::double_constants::pi * p_.a * p_.a) / p_.k;
  return kTimeTolerance * bound / (static_cast<double>(p_.resolution) * p_.resolution);
}

void BrushTransient::leavePatch(std::size_t p)
{
  u_[p].setZero();  // outside the patch: undeformed (it re-enters under eq. 8)
  step_error_[p] = 0.0;
  inside_[p] = sliding_[p] = 0;
}

double BrushTransient::streakBound(const Slips& s, long max_work, long& work) const
{
  // A stretch of G (where sliding bristles re-adhere) narrower than a few lattice rows anchors a streak the
  // rows may all miss. Its force is bounded by |u - f w/|w|| <= 2 f over its width times the longest path
  // (pi in units of a), the field's units: 2 pi width (q_z(0) / (F_z / pi a^2)) / pi of mu F_z. The bands' ends are
  // needed only against three spacings: to kStreakPrecision, each width taken within its brackets either way (wider
  // where it counts); the search then counts less than half the work it takes to the steady solver's 1e-12 (a tilted
  // Hertzian robot: 21 500 units against 50 500).
  if (p_.sliding_law == SlidingLaw::Coulomb)
    return 0.0;  // eq. (4b)'s field is continuous across the paths: no streaks of re-adhered bristles
  BristleField field;
  if (!s.defined || (p_.tilt && std::abs(s.phi_gamma) * p_.a > 1.0))
    return 0.0;
  const Eigen::Vector2d sigma = RollingFrame(s.epsilon).toRolling(s.sigma);
  if (!makeBristleField(p_, { sigma.x(), sigma.y() }, s.phi, s.phi_gamma, s.phi_psi, field))
    return 0.0;
  constexpr int kBands = 8;  // the most it looks for
  double lo[kBands], hi[kBands], bound = 0.0;
  StructureSearch search;
  search.precision = kStreakPrecision;
  search.max_work = max_work;
  const int n = reAdhesionBands(field, lo, hi, kBands, search);
  work += search.work;
  if (search.cut)  // the work spent before every band was found: the most that as many bands as it looks for could hold
    return kBands * 2.0 * peakFactor(p_.pressure) * 3.0 * h_ / p_.a;
  const double slack = 2.0 * search.bracket;  // |d sin| <= |d theta| at either end
  for (int i = 0; i < n; ++i)
  {
    const double width = std::sin(hi[i]) - std::sin(lo[i]);  // in units of a
    if ((width - slack) * p_.a < 3.0 * h_)
      bound += 2.0 * peakFactor(p_.pressure) * (width + slack);
  }
  return bound;
}

Eigen::Vector2i BrushTransient::recentre()
{
  // The patch centre in lattice coordinates, in spacings from the window centre.
  const Eigen::Vector2d l = -R_.transpose() * o_ / h_;
  const int di = static_cast<int>(std::lround(l.x())), dj = static_cast<int>(std::lround(l.y()));
  if (di == 0 && dj == 0)
    return { 0, 0 };
  // New index (i, j) holds old (i + di, j + dj); points shifted in from outside the window lie outside
  // the patch (the margin), so they start undeformed. Row by row: the kept stretch of a row is contiguous in both.
  const int i0 = std::clamp(-di, 0, w_), i1 = std::clamp(w_ - di, i0, w_);  // the kept columns [i0, i1)
  const auto shift = [&](auto& to, const auto& from, const auto& blank) {
    for (int j = 0; j < w_; ++j)
    {
      const auto row = to.begin() + static_cast<std::ptrdiff_t>(index(0, j));
      const int sj = j + dj;
      if (sj < 0 || sj >= w_ || i0 >= i1)
      {
        std::fill(row, row + w_, blank);
        continue;
      }
      std::fill(row, row + i0, blank);
      const auto source = from.begin() + static_cast<std::ptrdiff_t>(index(i0 + di, sj));
      std::copy(source, source + (i1 - i0), row + i0);
      std::fill(row + i1, row + w_, blank);
    }
  };
  shift(u_scratch_, u_, Eigen::Vector2d::Zero().eval());
  shift(jump_scratch_, jump_, Eigen::Vector2d::Zero().eval());
  shift(inside_scratch_, inside_, std::uint8_t{ 0 });
  shift(sliding_scratch_, sliding_, std::uint8_t{ 0 });
  shift(slip_travel_scratch_, slip_travel_, static_cast<double>(INFINITY));
  shift(step_error_scratch_, step_error_, 0.0);
  u_.swap(u_scratch_);
  jump_.swap(jump_scratch_);
  inside_.swap(inside_scratch_);
  sliding_.swap(sliding_scratch_);
  slip_travel_.swap(slip_travel_scratch_);
  step_error_.swap(step_error_scratch_);
  o_ += R_ * Eigen::Vector2d(di * h_, dj * h_);
  return { di, dj };
}

}  // namespace sphere_contact_estimator
