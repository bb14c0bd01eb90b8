#include "sphere_contact_estimator/core/brush/brush_auto.h"

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// The brush library's private rooms
#include "rolling_frame.h"
#include "steady_lag.h"

namespace sphere_contact_estimator
{
namespace
{
BrushParameters withResolution(BrushParameters p, int n)
{
  p.resolution = n;
  return p;
}

// The largest of |dF_x|, |dF_y| and |dM_z| / a, as a fraction of mu F_z.
double distance(const BrushForces& a, const BrushForces& b, const BrushParameters& p)
{
  const double scale = p.mu * p.F_z;
  if (!(scale > 0.0))
    return 0.0;
  return std::max({ std::abs(a.F_x - b.F_x), std::abs(a.F_y - b.F_y), std::abs(a.M_z - b.M_z) / p.a }) / scale;
}

// The longest travel through the patch from the leading to the trailing edge: 2a on straight paths; an arc
// about a tilting centre at |R_gamma| >= a is at most pi/2 times its chord (the half circle), so pi a.
double longestPath(const BrushParameters& p)
{
  return p.tilt ? boost::math::double_constants::pi * p.a : 2.0 * p.a;
}
}  // namespace

BrushAuto::BrushAuto(const BrushParameters& parameters)
  : BrushModel(parameters), linear_(parameters), steady_(parameters), lag_(std::make_unique<SteadyLag>(2.0 * parameters.a, parameters.pressure))
{
  transient_resolution_ = configured_resolution_ = std::min(p_.resolution, kMaxTransientResolution);
  transient_ = std::make_unique<BrushTransient>(withResolution(p_, transient_resolution_));
  // Storage for twice the resolution in both lattices (this one, and the spare a finer one starts in): refining up to
  // there, taking over and coarsening back size nothing in a message. (The first refinement had sized it there: from 32
  // to 64, 1.0-1.2 ms of fresh pages in one message, uncounted. At most 2 x 2 MB, at kMaxTransientResolution.) Beyond,
  // the storage a lattice grows is counted (BrushTransient::growthWork).
  const int finer = std::min(2 * configured_resolution_, kMaxTransientResolution);
  if (finer > configured_resolution_)
  {
    transient_->reserve(finer);
    spare_ = std::make_unique<BrushTransient>(withResolution(p_, finer));
  }
}

BrushAuto::~BrushAuto() = default;

void BrushAuto::retire(std::unique_ptr<BrushTransient>& lattice)
{
  if (lattice && (!spare_ || spare_->pointCapacity() < lattice->pointCapacity()))
    spare_ = std::move(lattice);
  lattice.reset();
}

void BrushAuto::resizeTransient(int resolution)
{
  const std::size_t needed = BrushTransient::points(resolution);
  if (spare_ && resolution != transient_->lastResolution() && transient_->pointCapacity() < needed &&
      spare_->pointCapacity() > transient_->pointCapacity())
    transient_->swapStorage(*spare_);  // setParameters resets the state at another resolution: only storage changes
  transient_->setParameters(withResolution(p_, resolution));
}

long BrushAuto::growthWork(int resolution, bool finer) const
{
  // transient_ grows in the larger of its own storage and spare_'s (resizeTransient), a finer lattice in spare_'s, or
  // new (latticeAt)
  const std::size_t spare = spare_ ? spare_->pointCapacity() : 0;
  return BrushTransient::growthWork(BrushTransient::points(resolution),
                                    finer ? spare : std::max(transient_->pointCapacity(), spare));
}

std::unique_ptr<BrushTransient> BrushAuto::latticeAt(int resolution)
{
  if (!spare_)
    return std::make_unique<BrushTransient>(withResolution(p_, resolution));  // the first: it allocates
  std::unique_ptr<BrushTransient> lattice = std::move(spare_);
  lattice->renew(withResolution(p_, resolution));
  return lattice;
}

void BrushAuto::rotateFrame(double alpha)
{
  transient_->rotateFrame(alpha);
  if (finer_)
    finer_->rotateFrame(alpha);
  // a physical vector in the turned axes (x' = R(-alpha) x)
  const double c = std::cos(alpha), s = std::sin(alpha);
  const auto turned = [c, s](double x, double y) { return Eigen::Vector2d(c * x + s * y, -s * x + c * y); };
  lag_->rotate(alpha);
  for (BrushForces* f : { &offset_, &last_raw_, &warm_forces_ })
  {
    const Eigen::Vector2d F = turned(f->F_x, f->F_y);
    f->F_x = F.x();
    f->F_y = F.y();
  }
  // and the last rolling inputs, which a warm start rolls: velocities (unturned, a warm start after a heading jump
  // rolled the patch along the old direction's coordinates in the new axes)
  for (Eigen::Vector2d* v : { &last_rolling_.V_r, &last_rolling_.V_s })
    *v = turned(v->x(), v->y());
}

double BrushAuto::effectiveTarget() const
{
  // Below the noise: an answer within a fraction f of the forces' own standard deviation s adds to their spread at
  // most f s, or in quadrature (an error independent of the noise) a share sqrt(1 + f^2) - 1 of it.
  return std::max(p_.accuracy_target, p_.auto_noise_fraction * input_spread_);
}

void BrushAuto::reset()
{
  if (transient_resolution_ != configured_resolution_)
  {
    transient_resolution_ = configured_resolution_;
    resizeTransient(transient_resolution_);
  }
  pending_resolution_ = 0;
  budget_cut_ = 0;
  easy_travel_ = 0.0;
  steady_short_ = false;
  transient_->reset();
  retire(finer_);
  in_transient_ = false;
  probation_ = false;
  steady_distance_ = 0.0;
  lag_->reset();
  have_check_ = false;
  lag_travel_ = 0.0;
  check_work_ = 0;
  checks_short_ = 0;
  have_rolling_ = false;
  offset_ = BrushForces{};
  last_raw_ = BrushForces{};
  warm_entered_ = false;
  rolled_before_ = false;
  answered_ = false;
}

bool BrushAuto::stepLag(const Slips& s, const Eigen::Vector2d& sigma, const RollingFrame& frame, double target,
                        bool steady_exists, double travel, long max_work)
{
  // The linear forces where they are within a quarter of the target of the steady ones, split into what the
  // slips and what the spin drive (SteadyLag weighs each by its own memory; for adhesion the lag is then
  // exact); else the steady model to a quarter of the target, kept for the answer. The lag needs the forces
  // that actually change: the linear force clipped at mu F_z, or any simple saturation law, missed a robot
  // accelerating out of a spinning skid (the force fell by a tenth of mu F_z per message while the clipped one
  // stood still), measured over random histories.
  steady_cached_ = false;
  const auto toPatch = [&](double F_x, double F_y, double M_z) {
    BrushForces f;
    f.F_x = F_x;
    f.F_y = F_y;
    frame.forcesToPatch(f);
    return Eigen::Vector3d(f.F_x, f.F_y, M_z / p_.a);
  };
  Eigen::Vector3d slip, spin = Eigen::Vector3d::Zero();
  bool split = false, ran_out = false;
  const double limit = p_.mu * p_.F_z;
  // which drive made the change since the last step, in the linear theory's forces
  const Eigen::Vector2d d_sigma = sigma - last_lag_sigma_;
  const double d_slip = linear_.C_sigma() * d_sigma.norm(), d_spin = linear_.C_phi() * std::abs(s.phi - last_lag_phi_);
  const double spin_share = d_slip + d_spin > 0.0 ? d_spin / (d_slip + d_spin) : 1.0;
  last_lag_sigma_ = sigma;
  last_lag_phi_ = s.phi;
  if (!lagNeedsSteady(steady_exists, target))
  {
    // eqs. 61-62 by drive, scaled back together onto the friction circle like BrushLinear (then not split)
    const Eigen::Vector2d F_slip = linear_.C_sigma() * sigma;
    const double F_spin = linear_.C_phi() * s.phi;
    const double M_slip = -linear_.C_Msigma_y() * sigma.y(), M_spin = linear_.C_Mphi() * s.phi;
    const double norm = std::hypot(F_slip.x(), F_slip.y() + F_spin);
    const double scale = norm > limit && norm > 0.0 ? limit / norm : 1.0;
    slip = scale * toPatch(F_slip.x(), F_slip.y(), M_slip);
    spin = scale * toPatch(0.0, F_spin, M_spin);
    split = scale == 1.0;
  }
  else
  {
    BrushSteady::Stats stats;
    steady_cache_ = steady_.evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi, 0.25 * target, &stats, max_work);
    spent_ += stats.work;
    cost_ += kSteadyPathCost * stats.paths;
    steady_cached_ = true;
    ran_out = (steady_cache_.flags & brush_flags::kAccuracyNotMet) != 0;
    check_work_ = ran_out ? 2 * std::max(stats.work, 1L) : stats.work;
    slip = toPatch(steady_cache_.F_x, steady_cache_.F_y, steady_cache_.M_z);
  }
  // Under eq. (4b) a sliding bristle's direction carries memory too (it turns towards the drive no faster than its tip
  // moves): the forces then follow a change of the slips as slowly as the slowest kernel, not as the slips' own
  // (measured on random histories: the slips' kernel fell 20 % short on a ramp with tilt)
  const double share = p_.sliding_law == SlidingLaw::Coulomb && !split ? 1.0 : spin_share;
  lag_->step(slip, spin, split, share, travel, linear_bound_);
  return !ran_out;
}

