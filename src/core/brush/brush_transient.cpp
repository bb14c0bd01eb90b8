#include "sphere_contact_estimator/core/brush/brush_transient.h"

// STL
#include <algorithm>
#include <array>
#include <tuple>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/numerics/quadrature_rules.h"

// The brush library's private rooms
#include "bristle_path.h"
#include "friction_cap.h"
#include "lattice/bristle_advance.h"
#include "patch_integral.h"
#include "rolling_frame.h"
#include "transient_rows.h"

namespace sphere_contact_estimator
{
namespace
{
constexpr double kMaxAngle = 0.1;  // rad per substep, for every rotation

Eigen::Matrix2d rotation(double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

// Integral over [0, t] of the rotation R(rate tau): [[S, -C], [C, S]] with S = sin(rate t)/rate and
// C = (1 - cos(rate t))/rate, by series where rate t is small.
Eigen::Matrix2d rotationIntegral(double rate, double t)
{
  const double x = rate * t;
  double S, C;
  if (std::abs(x) < 1e-3)
  {
    S = t * (1.0 - x * x / 6.0);
    C = t * x * 0.5 * (1.0 - x * x / 12.0);
  }
  else
  {
    S = std::sin(x) / rate;
    C = (1.0 - std::cos(x)) / rate;
  }
  return (Eigen::Matrix2d() << S, -C, C, S).finished();
}

// -V_s - A_omega_z x: the drive of the bristle ODE and the rigid sliding direction (time domain).
Eigen::Vector2d drive(const ContactKinematics& k, const Eigen::Vector2d& x)
{
  return { -k.V_s.x() + k.omega_z * x.y(), -k.V_s.y() - k.omega_z * x.x() };
}

// Where a sliding bristle moving from x0 to x1 in a substep first enters G, the region where it re-adheres, as a
// share s of the substep in [0, 1]; -1 if it does not. In G the bound mu q_z / k grows along the motion faster than
// the drive w would grow an adhering |u| from the bound (the sliding direction being w / |w|, docs/conventions.md):
// L >= |w| with L = d(mu q_z / k)/dt = -2 x . V_r d(mu q_z / k)/d(r^2) (the roots move at -V_r + omega_gamma e_z x x,
// so the turn adds nothing to d(r^2)/dt, and the turn coupling only rotates u). Over the substep w is affine in s
// and L is taken linear (exact for the parabolic pressure), so L >= 0 and L^2 - |w|^2 >= 0, a quadratic, give the
// entry in closed form. Testing the ends alone, or the adhering step against the bound, missed G where a path
// passes it within a substep, beside a spin pole where the sliding direction turns: whole streaks of re-adhered
// bristles then slid instead, an error that did not fall with the resolution (the example point of issue 11).
double reAdhesionEntry(const ContactKinematics& k, const FrictionCap& cap, const Eigen::Vector2d& x0,
                       const Eigen::Vector2d& x1)
{
  const auto growth = [&](const Eigen::Vector2d& x) { return -2.0 * x.dot(k.V_r) * cap.boundSlope(x.squaredNorm()); };
  const double L0 = growth(x0), L1 = growth(x1), dL = L1 - L0;
  if (L0 < 0.0 && L1 < 0.0)
    return -1.0;  // the bound shrinks all along (the rear half): no G
  const Eigen::Vector2d w0 = drive(k, x0), dw = drive(k, x1) - w0;
  const auto inside = [&](double s) {
    const double L = L0 + s * dL;
    return L >= 0.0 && L * L >= (w0 + s * dw).squaredNorm() * (1.0 - 1e-12);
  };
  if (inside(0.0))
    return 0.0;
  // the first s where either condition starts to hold: a root of L or of the quadratic
  const double q2 = dL * dL - dw.squaredNorm(), q1 = 2.0 * (L0 * dL - w0.dot(dw)), q0 = L0 * L0 - w0.squaredNorm();
  double candidates[3];
  int n = 0;
  if (dL != 0.0)
    candidates[n++] = -L0 / dL;
  if (q2 != 0.0)
  {
    const double disc = q1 * q1 - 4.0 * q2 * q0;
    if (disc >= 0.0)
    {
      // the roots without cancellation
      const double r = -0.5 * (q1 + std::copysign(std::sqrt(disc), q1));
      if (r != 0.0)
        candidates[n++] = q0 / r;
      candidates[n++] = r / q2;
    }
  }
  else if (q1 != 0.0)
    candidates[n++] = -q0 / q1;
  std::sort(candidates, candidates + n);
  for (int i = 0; i < n; ++i)
    if (candidates[i] > 0.0 && candidates[i] <= 1.0 && inside(candidates[i]))
      return candidates[i];
  return -1.0;
}

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

int BrushTransient::substeps(const ContactKinematics& kin, double dt) const { return substepsAt(kin, dt, h_); }

int BrushTransient::substepsAt(const ContactKinematics& kin, double dt, double h) const
{
  // each bristle's path within half a lattice spacing, every rotation below kMaxAngle; -1 beyond kMaxSubsteps
  const double omega_gamma = p_.tilt ? kin.omegaGamma() : 0.0;
  double travel = (kin.V_r.norm() + std::abs(omega_gamma) * (p_.a + h)) * dt;
  // Under eq. (4b) the step is also one of time: the tips' motion (the drive, V_s + A_omega x) is resolved as the
  // roots' (at standstill with spin it is the only motion, and one step per message left a first-order error at the
  // bound's scale)
  if (p_.sliding_law == SlidingLaw::Coulomb)
    travel = std::max(travel, (kin.V_s.norm() + std::abs(kin.omega_z) * (p_.a + h)) * dt);
  double angle = std::abs(omega_gamma) * dt;
  if (p_.tilt)
    angle = std::max(angle, std::abs(kin.psi_dot) * dt);
  const double wanted = std::ceil(std::max({ 1.0, travel / (0.5 * h), angle / kMaxAngle }));
  return wanted <= kMaxSubsteps ? static_cast<int>(wanted) : -1;
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

struct BrushTransient::Coupling
{
  // du/dt = w - [A_psi_dot u] over a time t with the drive w held: R(spin t) u + Int_0^t R(spin tau) dtau w. Every
  // bristle inside throughout a substep takes it over the substep, a sliding one over its halves too: their cosines and
  // sines once per substep (they were a sixth of a tilted message's instructions), the same numbers as before.
  Coupling(double spin, double dt)
    : spin(spin), full(dt), R_full(rotation(spin * dt)), S_full(rotationIntegral(spin, dt))
    , R_half(rotation(spin * (0.5 * dt))), S_half(rotationIntegral(spin, 0.5 * dt))
  {
  }
  Eigen::Vector2d operator()(const Eigen::Vector2d& u, const Eigen::Vector2d& w, double t) const
  {
    if (spin == 0.0)
      return u + t * w;
    if (t == full)
      return R_full * u + S_full * w;
    if (t == 0.5 * full)
      return R_half * u + S_half * w;
    return rotation(spin * t) * u + rotationIntegral(spin, t) * w;
  }
  double spin, full;
  Eigen::Matrix2d R_full, S_full, R_half, S_half;
};

void BrushTransient::substep(const ContactKinematics& kin, double dt)
{
  // Rigid motion of the bristle roots over dt (eq. 31): dx/dt = -V_r - A_omega_gamma x with
  // A_omega_gamma = -chi_gamma A_omega_z (after eq. 31), i.e. the roots turn with the sphere at rate
  // +omega_gamma. Exactly: x' = R(omega_gamma dt) x - Int_0^dt R(omega_gamma tau) dtau V_r.
  const double rate = p_.tilt ? kin.omegaGamma() : 0.0;
  V_r_ = kin.V_r;
  omega_gamma_ = rate;
  const Eigen::Matrix2d Q = rotation(rate * dt);
  const Eigen::Matrix2d R_old = R_;
  const Eigen::Vector2d o_old = o_;
  R_ = Q * R_;
  o_ = Q * o_ - rotationIntegral(rate, dt) * kin.V_r;
  suspect_centre_ = Q * suspect_centre_ - rotationIntegral(rate, dt) * kin.V_r;
  const Coupling coupling(p_.tilt ? -kin.psi_dot : 0.0, dt);
  const FrictionCap cap(p_);
  for (int j = 0; j < w_; ++j)
    for (int i = 0; i < w_; ++i)
    {
      const Eigen::Vector2d l((i - c0_) * h_, (j - c0_) * h_);
      substepBristle(kin, cap, coupling, index(i, j), o_old + R_old * l, o_ + R_ * l, dt);
    }
  recentre();
}

void BrushTransient::substepBristle(const ContactKinematics& kin, const FrictionCap& cap, const Coupling& coupling,
                                    std::size_t p, const Eigen::Vector2d& x0, const Eigen::Vector2d& x1, double dt)
{
  // Bristle ODE du/dt = w(x) - [A_psi_dot u]: exact rotation at rate -psi_dot of the coupling, drive at the midpoint
  // of the time spent inside the patch.
  const double a2 = p_.a * p_.a;
  const double g1 = x1.squaredNorm() - a2;
  if (g1 >= 0.0)
  {
    leavePatch(p);
    return;
  }
  double share = 1.0;  // part of the substep spent inside
  const bool was_sliding = inside_[p] && sliding_[p];
  if (!inside_[p])
  {
    const double g0 = x0.squaredNorm() - a2;
    share = g0 > 0.0 ? -g1 / (g0 - g1) : 1.0;
    u_[p].setZero();
    step_error_[p] = 0.0;
  }
  double t = share * dt;
  Eigen::Vector2d x_start = x1 + share * (x0 - x1);
  Eigen::Vector2d& u = u_[p];
  const double travel = (x1 - x_start).norm();
  if (p_.sliding_law == SlidingLaw::Coulomb)
  {
    coulombStep(kin, cap, coupling, p, x_start, x1, t, was_sliding);
    return;
  }
  if (was_sliding)
  {
    // A sliding bristle re-adheres only where it enters G (reAdhesionEntry). Testing the adhering step against
    // the bound instead re-adhered too early where the sliding direction turns within a substep (beside a spin
    // pole, where G lies): 5 % of the bound off on whole streaks at the example point of issue 11.
    const double s_in = reAdhesionEntry(kin, cap, x_start, x1);
    if (s_in < 0.0)
    {
      cap.slide(u, x1, drive(kin, x1));
      slip_travel_[p] += travel;
      return;  // inside and sliding, as it was
    }
    x_start += s_in * (x1 - x_start);
    cap.slide(u, x_start, drive(kin, x_start));  // the capped deflection it re-adheres from
    t *= 1.0 - s_in;
  }
  const Eigen::Vector2d x_mid = 0.5 * (x_start + x1);
  const double over_start = u.norm() - p_.mu * cap.qz(x_start.squaredNorm()) / p_.k;  // <= 0 if it adhered
  u = coupling(u, drive(kin, x_mid), t);
  const Eigen::Vector2d adhering = u;
  const FrictionCap::Result r = cap.apply(u, x1, drive(kin, x1));
  if (!r.sliding)
    slip_travel_[p] = INFINITY;
  else
  {
    // onset in this substep (or after re-adhering in it): where |u| - bound crossed zero, linearly between its
    // start and end values
    const double over_end = adhering.norm() - p_.mu * r.q_z / p_.k;
    const double before = over_start < 0.0 && over_end > over_start ? -over_start / (over_end - over_start) : 0.0;
    slip_travel_[p] = (1.0 - before) * (x1 - x_start).norm();
    // at the onset |u| is the bound: the jump turns it from the adhering direction onto the sliding field
    const double n_adh = adhering.norm(), bound = p_.mu * r.q_z / p_.k;
    jump_[p] = n_adh > 0.0 ? Eigen::Vector2d(bound * adhering / n_adh - u) : Eigen::Vector2d::Zero();
  }
  inside_[p] = 1;
  sliding_[p] = r.sliding;
}

bool BrushTransient::advanceArcs(const ContactKinematics& kin, double dt, int count)
{
  // The same substeps as substep() (the roots' rigid motion of eq. 31 over each), taken bristle by bristle: the lattice's
  // pose moves over the whole update and the window is recentred on the patch's new place first, then each bristle
  // steps along its arc, x_k = Q x_(k-1) - c. An adhering bristle whose arc from a substep's end on cannot reach its
  // bound (arcStaysInside) is advanced over the rest of the update in closed form (arcMap): most bristles of a rolling
  // patch, which took every substep before.
  const double step = dt / count, rate = kin.omegaGamma();
  V_r_ = kin.V_r;
  omega_gamma_ = rate;
  const Eigen::Matrix2d Q = rotation(rate * step), R0 = R_;
  const Eigen::Vector2d c = rotationIntegral(rate, step) * kin.V_r, o0 = o_;
  for (int s = 0; s < count; ++s)
  {
    R_ = Q * R_;
    o_ = Q * o_ - c;
    suspect_centre_ = Q * suspect_centre_ - c;
  }
  const Eigen::Vector2i shift = recentre();  // bristle (i, j) now was (i, j) + shift at the start
  // the closed forms along arcs of at most a quarter turn (arcStaysInside's sagitta), each remaining span's map once
  const bool arcs = std::abs(rate) * dt <= 0.5 * boost::math::double_constants::pi;
  const auto clear = [&](std::vector<ArcMap>& maps, int substeps) {
    for (int k = 0; k <= std::min(substeps, kArcMaps); ++k)
      maps[k].ready = false;
  };
  clear(arc_maps_, count);
  const FrictionCap cap(p_);
  const double a2 = p_.a * p_.a;
  // an adhering bristle at x after k of n substeps of length h, out of reach of its bound over the rest: in closed form
  const auto adheres = [&](std::vector<ArcMap>& maps, std::size_t p, const Eigen::Vector2d& x,
                           const Eigen::Vector2d& x_end, int k, int n, double h) {
    if (!arcs || n > kArcMaps || !inside_[p] || sliding_[p] || !arcStaysInside(kin, cap, u_[p], x, x_end, (n - k) * h))
      return false;
    const ArcMap& m = arcMap(maps, kin, k, n, h);
    u_[p] = m.A * u_[p] - m.C * x + m.d;
    return true;
  };
  // The work: kBristleWork for a point outside at the end or a closed form, kPointWork for each substep, so at most
  // kPointWork a point and substep, as the lattice's loop counts. First every point that leaves the patch or adheres
  // out of reach from the start (most of a rolling patch); then the rest, which may take every substep. Each of those
  // takes every substep while the budget left pays for them all at the same share for it and every one after it; where
  // it does not, the bristle takes that share's fewer, longer substeps along its arc (still in closed form once out of
  // reach), so that a shortfall is shared among all the bristles left, not put on the last rows, and what a bristle
  // does not use goes to the ones after it. Such a bristle carries 3 bounds as its error (it and the true deflection
  // within the bound, and the rigid law's onset jump, at most one bound, in its cell), which the estimate sums with the
  // steps' errors until it leaves.
  // where bristle (i, j) starts the update (it stood at (i, j) + shift of the pose then) and ends it (position)
  const auto start = [&](int i, int j) -> Eigen::Vector2d {
    return o0 + R0 * (Eigen::Vector2d((i - c0_) * h_, (j - c0_) * h_) + h_ * shift.cast<double>());
  };
  long work = 0, visits = 0;
  std::size_t stepping = 0;
  for (int j = 0; j < w_; ++j)
    for (int i = 0; i < w_; ++i)
    {
      const std::size_t p = index(i, j);
      const Eigen::Vector2d x_end = position(i, j);
      if (x_end.squaredNorm() >= a2)
        leavePatch(p);
      else if (!adheres(arc_maps_, p, start(i, j), x_end, 0, count, step))
      {
        arc_stepping_[stepping++] = p;
        continue;
      }
      work += kBristleWork;
    }
  long pool = work_budget_ - work_ - afterStepsWork() - work;
  bool enough = true;
  const Coupling coupling(-kin.psi_dot, step);
  int level = count;  // the substeps of the coarse level whose coupling, motion and maps are kept
  Coupling coarse = coupling;
  Eigen::Matrix2d Q_level = Q;
  Eigen::Vector2d c_level = c;
  for (std::size_t n = 0; n < stepping; ++n)
  {
    const std::size_t p = arc_stepping_[n];
    const long share = pool / (static_cast<long>(stepping - n) * kPointWork);
    const int substeps = share >= count ? count : static_cast<int>(std::max(1L, share));
    const bool full = substeps == count;
    if (!full && substeps != level)
    {
      level = substeps;
      const double h = dt / level;
      coarse = Coupling(-kin.psi_dot, h);
      Q_level = rotation(rate * h);
      c_level = rotationIntegral(rate, h) * kin.V_r;
      clear(coarse_maps_, level);
    }
    const double h = full ? step : dt / substeps;
    const int i = static_cast<int>(p % w_), j = static_cast<int>(p / w_);
    const Eigen::Vector2d x_end = position(i, j);
    Eigen::Vector2d x = start(i, j);
    long used = 0;
    for (int k = 0; k < substeps; ++k)
    {
      if (k > 0 && adheres(full ? arc_maps_ : coarse_maps_, p, x, x_end, k, substeps, h))
      {
        used += kBristleWork;
        break;
      }
      const Eigen::Vector2d next =
          k + 1 == substeps ? x_end : Eigen::Vector2d(full ? Q * x - c : Q_level * x - c_level);
      substepBristle(kin, cap, full ? coupling : coarse, p, x, next, h);
      used += kPointWork;
      ++visits;
      x = next;
    }
    if (!full)
    {
      enough = false;
      if (inside_[p])
        step_error_[p] = 3.0 * p_.mu * cap.qz(x_end.squaredNorm()) / p_.k;
    }
    pool -= used;
    work += used;
  }
  work_ += work;
  // (cut short, what it would have taken: every bristle it stepped at every substep, so that auto does not read a cut
  // update as a cheap one)
  const double wanted = enough ? static_cast<double>(visits) : static_cast<double>(stepping) * count;
  arc_visit_share_ = wanted / (static_cast<double>(count) * w_ * w_);
  return enough;
}

bool BrushTransient::arcStaysInside(const ContactKinematics& kin, const FrictionCap& cap, const Eigen::Vector2d& u,
                                    const Eigen::Vector2d& x, const Eigen::Vector2d& x_end, double tau) const
{
  // The arc from x to x_end (an angle theta = |omega_gamma| tau <= pi / 2) lies within its sagitta, (L / 2) tan(theta /
  // 4) for a chord L, of the chord, on which |x| is largest at an end: r_max bounds |x| along it, and the bound
  // mu q_z / k is least there (q_z falls with r). In the coupling's frame (arcMap) |u| grows by at most the drive's
  // norm, |V_s| + |omega_z| r_max, over the time. Where that reach stays below the least bound, no onset.
  const double L = (x_end - x).norm(), theta = std::abs(kin.omegaGamma()) * tau;
  const double r_max = std::max(x.norm(), x_end.norm()) + 0.5 * L * std::tan(0.25 * theta);
  if (!(r_max < p_.a))
    return false;
  const double bound = p_.mu * cap.qz(r_max * r_max) / p_.k;
  const double reach = u.norm() + tau * (kin.V_s.norm() + std::abs(kin.omega_z) * r_max);
  return reach < (1.0 - 1e-9) * bound;
}

const BrushTransient::ArcMap& BrushTransient::arcMap(std::vector<ArcMap>& maps, const ContactKinematics& kin, int k,
                                                    int count, double step) const
{
  // An adhering bristle along its arc over tau (the docs' closed form, checked against these substeps: their difference
  // falls as their length cubed). In the frame turning with the coupling, v = R(psi_dot t) u, eq. 31's
  // du/dt = w - A_psi_dot u is dv/dt = R(psi_dot t) w(x(t)), with x(t) = R(omega_gamma t) x0 - S(omega_gamma, t) V_r,
  // w = -V_s - omega_z J x and S(alpha, t) the integral of R(alpha s) over [0, t]; integrated,
  //   u(tau) = R(-psi_dot tau) (u0 - S(psi_dot, tau) V_s - omega_z J S(psi_dot + omega_gamma, tau) x0
  //                              + omega_z J W V_r),   W = Int_0^tau R(psi_dot s) S(omega_gamma, s) ds,
  // affine in u0 and x0 with the same matrices for every bristle: u = A u0 - C x0 + d.
  ArcMap& m = maps[k];
  if (m.ready)
    return m;
  const double tau = (count - k) * step, psi_dot = kin.psi_dot, rate = kin.omegaGamma();
  const Eigen::Matrix2d J = (Eigen::Matrix2d() << 0.0, -1.0, 1.0, 0.0).finished();
  // W by Gauss-Legendre's five-point rule on panels that turn by at most half a radian (exact to rounding there)
  const numerics::GaussLegendre& rule = numerics::gaussLegendre(5);
  const int panels = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(psi_dot), std::abs(rate)) * tau / 0.5)));
  const double width = tau / panels;
  Eigen::Matrix2d W = Eigen::Matrix2d::Zero();
  for (int q = 0; q < panels; ++q)
    for (int n = 0; n < rule.m; ++n)
    {
      const double s = (q + 0.5 * (1.0 + rule.x[n])) * width;
      W += 0.5 * rule.w[n] * width * rotation(psi_dot * s) * rotationIntegral(rate, s);
    }
  m.A = rotation(-psi_dot * tau);
  m.C = kin.omega_z * m.A * J * rotationIntegral(psi_dot + rate, tau);
  m.d = m.A * (-(rotationIntegral(psi_dot, tau) * kin.V_s) + kin.omega_z * J * W * kin.V_r);
  m.ready = true;
  return m;
}