BrushForces BrushAuto::steadyFamily(const Slips& s, const Eigen::Vector2d& sigma, double budget, BrushModelKind& model)
{
  steady_short_ = false;
  // the linear model's bound at the largest inputs the patch still remembers: a lagging state carries the
  // sliding of its past inputs, which the bound at the current ones may understate
  const double bound = std::max(linear_bound_, lag_->largestHeld());
  if (bound <= budget)
  {
    model = BrushModelKind::Linear;
    cost_ += kLinearCost;
    spent_ += BrushLinear::kWork;
    BrushForces f = linear_.evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi);
    f.error_estimate = std::max(f.error_estimate, bound);
    return f;
  }
  model = BrushModelKind::Steady;
  if (steady_cached_ && steady_cache_.error_estimate <= budget)
    return steady_cache_;  // evaluated for the lag, to a quarter of the target
  BrushSteady::Stats stats;
  const long room = remaining();
  BrushForces f = steady_.evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi, budget, &stats,
                                   std::min(BrushSteady::kMaxWork, room));
  spent_ += stats.work;
  cost_ += kSteadyPathCost * stats.paths;
  steady_short_ = (f.flags & brush_flags::kAccuracyNotMet) != 0;
  budget_held_ = budget_held_ || (steady_short_ && room < BrushSteady::kMaxWork);  // (not the solver's own limit)
  // the work budget spent before the target: the linear answer where its bound is the smaller
  const double linear_bound = std::max(linear_bound_, lag_->largestHeld());
  if ((f.flags & brush_flags::kAccuracyNotMet) && linear_bound < f.error_estimate)
  {
    model = BrushModelKind::Linear;
    spent_ += BrushLinear::kWork;
    f = linear_.evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi);
    f.error_estimate = std::max(f.error_estimate, linear_bound);
  }
  return f;
}

void BrushAuto::enterTransient(const ContactKinematics& kin, double dt)
{
  // Warm start: the bristles in the steady state of the last rolling inputs before this step (2.5 transits), so
  // the transient model takes over where the steady one was and then rolls this step under the new inputs; at
  // the finer resolution asked for last time, else at least the configured one (a coarsening was for the inputs of the
  // last visit, not these), or the finest whose warm start and step fit the work budget.
  int resolution = std::max({ transient_resolution_, pending_resolution_, configured_resolution_ });
  pending_resolution_ = 0;
  const double V = have_rolling_ ? last_rolling_.V_r.norm() : 0.0;
  const double warm = have_rolling_ ? 2.5 * longestPath(p_) / V : 0.0;
  const int wanted = resolution;
  // the cost of a lattice grows as its resolution cubed (points times substeps); each resolution predicted as the
  // lattice would stand there (predictWorkAt, the lattice as it is at its own), and only the one chosen sized: growing
  // the storage costs its fresh pages, which no prediction counts
  // (one halved from the one before is a lattice allocated afresh)
  const auto predicted = [&](int r, const ContactKinematics& k, double t) {
    const bool as_is = r == wanted && r == transient_->lastResolution();
    return as_is ? transient_->predictWork(k, t) : transient_->predictWorkAt(r, k, t);
  };
  while (resolution / 2 >= BrushTransient::kMinCoarsened &&
         (have_rolling_ ? predicted(resolution, last_rolling_, warm) : 0) + predicted(resolution, kin, dt) +
                 growthWork(resolution, false) >
             remaining())
    resolution /= 2;
  if (resolution != transient_->lastResolution())  // (transient_resolution_ is always the lattice's own)
  {
    spent_ += growthWork(resolution, false);
    resizeTransient(resolution);
  }
  transient_resolution_ = resolution;
  budget_cut_ = resolution < wanted ? wanted : 0;
  budget_held_ = budget_held_ || resolution < wanted;
  steady_short_ = false;
  transient_->reset();
  easy_travel_ = 0.0;
  in_transient_ = true;
  steady_distance_ = 0.0;
  // the warm start is the steady state of the last inputs, which the true state lagged by at most the lag then
  // (the steady family's answer accepted it); only renewed bristles forget that
  entry_error_ = last_lag_;
  if (have_rolling_)
  {
    // Even the coarsest lattice may not roll 2.5 transits within the budget: then as far as it can, and the bristles it
    // did not reach (their share of the patch: those that did not enter during the roll) may miss all of their
    // force, which the entry error carries until they renew.
    double roll = warm;
    const long whole = transient_->predictWork(last_rolling_, warm), step = transient_->predictWork(kin, dt);
    const long rounding = 2 * transient_->predictWork(last_rolling_, 0.0);  // a substep and the sums, rounded up
    const long room = remaining() - step - rounding;  // for the roll
    if (whole > room && whole > 0)
    {
      roll = warm * std::max(0.0, static_cast<double>(room) / static_cast<double>(whole));
      budget_held_ = true;  // a warm start short of its roll, whose bristles carry the entry error
      const double reached = std::min(1.0, V * roll / longestPath(p_));
      entry_error_ += 1.0 - reached;
    }
    if (roll > 0.0)
    {
      // Its prediction, and of the room beyond it the roll's share by travel against this step's (a bristle's sliding
      // steps grow with its path, up to a transit: predictSteps). A lattice just reset predicts its sliding steps from
      // its last visit's, none on the first: given only its prediction, the roll into the pivot of sweep seed 1014 (85
      // rad/m of spin) took none, each sliding bristle's path in one return mapping, its forces 0.36 of mu F_z from
      // that steady state (estimate 2.0); so did the first entries of seeds 1004, 1009 and 1022.
      const long predicted = std::min(transient_->predictWork(last_rolling_, roll), room);
      const double travel = std::min(V * roll, longestPath(p_)),
                   step_travel = std::min(kin.V_r.norm() * std::max(dt, 0.0), longestPath(p_));
      const double share = travel > 0.0 ? travel / (travel + step_travel) : 0.0;
      transient_->setWorkBudget(predicted + static_cast<long>(share * static_cast<double>(room - predicted)));
      const BrushForces rolled = transient_->update(last_rolling_, roll);
      spent_ += rolled.work;
      // The steady state of the last inputs only where every bristle in the patch entered during the roll and took every
      // sliding step it wanted (a roll cut short is not: above), and only where those inputs were the last update's,
      // which the last answer is of (its forces: the roll's answer, no work)
      warm_entered_ = V * roll >= longestPath(p_) && !(rolled.flags & brush_flags::kSubstepsTruncated) && rolled_before_;
      if (warm_entered_)
        warm_forces_ = latticeForces(*transient_);
    }
    cost_ += transientStepCost(transient_resolution_) * std::ceil(5.0 * transient_resolution_);
  }
}