void BrushTransient::coulombStep(const ContactKinematics& kin, const FrictionCap& cap, const Coupling& coupling,
                                 std::size_t p, const Eigen::Vector2d& x_start, const Eigen::Vector2d& x1, double t,
                                 bool was_sliding)
{
  // The bristle as if it adhered over the step (eq. 1 with v_s = 0: the drive at the midpoint, the turn coupling's
  // rotation exact), then scaled back onto the bound where it would pass it: the implicit (backward Euler) step of eq.
  // (4b), the "return mapping". A sliding bristle thereby turns towards the drive by the angle its tip moves and
  // re-adheres wherever the trial falls inside the bound; u stays continuous, so no onset jumps (jump_ stays 0).
  const auto trial = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double dt) {
    return coupling(u, drive(kin, 0.5 * (a + b)), dt);
  };
  const auto bound = [&](const Eigen::Vector2d& x) { return p_.mu * cap.qz(x.squaredNorm()) / p_.k; };
  Eigen::Vector2d& u = u_[p];
  const Eigen::Vector2d u0 = u;
  const double over_start = u0.norm() - bound(x_start);  // <= 0 if it adhered
  const Eigen::Vector2d adhering = trial(u0, x_start, x1, t);
  u = adhering;
  const FrictionCap::Result r = cap.apply(u, x1, adhering);
  const double travel = (x1 - x_start).norm();
  if (!r.sliding)
    slip_travel_[p] = INFINITY;
  else if (was_sliding && over_start >= -1e-15 * bound(x_start))
    slip_travel_[p] += travel;
  else
  {
    // onset in this substep: where |u| - bound crossed zero, linearly between its start and end values
    const double over_end = adhering.norm() - p_.mu * r.q_z / p_.k;
    const double before = over_start < 0.0 && over_end > over_start ? -over_start / (over_end - over_start) : 0.0;
    slip_travel_[p] = (1.0 - before) * travel;
  }
  jump_[p].setZero();
  // Where it slides, the same over two half steps: the first-order method's error is twice their difference, and their
  // Richardson combination 2 u_half - u_one, put back on the bound, is second order. The first-order difference bounds
  // what the combination leaves; a direction error made sliding shrinks by the projection's ratio f / |trial| at each
  // later sliding step, and adhesion carries it unchanged.
  if (r.sliding)
  {
    const Eigen::Vector2d x_half = 0.5 * (x_start + x1);
    Eigen::Vector2d half = trial(u0, x_start, x_half, 0.5 * t);
    cap.apply(half, x_half, half);
    half = trial(half, x_half, x1, 0.5 * t);
    cap.apply(half, x1, half);
    const double n = adhering.norm(), b = p_.mu * r.q_z / p_.k;
    // the combination's own error is smaller than the first-order one by a further power of the step's expansion
    // parameter, the tip's motion over the bound
    const double theta = b > 0.0 ? std::min(1.0, (adhering - u0).norm() / b) : 1.0;
    step_error_[p] = step_error_[p] * (n > 0.0 ? std::min(1.0, b / n) : 1.0) + 2.0 * theta * (u - half).norm();
    const Eigen::Vector2d combined = 2.0 * half - u;
    const double c = combined.norm();
    if (c > 0.0)
      u = b / c * combined;
  }
  inside_[p] = 1;
  sliding_[p] = r.sliding;
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

Eigen::Vector2d BrushTransient::headingAt(const Eigen::Vector2d& x) const
{
  const Eigen::Vector2d v = Eigen::Vector2d(-omega_gamma_ * x.y(), omega_gamma_ * x.x()) - V_r_;
  return v.squaredNorm() > 0.0 ? v.normalized() : Eigen::Vector2d::Zero();
}

BrushTransient::Motion BrushTransient::motionAt(const Eigen::Vector2d& x, const Eigen::Vector2d& e) const
{
  // along this bristle's motion: how far the patch edge lies ahead and behind, and which lattice neighbour is upstream
  // (the lattice axis nearest the motion)
  Motion m;
  m.e = e;
  if (e.squaredNorm() > 0.0)
  {
    const double b = x.dot(e), c = x.squaredNorm() - p_.a * p_.a, root = std::sqrt(std::max(0.0, b * b - c));
    m.ahead = -b + root;
    m.behind = b + root;
    const Eigen::Vector2d l = R_.transpose() * e;  // the motion in lattice axes
    if (std::abs(l.x()) >= std::abs(l.y()))
      m.di = l.x() > 0.0 ? -1 : 1;
    else
      m.dj = l.y() > 0.0 ? -1 : 1;
  }
  return m;
}

Eigen::Vector2d BrushTransient::cellSum(int i, int j, const Motion& m, int k, double& weight) const
{
  // the cell, a strip of length h along the motion (2h on a sub-lattice): the part past the edge (or short of it), and
  // the part upstream of the onset of sliding, which still holds the deflection before the jump
  const std::size_t p = index(i, j);
  const Eigen::Vector2d& u = u_[p];
  const bool slides = sliding_[p];
  const double h = k == 0 ? h_ : 2.0 * h_;
  weight = 1.0;
  if (m.ahead <= h)
    weight += m.ahead / h - 0.5;
  if (m.behind <= h)
    weight += m.behind / h - 0.5;
  Eigen::Vector2d cell = weight * u;
  // a jump in space (not in time, as at standstill): the upstream neighbour on this lattice still adheres
  const int step = k == 0 ? 1 : 2, ui = i + step * m.di, uj = j + step * m.dj;
  if (slides && slip_travel_[p] < h && (m.di != 0 || m.dj != 0) && ui >= 0 && uj >= 0 && ui < w_ && uj < w_ &&
      inside_[index(ui, uj)] && !sliding_[index(ui, uj)])
    cell += (0.5 - slip_travel_[p] / h) * jump_[p];
  // the first cell from the leading edge, sliding: between its onset and the edge the bristle adhered, growing from 0
  // to the deflection before the jump, u + jump (half of it on average) instead of u. Unresolved, that ramp was a
  // first-order error where the adhesion zone is shorter than a spacing (stiff bristles; with the uniform pressure the
  // bound does not vanish at the edge: 0.1 % of mu F_z at resolution 128)
  else if (slides && m.behind <= h && slip_travel_[p] < m.behind)
    cell += (m.behind - slip_travel_[p]) / h * 0.5 * (jump_[p] - u);
  // the last cell before the trailing edge, adhering: where the bound falls below |u| within it, the bristle slides on
  // it (trailingLayer). That layer is (|u| / c)^m a / 2 wide (f^2 = t^m, c the bound at the centre); where it is
  // narrower than a spacing its error is one no spacing above its width reduces, and the sub-lattices, which make the
  // same one, did not see it: with the Hertzian pressure sweep seed 9018's robot (a = 7.8 mm, a layer of 40 um) stood
  // 7e-5 of mu F_z off the steady forces at every resolution from 128 to 400, up to 1.4 times the estimate; with the
  // parabolic one a robot of slips of 6e-4 (a layer of 2 um) 0.5 % of its forces off at every resolution from 64 to 512,
  // up to 1.6 times the estimate. (A sliding bristle there is on the bound, as q_z: the sum's normalisation to the rows'
  // load corrects its cell.)
  if (!slides && m.ahead <= h)
    cell += trailingLayer(position(i, j), u, m) / h;
  return cell;
}