BrushForces BrushAuto::update(const ContactKinematics& kin, const Slips& s, double dt)
{
  checkInput(kin, s, dt);
  spent_ = 0;
  budget_held_ = false;
  last_slips_ = s;
  const double target = target_ = effectiveTarget();
  const BrushModelKind before = last_model_;
  const int before_resolution = last_resolution_;
  const RollingFrame frame(s.defined ? s.epsilon : Eigen::Vector2d(0.0, 1.0));
  const Eigen::Vector2d sigma = s.defined ? frame.toRolling(s.sigma) : Eigen::Vector2d::Zero();

  const SteadyCheck check = checkSteady(kin, s, sigma, frame, dt, target);
  chooseFamily(kin, s, dt, check);
  BrushForces out;
  BrushModelKind model;
  int resolution = 0;
  if (in_transient_)
  {
    out = transientAnswer(kin, s, dt, target, resolution);
    model = BrushModelKind::Transient;
  }
  else
  {
    out = steadyFamily(s, sigma, target - check.lag, model);
    out.error_estimate += check.lag;
    frame.forcesToPatch(out);
    if (probation_)
      rollOnProbation(kin, s, dt);
  }
  carryAcrossSwitches(out, s, sigma, frame, dt, before, before_resolution, model, resolution);
  out.flags &= ~brush_flags::kLinearSaturated;  // auto never publishes a saturated linear answer as such
  out.flags &= ~brush_flags::kAccuracyNotMet;  // (its lattice's, against the configured target)
  out.flagAbove(target);
  if (budget_held_ && (out.flags & brush_flags::kAccuracyNotMet))
    out.flags |= brush_flags::kBudgetLimited;  // (what a larger work_budget would buy: the operator's to decide)
  last_model_ = model;
  last_resolution_ = resolution;
  answered_ = true;
  out.work = spent_;
  return out;
}