Eigen::Vector2d BrushTransient::trailingLayer(const Eigen::Vector2d& x, const Eigen::Vector2d& u, const Motion& m) const
{
  const double un = u.norm();
  if (p_.pressure == PressureDistribution::Uniform || !(un > 0.0) || !(m.ahead > 0.0))
    return Eigen::Vector2d::Zero();
  const bool parabolic = p_.pressure == PressureDistribution::Parabolic;
  // along the motion back from the edge x_e = x + ahead e, at distance d: t = 1 - |x_e - d e|^2 / a^2 = g1 d + g2 d^2
  const double inv_a2 = 1.0 / (p_.a * p_.a);
  const Eigen::Vector2d x_e = x + m.ahead * m.e;
  const double g1 = 2.0 * x_e.dot(m.e) * inv_a2, g2 = -inv_a2;
  const double c = p_.mu / p_.k * p_.qz(0.0);  // the bound at the centre
  if (!(g1 > 0.0) || !(c > 0.0))
    return Eigen::Vector2d::Zero();
  // the layer: from the edge to where the bound c f(t) is |u| (t = (|u| / c)^(2 / m)), at most to the bristle (the
  // deflection taken as u throughout: its growth over a spacing is the sum's own first-order error)
  const double t_u = parabolic ? un / c : (un / c) * (un / c);
  double d = m.ahead;
  const double disc = g1 * g1 + 4.0 * g2 * t_u;
  if (disc >= 0.0)
    d = std::min(d, 2.0 * t_u / (g1 + std::sqrt(disc)));
  // the bound's integral over it: parabolic exactly; Hertzian with d' = d v^2 (its square root at the edge becomes
  // smooth), c d^1.5 2 int_0^1 v^2 sqrt(g1 + g2 d v^2) dv by Gauss-Legendre's five points
  double integral = c * d * d * (0.5 * g1 + g2 * d / 3.0);
  if (!parabolic)
  {
    static constexpr double kNodes[5] = { 0.04691007703066800, 0.23076534494715845, 0.5, 0.76923465505284155,
                                          0.95308992296933200 };
    static constexpr double kWeights[5] = { 0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                            0.23931433524968324, 0.11846344252809454 };
    double sum = 0.0;
    for (int n = 0; n < 5; ++n)
    {
      const double v2 = kNodes[n] * kNodes[n];
      sum += kWeights[n] * v2 * std::sqrt(std::max(0.0, g1 + g2 * d * v2));
    }
    integral = 2.0 * c * d * std::sqrt(d) * sum;
  }
  // there the bristle lies on the bound: along u (eq. 4b's direction is continuous at the onset and barely turns in so
  // thin a layer) or, under the rigid law, along the drive
  Eigen::Vector2d e = u / un;
  if (p_.sliding_law == SlidingLaw::Rigid && have_last_kin_)
  {
    const Eigen::Vector2d w(-last_kin_.V_s.x() + last_kin_.omega_z * x_e.y(),
                            -last_kin_.V_s.y() - last_kin_.omega_z * x_e.x());
    if (w.squaredNorm() > 0.0)
      e = w.normalized();
  }
  // The layer reaches the bristle as it nears its bound, where it is the sliding one's case, left to the normalisation
  // as theirs. Parabolic, the correction fades linearly to that (in full, the default robot's cells next to the edge,
  // most of them near their bound, moved the sub-lattices' sums apart: the recorded manoeuvre's flags rose by half);
  // Hertzian, in full (faded, half of seed 9018's error stayed, 0.8 of the estimate at resolution 448 and rising)
  const double share = parabolic ? std::max(0.0, 1.0 - d / m.ahead) : 1.0;
  return share * (integral * e - d * u);
}