BrushAuto::SteadyCheck BrushAuto::checkSteady(const ContactKinematics& kin, const Slips& s,
                                              const Eigen::Vector2d& sigma, const RollingFrame& frame, double dt,
                                              double target)
{
  // Conditions under which a steady state describes the contact, and the lag of that state.
  steady_cached_ = false;
  SteadyCheck c;
  c.steady = s.defined;
  if (!s.defined)
  {
    lag_->reset();
    have_check_ = false;
    lag_travel_ = 0.0;
    checks_short_ = 0;
    return c;
  }
  if (p_.tilt && std::abs(s.phi_gamma) * p_.a > 1.0)
    c.steady = false;  // |R_gamma| < a: no steady state on an inner disc
  c.renewed = s.V_r * dt >= longestPath(p_);
  linear_bound_ = BrushLinear::errorBound(p_, sigma, s.phi, s.phi_gamma, s.phi_psi);
  // In the transient model the lag only decides when to leave it, which takes steady conditions held over a transit:
  // while they do not hold it is evaluated once the patch has rolled a quarter of its radius since the last time (the
  // lag then takes the changes and the travel since at once), not at every message of a fast stream. Once a check finds
  // them, at every message: a change taken at once is the inputs' net change since the last check, and the noise's
  // excursions between checks, which the state remembers, were missing from the lag the steady family left with
  // (scripts/stream_sweep.py seed 1062 at 1 kHz: a linear answer's error 1.2 times its estimate, beyond the reference's
  // own estimate, two messages after leaving).
  const double stride = have_check_ && last_check_.lag > kFarLag * kLeavingLag * target ? kFarLagStride : kLagStride;
  // (at most half of what is left: the answer's model needs the rest; in the transient model, what its lattices'
  // predicted steps leave, where that is less, less the steady solver's granularity, the path under way when it runs out:
  // a check that passed its room by 56 units left the lattice's predicted step 56 units short of what remained, and the
  // lattice was coarsened, test_brush_auto's pivot at 0.1 %; check_work_)
  long check_room = std::min(BrushSteady::kMaxWork, remaining() / 2);
  const bool evaluates = lagNeedsSteady(c.steady, target);
  if (in_transient_ && evaluates && !c.renewed)
  {
    const long lattices = transient_->predictWork(kin, dt) + (finer_ ? finer_->predictWork(kin, dt) : 0);
    check_room = std::min(check_room, remaining() - lattices - kWorkGranularity);
  }
  const double since = lag_travel_ + s.V_r * dt;
  // (waiting for room for a transit at most, or a few after checks that ran out of it, roomWait: a check that ran out
  // of half of what was left would otherwise wait for good, and leaving with it)
  const bool no_room = evaluates && check_work_ > check_room && since < roomWait() * p_.a;
  const bool within_stride = !last_check_.steady && since < stride * p_.a;
  if (in_transient_ && have_check_ && !c.renewed && (no_room || within_stride))
  {
    lag_travel_ += s.V_r * dt;
    c.lag = last_check_.lag;
    // that check found no steady conditions, and none are taken without a check of this message's lag (a verdict
    // carried between checks had also outlived its target, which follows the inputs' noise: the steady solver was then
    // asked for target - lag <= 0)
    c.steady = false;
    return c;
  }
  if (!in_transient_ && steady_short_ && evaluates)
  {
    // The steady family's last answer ran out of the budget before its target: the steady solver cannot finish within
    // it here, and a check would spend half of it on the same. No check: the transient model, whose lattice fits the
    // budget, answers, with all of it for its warm start. (Before, the budget's best steady answers went on, at
    // estimates of up to 14 mu F_z: a 48-mm patch with tilt under eq. 4b needs 2.2e5 units of the steady solver at any
    // target, and with the budget's 1e5 stream_sweep.py --set tilt=true seed 5009 answered F_y 0.3 against 4.8 N for
    // its first 11 messages.)
    lag_travel_ += s.V_r * dt;  // (the next check takes it)
    c.lag = last_check_.lag;
    c.steady = false;
    return c;
  }
  const double travel = s.V_r * dt + lag_travel_;
  lag_travel_ = 0.0;
  // the lag of the steady state behind the true one, from the changes of the steady forces
  const double limit = p_.mu * p_.F_z;
  // with tilt the paths are arcs about the tilting centre, longer than their chords: the central one by
  // (|R_gamma| / a) asin(a / |R_gamma|), up to pi / 2; the patch renews that much more slowly
  double stretch = 1.0;
  const double a_phi_gamma = std::abs(s.phi_gamma) * p_.a;
  if (p_.tilt && a_phi_gamma > 0.0)
    stretch = a_phi_gamma < 1.0 ? std::asin(a_phi_gamma) / a_phi_gamma : 0.5 * boost::math::double_constants::pi;
  const bool evaluated = stepLag(s, sigma, frame, target, c.steady, travel / stretch, std::max(check_room, 1L));
  c.lag = limit > 0.0 ? lag_->lag() / limit : 0.0;
  if (in_transient_)
    checks_short_ = evaluated ? 0 : std::min(checks_short_ + 1, kMaxChecksShort);
  if (!(c.lag <= kLeavingLag * target) || (in_transient_ && !evaluated))
    c.steady = false;  // (a check that ran out of its room in the transient model gives no verdict: it stays)
  last_check_ = c;
  have_check_ = true;
  return c;
}