BrushForces BrushTransient::forces() const
{
  if (forces_kept_)
    return kept_forces_;
  double fixed = 0.0, spread = 0.0;
  BrushForces f = sums(fixed, spread);
  f.error_estimate = estimate(fixed, spread) + cutShortError();
  return f;
}

void BrushTransient::gather(LatticeSums& g) const
{
  // the cells that differ between the lattice and its sub-lattices (near the edge or an onset) by lattice, into g; the
  // plain cells, the same on both, by sub-lattice only (the full lattice's are their sum)
  Eigen::Vector2d F_plain[5];
  double M_z_plain[5] = {}, load_plain[5] = {};
  int count_plain[5] = {};
  for (int k = 0; k < 5; ++k)
  {
    g.F[k].setZero();
    F_plain[k].setZero();
  }
  const FrictionCap cap(p_);
  const double mu_over_k = p_.mu / p_.k;
  // Whatever the motion, a bristle within a - 2h of the centre lies further than a sub-lattice cell (2h) from the edge
  // ahead and behind (weight 1, no ramp from the edge); the upstream neighbour matters only to a bristle that slid less
  // than that far: elsewhere the motion is not needed.
  const double inner = p_.a - 2.0 * h_, inner2 = inner > 0.0 ? inner * inner : -1.0;
  const Eigen::Vector2d along = rowStep();
  const bool turning = omega_gamma_ != 0.0;
  const Eigen::Vector2d heading = turning ? Eigen::Vector2d::Zero() : headingAt(Eigen::Vector2d::Zero());
  for (int j = 0; j < w_; ++j)
  {
    const Eigen::Vector2d first = rowStart(j);
    const std::size_t row = index(0, j);
    for (int i = 0; i < w_; ++i)
    {
      const std::size_t p = row + i;
      if (!inside_[p])
        continue;
      const Eigen::Vector2d x = first + i * along, &u = u_[p];
      const bool slides = sliding_[p];
      g.sliding += slides;
      const double r2 = x.squaredNorm(), q_z = cap.qz(r2);
      const double bound = mu_over_k * q_z;
      if (slides)
        g.utilisation2 = std::max(g.utilisation2, 1.0);
      else if (bound > 0.0)
        g.utilisation2 = std::max(g.utilisation2, u.squaredNorm() / (bound * bound));
      // plain: cellSum's weight is 1 and its cell u on both lattices, and the motion is not needed. Inside a - 2h only an
      // onset's jump changes the cell: one that did not jump (eq. 4b's are continuous) is plain however lately it began
      // to slide (spinning in place or parked a message rolls micrometres, and the bristles stayed "lately" for good)
      const bool plain = !(r2 > inner2 || (slides && slip_travel_[p] < 2.0 * h_ && jump_[p].squaredNorm() > 0.0));
      const int sub = 1 + (i & 1) + 2 * (j & 1);
      if (plain)
      {
        F_plain[sub] += u;
        M_z_plain[sub] += x.x() * u.y() - x.y() * u.x();
        load_plain[sub] += q_z;
        g.step_error += step_error_[p];
        ++count_plain[sub];
        continue;
      }
      const Motion motion = motionAt(x, turning ? headingAt(x) : heading);
      for (int k : { 0, sub })
      {
        double weight = 1.0;
        const Eigen::Vector2d cell = cellSum(i, j, motion, k, weight);
        g.F[k] += cell;
        g.M_z[k] += x.x() * cell.y() - x.y() * cell.x();
        g.load[k] += weight * q_z;
        if (k == 0)
          g.step_error += weight * step_error_[p];
        ++g.count[k];
      }
    }
  }
  for (int k = 1; k <= 4; ++k)
  {
    g.F[0] += F_plain[k];
    g.M_z[0] += M_z_plain[k];
    g.load[0] += load_plain[k];
    g.count[0] += count_plain[k];
    g.F[k] += F_plain[k];
    g.M_z[k] += M_z_plain[k];
    g.load[k] += load_plain[k];
    g.count[k] += count_plain[k];
  }
}