void BrushAuto::chooseFamily(const ContactKinematics& kin, const Slips& s, double dt, const SteadyCheck& check)
{
  // the transient model is left only once the steady conditions have held for a transit (or one step rolled
  // it: every bristle then entered under these inputs, so the state is exactly the steady one)
  if (in_transient_ && check.steady)
  {
    steady_distance_ += s.V_r * dt;
    if (check.renewed || steady_distance_ >= longestPath(p_))
    {
      in_transient_ = false;  // its state is the steady one now
      retire(finer_);
      probation_ = true;
      probation_travel_ = 0.0;
    }
  }
  else if (in_transient_)
    steady_distance_ = 0.0;
  else if (!check.steady && probation_)
  {
    // back within the transit after leaving: the lattice rolled all along, and goes on from where it is; its forces
    // before this step are of the state the last answer is of (carryAcrossSwitches)
    probation_ = false;
    in_transient_ = true;
    steady_distance_ = 0.0;
    warm_entered_ = rolled_before_;
    if (warm_entered_)
      warm_forces_ = latticeForces(*transient_);  // (its last roll's answer: no work, unless a retune came between)
  }
  else if (!check.steady)
    enterTransient(kin, dt);  // from the state before this step
  if (s.defined)
  {
    last_rolling_ = kin;
    have_rolling_ = true;
    last_lag_ = check.lag;
  }
  rolled_before_ = s.defined;
}

void BrushAuto::rollOnProbation(const ContactKinematics& kin, const Slips& s, double dt)
{
  // the lattice's step beside the steady family's answer, while the budget carries it; a transit on, the steady state
  // has held long enough that a later return starts warm
  probation_travel_ += s.defined ? s.V_r * dt : 0.0;
  if (probation_travel_ >= longestPath(p_) || transient_->predictWork(kin, dt) > remaining())
  {
    probation_ = false;
    return;
  }
  stepTransient(kin, s, dt);
}

BrushForces BrushAuto::stepTransient(const ContactKinematics& kin, const Slips& s, double dt)
{
  const BrushForces f = stepLattice(*transient_, transient_resolution_, kin, s, dt);
  entry_error_ *= lag_->slowest(s.V_r * dt / (0.5 * longestPath(p_) / p_.a));  // the slowest renewal
  return f;
}

BrushForces BrushAuto::latticeForces(const BrushTransient& lattice)
{
  spent_ += lattice.forcesWork();
  return lattice.forces();
}

BrushForces BrushAuto::stepLattice(BrushTransient& lattice, int resolution, const ContactKinematics& kin,
                                   const Slips& s, double dt)
{
  lattice.setWorkBudget(remaining());
  const BrushForces f = lattice.update(kin, s, dt);
  spent_ += f.work;
  cost_ += transientStepCost(resolution) * std::max(1.0, std::ceil(s.V_r * dt / (p_.a / resolution)));
  return f;
}