bool BrushTransient::adhesionResponse(AdhesionResponse& response, long& work, double band) const
{
  // F = k sum u dA, M_z = k sum (x_x u_y - x_y u_x) dA (sums()); an adhering bristle's u' = w with
  // dw / d(V_s,x, V_s,y, omega_z) = [[-1, 0, x_y], [0, -1, -x_x]] = -B^T, B = [I; (-x_y, x_x)] (eq. 1, drive()), so that
  // it moves (F_x, F_y, M_z) by -B B^T; dA as the sums weigh the cells. One held by its bound (sliding, or adhering
  // within `band` of it) moves only along it, by the drive's part across its normal n = u / |u| (eq. 4b on the bound):
  // -B (I - n n^T) B^T = -B B^T + c c^T with c = B n.
  const FrictionCap cap(p_);
  double load = 0.0, S0 = 0.0, S2 = 0.0;
  Eigen::Vector2d S1 = Eigen::Vector2d::Zero(), F = Eigen::Vector2d::Zero();
  Eigen::Matrix3d held = Eigen::Matrix3d::Zero();  // sum of c c^T
  // the roll's share, per metre along each direction e_j: the adhering field moves with the roots, its moment by
  // e_j x F (a sliding bristle stays on the bound the patch's pressure sets: its force stays put); and the bristles
  // within a spacing of the rim each leave with the chance (e_j . n)+ / h, taking (u, x x u) with them
  constexpr int kN = AdhesionResponse::kDirections;
  double lost_x[kN] = {}, lost_y[kN] = {}, lost_m[kN] = {};  // (plain arrays: the loop below vectorises)
  double e_x[kN], e_y[kN];
  for (int j = 0; j < kN; ++j)
  {
    e_x[j] = AdhesionResponse::directions()[j].x();
    e_y[j] = AdhesionResponse::directions()[j].y();
  }
  const double rim_band = p_.a - h_, mu_over_k = p_.mu / p_.k;
  long rim = 0;  // points in the band, each about 10 units more (callgrind: about 470 instructions, 32 directions)
  forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool sliding) {
    const double r2 = x.squaredNorm();
    load += cap.qz(r2);
    if (r2 > rim_band * rim_band)
    {
      ++rim;
      const double m = x.x() * u.y() - x.y() * u.x();
      const double r = std::sqrt(r2), n_x = x.x() / r, n_y = x.y() / r;
      for (int j = 0; j < kN; ++j)
      {
        const double out = std::max(0.0, n_x * e_x[j] + n_y * e_y[j]);
        lost_x[j] += out * u.x();
        lost_y[j] += out * u.y();
        lost_m[j] += out * m;
      }
    }
    if (!sliding)
      F += u;  // (the roll moves the adhering field with the roots)
    const double un = u.norm(), bound = mu_over_k * cap.qz(r2);
    // (undeformed inside the patch, as a lattice no motion has reached yet, or one whose noise was held: it adheres, and
    // the noise first moves it with the drive, in whichever direction; a band wider than its bound does not hold it)
    if ((sliding || (band > 0.0 && un > bound - band)) && !(un == 0.0 && bound > 0.0))
    {
      // held by its bound (the noise's reflected walk reaches it within the band, StandstillCovariance::band)
      if (!(un > 0.0))
        return;  // at the rim, with no bound: nothing moves it
      const Eigen::Vector2d n = u / un;
      const Eigen::Vector3d c(n.x(), n.y(), x.x() * n.y() - x.y() * n.x());
      held += c * c.transpose();
    }
    S0 += 1.0;
    S1 += x;
    S2 += r2;
  });
  work = sumsWork() + rim * 10;
  response = AdhesionResponse{};
  if (!(load > 0.0))
    return true;  // no load: no forces to move
  const double kdA = p_.k * rows_->load(0, p_.F_z) / load;
  response.drive << -S0, 0.0, S1.y(),  //
      0.0, -S0, -S1.x(),               //
      S1.y(), -S1.x(), -S2;
  response.drive = kdA * (response.drive + held);
  for (int j = 0; j < kN; ++j)
    response.roll.col(j) = kdA * (Eigen::Vector3d(0.0, 0.0, e_x[j] * F.y() - e_y[j] * F.x()) -
                                  Eigen::Vector3d(lost_x[j], lost_y[j], lost_m[j]) / h_);
  return true;
}