BrushForces BrushAuto::transientAnswer(const ContactKinematics& kin, const Slips& s, double dt, double target,
                                       int& resolution)
{
  // a lattice whose step does not fit what is left of the budget: every other bristle, until it does
  while (transient_->predictWork(kin, dt) > remaining() && transient_->coarsen())
  {
    budget_cut_ = std::max(budget_cut_, transient_resolution_);
    transient_resolution_ /= 2;
    retire(finer_);
    easy_travel_ = 0.0;
    budget_held_ = true;
  }
  resolution = transient_resolution_;
  BrushForces out = stepTransient(kin, s, dt);
  out.error_estimate += entry_error_;
  // A missed target asks for twice the resolution. Rolling, a finer lattice starts beside this one (warm, in
  // the steady state of these inputs) and takes over once it has rolled the longest path: then every bristle
  // on it entered under inputs it followed, so it holds nothing of its start. Interpolating the state onto the
  // finer lattice instead was wrong near a spin pole, where the sliding direction turns within a spacing, by
  // 7 % of mu F_z a transit later on random histories. At standstill nothing renews a state: the finer lattice
  // waits for the next entry into the transient model, and the estimate meanwhile says that the target is
  // missed.
  if (finer_ && finer_->predictWork(kin, dt) > remaining())
  {
    retire(finer_);  // the budget no longer carries both lattices
    budget_held_ = true;
  }
  if (finer_)
  {
    stepLattice(*finer_, 2 * resolution, kin, s, dt);
    finer_travel_ += s.V_r * dt;
    if (finer_travel_ >= longestPath(p_))
    {
      // continuity: the coarse answer's difference from the finer one is carried and decays like any switch
      const BrushForces fine = latticeForces(*finer_);  // (its step's answer: no work)
      offset_.F_x += out.F_x - fine.F_x;
      offset_.F_y += out.F_y - fine.F_y;
      offset_.M_z += out.M_z - fine.M_z;
      const double entry = entry_error_;
      out = fine;
      out.error_estimate += entry;
      retire(transient_);
      transient_ = std::move(finer_);
      transient_resolution_ = resolution = 2 * resolution;
      if (transient_resolution_ >= budget_cut_)
        budget_cut_ = 0;  // back where the budget took it from
    }
  }
  else if ((out.error_estimate - transient_->cutShortError() > target || pending_resolution_ > transient_resolution_) &&
           transient_resolution_ < kMaxTransientResolution)
  {
    // (not for the error of substeps cut short, which a finer lattice does not mend: it wants more of them, beyond the
    // budget or kMaxSubsteps as well, and answers only after rolling as far as that error takes to leave. Refining for
    // it, an unbounded auto on BrushExtremes.NoLoadNoForce's inputs went up to 128 and 4096 substeps a message)
    const int finer = std::min(2 * transient_resolution_, kMaxTransientResolution);
    // A lattice twice as fine must fit what is left of the budget. It needs no warm start: it starts empty and answers
    // only once it has rolled the longest path, when every bristle on it entered under the inputs it followed. Back up
    // to where the budget coarsened the lattice from (budget_cut_), what it is predicted to cost (predictFinerWork:
    // without tilt four to five times this one's step, with tilt its own substeps); else eight times this one's step, a
    // reserve kept from the substeps' lattice (points times substeps): a lattice its own estimate coarsened (an eighth
    // of the target) comes back only with room to spare, as before, since its estimate may be as far below the finer
    // one's as that (a random robot of the sweep, seed 1253, rolling at 1.5 m/s: 0.035 at 16 against 0.0045 at 32, a
    // target of 0.04; at four to five times it went back and forth between 16 and 32 every few messages). With eight
    // times after a budget cut too, that robot, coarsened to 16 by a weave it could not afford at 32, stayed at 16
    // through the roll after it (1 s), flagged at 89 of 101 messages with estimates up to four times the target, while
    // 32 needed about a third of the budget there (docs/speed_and_accuracy.md).
    // (and its storage, sized now where the spare's is short of it: growthWork)
    const long cost =
        finer <= budget_cut_ ? transient_->predictFinerWork(kin, dt) : 8 * transient_->predictWork(kin, dt);
    const long growth = growthWork(finer, true);
    const bool affordable = cost + growth <= remaining();
    if (s.defined && affordable)
    {
      spent_ += growth;
      finer_ = latticeAt(finer);
      finer_travel_ = 0.0;
    }
    else if (!s.defined)
      pending_resolution_ = finer;  // (at standstill nothing renews a finer lattice: the budget is not what holds it)
    else
      budget_held_ = true;
  }
  // Both ways: an estimate that stays below an eighth of the target while the longest path rolls says that a lattice of
  // half the resolution (second order: about four times as far off) would still meet it.
  if (!finer_ && out.error_estimate <= 0.125 * target && transient_resolution_ > configured_resolution_ / 4)
  {
    easy_travel_ += s.defined ? s.V_r * dt : 0.0;
    if (easy_travel_ >= longestPath(p_) && transient_->coarsen())
    {
      transient_resolution_ /= 2;
      easy_travel_ = 0.0;
      budget_cut_ = 0;  // its own choice now
    }
  }
  else
    easy_travel_ = 0.0;
  return out;
}

void BrushAuto::carryAcrossSwitches(BrushForces& out, const Slips& s, const Eigen::Vector2d& sigma,
                                    const RollingFrame& frame, double dt, BrushModelKind before, int before_resolution,
                                    BrushModelKind model, int resolution)
{
  // Continuity: at a switch, carry the difference from the previous model's answer and let it decay (the first
  // answer after a reset has nothing to be continuous with).
  const double target = target_;
  const BrushForces raw = out;
  const bool warm = warm_entered_;
  warm_entered_ = false;
  const bool switched = answered_ && (model != before || resolution != before_resolution);
  if (switched && warm && before != BrushModelKind::Transient)
  {
    // Entering the transient model from the steady family with a warm start, or with the lattice that rolled on beside
    // it: the difference between the two models at the same state, the last answer's and the lattice's before this
    // step. Not the steady model's at these inputs: the switch happens where the steady state does not hold at them,
    // and carrying that difference put its lag into the answer (sweep seed 5021 with tilt, braking from 1.39 to 0.13
    // m/s into a spin within a 30-Hz message: 0.343 of mu F_z off, against 0.040 with this; 5 messages after leaving
    // in a test of Fig. 4, 0.074 and 0.85 against 0.0009 and 0.0005). Only from an answer that met its target: a
    // difference from one that did not is mostly its own error (below).
    if (last_raw_.error_estimate <= target)
    {
      offset_.F_x += last_raw_.F_x - warm_forces_.F_x;
      offset_.F_y += last_raw_.F_y - warm_forces_.F_y;
      offset_.M_z += last_raw_.M_z - warm_forces_.M_z;
    }
  }
  else if (switched)
  {
    BrushForces previous = out;
    // (the lattice's step beside this answer, or its last one: no work, even where the budget is spent to its
    // granularity; after a coarsening or a turn of the frame a pass of the sums, where it fits)
    if (before == BrushModelKind::Transient && transient_->forcesWork() <= std::max(0L, work_budget_ - spent_))
      previous = latticeForces(*transient_);
    else if (s.defined && before == BrushModelKind::Linear)
    {
      previous = linear_.evaluate(sigma, s.phi);
      frame.forcesToPatch(previous);
    }
    else if (s.defined && before == BrushModelKind::Steady && steady_cached_)
    {
      previous = steady_cache_;  // evaluated for the lag at these inputs
      frame.forcesToPatch(previous);
    }
    else if (s.defined && before == BrushModelKind::Steady && remaining() < kMinSwitchWork)
      previous = out;  // nothing left of the budget to evaluate the model switched from: no carried difference
    else if (s.defined && before == BrushModelKind::Steady)
    {
      BrushSteady::Stats stats;
      previous = steady_.evaluate(sigma, s.phi, s.phi_gamma, s.phi_psi, std::max(0.5 * target, 1e-6), &stats,
                                  std::min(BrushSteady::kMaxWork, remaining()));
      spent_ += stats.work;
      frame.forcesToPatch(previous);
    }
    // a steady answer the budget cut short of the target is no state to be continuous with: carried, its own error
    // went into the answer (sweep seed 1014, entering a pivot at 85 rad/m of spin: 0.25 of mu F_z off for five
    // messages, from a steady evaluation whose estimate was 2.9)
    if (before == BrushModelKind::Steady && previous.error_estimate > target)
      previous = out;
    offset_.F_x += previous.F_x - out.F_x;
    offset_.F_y += previous.F_y - out.F_y;
    offset_.M_z += previous.M_z - out.M_z;
  }
  const double decay = s.V_r > 0.0 ? std::exp(-s.V_r * dt / (0.5 * p_.a)) : std::exp(-dt / 0.05);
  offset_.F_x *= decay;
  offset_.F_y *= decay;
  offset_.M_z *= decay;
  out.F_x += offset_.F_x;
  out.F_y += offset_.F_y;
  out.M_z += offset_.M_z;
  out.error_estimate += distance(offset_, BrushForces{}, p_);
  // the offset never takes the force off the friction circle
  const double norm = std::hypot(out.F_x, out.F_y), limit = p_.mu * p_.F_z;
  if (norm > limit && norm > 0.0)
  {
    out.F_x *= limit / norm;
    out.F_y *= limit / norm;
  }
  last_raw_ = raw;
}

void BrushAuto::visitBristles(const BristleVisitor& visit) const
{
  if (last_model_ == BrushModelKind::Transient && transient_)
    transient_->visitBristles(visit);
  else
    steady_.visitBristles(last_slips_, visit);
}

bool BrushAuto::adhesionResponse(AdhesionResponse& response, long& work, double band) const
{
  // the lattice the next update advances without rolling: the one under way (answering, or rolling beside the steady
  // answer on probation) or one still undeformed (nothing rolled since a reset); not one that a warm start is about to
  // fill with the steady state of the last rolling inputs
  if (!(in_transient_ || probation_ || !have_rolling_))
    return false;
  return transient_->adhesionResponse(response, work, band);
}

}  // namespace sphere_contact_estimator