BrushForces BrushTransient::sums(double& fixed, double& spread) const
{
  fixed = spread = 0.0;
  // The lattice sum, and the same over each of the four sub-lattices of twice the spacing (the parities of
  // the lattice indices): how far those move from the full sum bounds the error. An error C h^p with p >= 1
  // makes the difference (2^p - 1) C h^p, at least the error itself; kSpreadFactor times it covers the irregular
  // part that the cells cut by the patch edge and by the onsets add (measured over noisy histories at random points,
  // test_brush_transient: without a factor the estimate fell short at 0.2-0.5 % of them, by up to 2.7x).
  BrushForces f;
  LatticeSums g;
  gather(g);
  const auto& F = g.F;
  const auto& M_z = g.M_z;
  const auto& load = g.load;
  const auto& count = g.count;
  if (count[0] == 0)
    return f;
  // Cell weight normalised so that the lattice sum of q_z is F_z: every bristle obeys |q| <= mu q_z, so
  // |F_t| <= mu F_z then holds exactly. Where the rows are corrected across (TransientRows), the sum of q_z is
  // normalised to the same rows' exact integrals of q_z instead: the normalisation then corrects the cells along the
  // rows (cut by the edge) and leaves across them to the correction, which would otherwise count the midpoint rule's
  // error across the rows twice (0.1 % of mu F_z at resolution 128 with the uniform pressure). Without load, the
  // patch area over the bristle count.
  const auto weight = [&](int k) {
    const double total = rows_->load(k, p_.F_z);
    return load[k] > 0.0 ? total / load[k] : boost::math::double_constants::pi * p_.a * p_.a / std::max(count[k], 1);
  };
  const auto sum = [&](int k) {
    BrushForces g;
    const double dA = weight(k);
    g.F_x = p_.k * F[k].x() * dA;
    g.F_y = p_.k * F[k].y() * dA;
    g.M_z = p_.k * M_z[k] * dA;
    const Eigen::Vector3d c = rows_->correction(k, p_.a);
    g.F_x += c.x();
    g.F_y += c.y();
    g.M_z += c.z();
    return g;
  };
  BrushForces full = sum(0);
  // the corrections may carry the sum past mu F_z, which the exact answer never passes: the nearest point on that
  // (convex) circle is never further from it
  const double norm = std::hypot(full.F_x, full.F_y), limit = p_.mu * p_.F_z;
  if (norm > limit)
  {
    full.F_x *= limit / norm;
    full.F_y *= limit / norm;
  }
  f.F_x = full.F_x;
  f.F_y = full.F_y;
  f.M_z = full.M_z;
  f.sliding_fraction = static_cast<double>(g.sliding) / count[0];
  f.max_utilisation = std::sqrt(g.utilisation2);
  const double scale = p_.mu * p_.F_z;
  fixed = streak_estimate_;
  if (scale > 0.0)
    fixed += p_.k * g.step_error * weight(0) / scale;
  fixed += rows_->error(p_.pressure);
  spread = 0.0;
  if (scale > 0.0)
    for (int k = 1; k <= 4; ++k)
    {
      const BrushForces g = count[k] > 0 ? sum(k) : BrushForces{};
      spread = std::max(spread, kSpreadFactor *
                                          std::max({ std::abs(g.F_x - full.F_x), std::abs(g.F_y - full.F_y),
                                                     std::abs(g.M_z - full.M_z) / p_.a }) / scale);
    }
  f.error_estimate = fixed + spread;
  return f;
}

}  // namespace sphere_contact_estimator
