#include "patch_integral.h"

// STL
#include <algorithm>
#include <array>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/numerics/polynomial_roots.h"
#include "sphere_contact_estimator/core/numerics/quadrature_rules.h"

namespace sphere_contact_estimator
{
namespace
{
using boost::math::double_constants::half_pi;
using boost::math::double_constants::pi;

constexpr int kMaxIntervals = 512;
constexpr int kMaxGaps = 64;
constexpr int kMaxMixedDepth = 4;
constexpr int kMaxSamples = 18;  // a rule's 15 nodes and up to three probes
// Eq. (4b)'s tolerance of each path, as a share of the patch's: the paths' estimates, weighted across them (the weights
// sum to pi), take at most pi times it (16 %), the rules across the paths the rest. They are a few to a hundred times
// above the paths' errors, but splitting intervals does not shrink them: with three times the share, Fig. 4's tilted
// points at 1e-4 needed 1.2-1.6 times the paths and 2.2x the time. At loose tolerances (from 1e-3 of the patch's
// integrals, about 6e-4 of mu F_z) the first rules across the paths already hold far less than the tolerance, and a
// larger share makes every path cheaper with no more of them: the Fig. 4 set's median 25 % faster at 1e-3 and 19 % at
// 1e-2 with 0.3 (the same paths; one run, scratch timing of the set). Where the whole patch takes a Jacobi pair
// (jacobiAcross), whose estimate is far smaller, 0.3 at every tolerance it serves.
constexpr double kCoulombPathShare = 0.05;
constexpr double kCoulombLoosePathShare = 0.3;
// Under a Jacobi pair whose error the pole test predicts at most kQuietPair of the tolerance, the paths take half of it.
// The pair's weights on the paths' integrals sum to 2.5-2.7 (they undo the cos^4 of the load), but most of that is on
// the outer paths, short, whose estimates are orders below any share; where the sum misses nonetheless, the patch is
// split as anywhere. Fig. 4 set's median work at 1e-3 / 1e-4 of mu F_z 9 % / 13 % lower, its total 2 % lower; with
// 0.6 the pair missed at more points and the total at 1e-4 rose 4 %, with 0.7 by 30 %.
constexpr double kQuietPairPathShare = 0.5;
constexpr double kQuietPair = 0.05;
constexpr double kLooseTolerance = 1e-3;

// A sign change of a continuous g between a (g >= 0) and b (g < 0), by the Illinois variant of regula falsi (fa, fb: g
// there, the caller's; before each evaluation stop(bracket, next) may end it: `bracket` is raised to the one it left).
template <class G, class Stop>
double solveSignChange(const G& g, double a, double fa, double b, double fb, const Stop& stop, double& bracket)
{
  for (int it = 0; it < 100 && std::abs(b - a) > 1e-13; ++it)
  {
    const double t = (fa - fb) != 0.0 ? b - fb * (b - a) / (fb - fa) : 0.5 * (a + b);
    if (stop(std::abs(b - a), t))
      break;
    const double ft = g(t);
    if (ft == 0.0)
      return t;
    if ((ft >= 0.0) == (fb >= 0.0))
    {
      b = t, fb = ft;
      fa *= 0.5;
    }
    else
    {
      a = b, fa = fb;
      b = t, fb = ft;
    }
  }
  bracket = std::max(bracket, std::abs(b - a));
  return 0.5 * (a + b);
}

// A Kronrod rule across the paths with its embedded Gauss rule and a third, lower-degree view of the same samples (the
// interpolatory rule on the Kronrod-only nodes), and the nodes' barycentric weights (hiddenChange's interpolant).
struct AcrossRule
{
  int n = 0;
  std::array<double, 15> x{}, wk{}, wg{}, wr{}, bary{};
  void finish()
  {
    for (int j = 0; j < n; ++j)
    {
      bary[j] = 1.0;
      for (int k = 0; k < n; ++k)
        if (k != j)
          bary[j] /= x[j] - x[k];
    }
  }
};

// A Gauss-Kronrod pair (numerics::GaussKronrod15 or GaussKronrod7) and its complement's weights as an AcrossRule.
template <class Pair, std::size_t N>
AcrossRule acrossRule(const Pair& gk, const std::array<double, N>& complement)
{
  AcrossRule r;
  r.n = static_cast<int>(N);
  for (std::size_t i = 0; i < N; ++i)
  {
    r.x[i] = gk.x[i];
    r.wk[i] = gk.wk[i];
    r.wg[i] = gk.wg[i];
    r.wr[i] = complement[i];
  }
  r.finish();
  return r;
}

// 15 points: Gauss 7 (degree 13) in Kronrod 15 (degree 22), the complement exact to degree 7.
const AcrossRule& kronrod15()
{
  static const AcrossRule rule = acrossRule(numerics::gaussKronrod15(), numerics::kronrodComplement());
  return rule;
}

// 7 points: Gauss 3 (degree 5) in Kronrod 7 (degree 11), the complement exact to degree 3.
const AcrossRule& kronrod7()
{
  static const AcrossRule rule = acrossRule(numerics::gaussKronrod7(), numerics::kronrod7Complement());
  return rule;
}

// The whole patch under the parabolic pressure: a path's load goes as cos^4(theta) (its length, its bound's height and
// the width it stands for each bring a cos), so that across the paths the integrand is (1 - y^2)^(3/2) R(y) in the
// crossing height y = sin(theta), with R smooth where the structure is one. Legendre rules in theta see the cos^4 as a
// function of degree ~ 10 (their errors at the Fig. 4 set: 3 points 0.3, 5 points 9e-3, 7 points 5e-5 of the patch
// integral, almost the same at every point), the Jacobi rules of that weight only R. The pair's nodes as theta on
// [-1, 1] (x = asin(y) / (pi / 2)) and its weights divided by the weight there, so that the integrator sums the
// integrand at its nodes as for any rule. (Not for the other pressures: near the patch's sides their bristles adhere
// from the rim, the load goes as the path's length squared, and the odd powers of cos it brings leave sqrt(1 - y^2) in
// R. Both laws: under the rigid law too the integrand is smooth across a patch of one structure.)
AcrossRule jacobiAcross(int n)
{
  const numerics::JacobiKronrod& jk = numerics::jacobiKronrod(n);
  AcrossRule r;
  r.n = jk.size;
  for (int i = 0; i < jk.size; ++i)
  {
    const double c2 = 1.0 - jk.y[i] * jk.y[i], k = 1.0 / (c2 * c2 * half_pi);  // dtheta = dy / cos, R = v / cos^4
    r.x[i] = std::asin(jk.y[i]) / half_pi;
    r.wk[i] = k * jk.wk[i];
    r.wg[i] = k * jk.wg[i];
    r.wr[i] = k * jk.wr[i];
  }
  r.finish();
  return r;
}

// The Jacobi pair's Gauss points by the tolerance (of the patch's integrals): 3 (7 paths) from 5e-4, one more for each
// factor 3.5 below, to 5 (11 paths) from 4.1e-5; below that the 15-point Legendre pair, as before (the references'
// tolerances: they do not share the rule they check). Over the Fig. 4 set the 3-point Gauss rule's difference to its
// Kronrod rule is at most 1.1e-3 where the structure is one, the 4-point's 3e-4, the 5-point's 8.5e-5, each the
// previous one's over 3.5-3.7, and the error of the Kronrod sum at most 0.08 of that difference; a whole patch whose
// estimate misses the tolerance is split into halves (the 15-point pairs): the thresholds put that at up to half of
// the points at each choice and gave the least work over the set (1.34 M against 1.41 M with 4 points at 1e-3 of
// mu F_z, 3.80 M against 4.52 M with 3 and 3.90 M with 5 points at 1e-4; the 15-point pair took 1.61 M and 4.60 M;
// the rigid law's 0.94 M and 1.41 M went to 0.88 M and 1.26 M). The Kronrod sum's error stayed within 0.14 of the
// estimate wherever the pair served (2000 random points of the Fig. 4 envelope per law, docs/models.md), and the
// estimate above the error at every comparison of model_accuracy --sweep under both laws.
constexpr double kJacobiTolerance = 5e-4;
constexpr double kJacobiRatio = 3.5;
// The Gauss rule's difference to its Kronrod rule against rho^(-2n) (the Integrator's pole test): 1.2-4.1 over the
// Fig. 4 set's points of one structure at n = 3, 4.
constexpr double kJacobiScale = 4.0;

const AcrossRule& jacobiRule(int n)
{
  static const std::array<AcrossRule, numerics::JacobiKronrod::kMaxPoints + 1> rules = [] {
    std::array<AcrossRule, numerics::JacobiKronrod::kMaxPoints + 1> r{};
    for (int k = numerics::JacobiKronrod::kMinPoints; k <= numerics::JacobiKronrod::kMaxPoints; ++k)
      r[k] = jacobiAcross(k);
    return r;
  }();
  return rules[std::clamp(n, numerics::JacobiKronrod::kMinPoints, numerics::JacobiKronrod::kMaxPoints)];
}

// The 7-point rule takes an interval no wider than this (in theta) at a tolerance of 1e-3 of mu F_z and, as its Gauss
// rule's error on a width w falls as w^7 (degree 5), w ~ tolerance^(1/7) at others: about 0.37 at 1e-6, 0.72 at 1e-4,
// 1.39 at 1e-2. The whole patch (pi wide) takes the 15-point rule where jacobiAcross's does not serve. Measured on the Fig. 4 set (both tilts, eq.
// 4b), against the 15-point rule everywhere: work -26 %, -17 %, -9 % at 1e-2, 1e-3, 1e-4 (the same paths at its median
// point, 36 instead of 68 where the pole's path and G's extent cut the patch into four), estimates up to 0.62, 0.99, 1.0
// of the tolerance; 0.8 saved less at every target, 1.2 cost more at 1e-4. Under eq. (4b) only: the rigid law's
// integrand jumps where the structure changes unseen, and its cheaper paths gained less (-32 % at 1e-2, +12 % at 1e-4).
constexpr double kNarrowWidth = 1.0;
// Under the rigid law the integrand jumps where the event structure changes; where a change lies between two nodes
// unseen, the Gauss and Kronrod sums may agree no better than the third rule does, and |K - G| is then no bound on K's
// error: a 15-point interval's |K - G| must be below this share of |K - R| to be taken as converged. With 1 (as the
// continuous eq. 4b keeps) the estimate fell short of the error at 1 of 15 000 comparisons of model_accuracy --sweep 41
// 5000 --law rigid (error / estimate 1.026 at 1e-4: a Hertzian point whose [0, pi/2] half had |K - G| = 0.97 |K - R|);
// with 0.9 (or 0.7) at none over seeds 2026, 11, 15, 16, 17, 31, 41, 43, 47, 53 (161 751 comparisons, error at most 0.52
// of the estimate), for 1 % more work on the Fig. 4 set at 1e-4 (2 % at 1e-2, 0 at 1e-3; 0.7 cost 6 % at 1e-4).
constexpr double kRigidConvergence = 0.9;

// Plain data, set when pushed: the integrator holds 512 of them, not cleared per evaluation.
struct Interval
{
  double a, b;
  double K[4];  // Kronrod sums of force x, y, moment, sliding area
  double E[3];  // error bounds of the first three
  bool gap;     // a located change of structure: bounded, never refined
  double priority() const { return gap ? -1.0 : std::max({ E[0], E[1], E[2] }); }
};

class Integrator
{
public:
  Integrator(const BristleField& field, double tolerance, long max_work, CoulombStepper stepper)
    : f_(field)
    , stepper_(stepper)
    , tol_(tolerance)
    , max_work_(max_work)
    , path_tol_(std::max(1e-14, (field.law == SlidingLaw::Rigid           ? 1e-2
                                 : tolerance >= kLooseTolerance ? kCoulombLoosePathShare
                                                                : kCoulombPathShare) *
                                    tolerance))
    // |weight * path integral| for any path and component: travel <= pi, |u| <= the field's bound, |z| <= 1,
    // weight <= 2
    , bound_(2.0 * pi * field.deflectionBound())
  {
    // where two structures meet, bisection stops at a width whose bound is a small part of the tolerance
    delta_ = std::max(1e-13, 1e-3 * tolerance / (2.0 * std::max(bound_, 1e-300)));
    continuous_ = field.law == SlidingLaw::Coulomb;
    // the tolerance as a fraction of mu F_z (the integrals' unit is mu F_z pi / peakFactor)
    narrow_ = continuous_ ? kNarrowWidth * std::pow(tolerance * field.pressure.peakFactor() / pi / 1e-3, 1.0 / 7.0) : 0.0;
    if (field.pressure.squaredExponent() == 2 && tolerance >= kJacobiTolerance / (kJacobiRatio * kJacobiRatio))
    {
      int n = numerics::JacobiKronrod::kMinPoints;
      for (double t = kJacobiTolerance; tolerance < t; t /= kJacobiRatio)
        ++n;
      // R's nearest singularity is the spin pole (the drive's direction turns about it): an n-point Gauss rule's error
      // falls as rho^(-2n), rho = r + sqrt(r^2 - 1) the Bernstein ellipse through a pole at r patch radii. Where that
      // leaves the estimate above half the tolerance, the pair would miss and cost its paths on top of the halves' (at
      // the skid of data/manoeuvre.bag, whose sigma points put the pole 1.2-1.5 radii out, the halves took 39-41 paths
      // where the 15-point rule took 17; with the test, 400 such points took 2.11 M units against 2.85 M before the pairs).
      const double r = field.phi != 0.0 ? std::abs(field.pole()) : INFINITY;
      const double rho = r + std::sqrt(std::max(0.0, r * r - 1.0));
      predicted_ = kJacobiScale * std::pow(rho, -2.0 * n);
      if (predicted_ <= 0.5 * tolerance)
        whole_ = &jacobiRule(n);
    }
  }

  PatchIntegral run()
  {
    double cuts[16];
    // (a quarter of the work for the search: beyond, a breakpoint left in its bracket is found again where the rules'
    // samples see the structure change, by bisection on it)
    StructureSearch search;
    search.max_work = max_work_ / 4;
    const int nc = structureBreakpoints(f_, cuts, 16, search);
    work_ += search.work;
    // A patch the whole of which a Jacobi pair takes: the pair's estimate leaves most of a tight tolerance to the paths
    // (its median over the Fig. 4 set at 1e-4 of mu F_z: 9e-6 of the patch integrals against 1.6e-4), so the loose
    // share serves for every path, the halves' too where the pair's estimate misses: at 1e-4 the Fig. 4 set's median
    // work 10 652 -> 7 096 units (largest error 3.3e-6 of mu F_z either way). Not where the patch is cut (a spin pole in
    // it): there the 15-point rules' estimates leave no such room, and the loose share split them further (the pivot of
    // data/manoeuvre.bag: 2.7x the work).
    // Where the pair's own error is predicted far below the tolerance, a larger share for its paths; if it misses
    // nonetheless, the halves' paths take the loose one again (their 15-point rules' weights sum to pi).
    double split_tol = path_tol_;
    if (whole_ && nc == 0 && continuous_)
    {
      path_tol_ = split_tol = std::max(path_tol_, kCoulombLoosePathShare * tol_);
      if (predicted_ <= kQuietPair * tol_)
        path_tol_ = std::max(path_tol_, kQuietPairPathShare * tol_);
    }
    double from = -half_pi;
    for (int i = 0; i <= nc; ++i)
    {
      const double to = i < nc ? cuts[i] : half_pi;
      if (to - from > 1e-14)
        add(from, to, 0, true);
      from = to;
    }
    // a split costs two rules (30 paths) and whatever changes of structure they locate: stop before a split the
    // budget cannot finish, so that the answer is the last complete one, not one with unsolved paths in it
    path_tol_ = split_tol;
    while (estimate() > tol_ && work_ + 4 * 30 * averagePathWork() <= max_work_ && n_ + 2 * kMaxGaps < kMaxIntervals)
    {
      int worst = -1;
      double p = 0.0;
      for (int i = 0; i < n_; ++i)
        if (iv_[i].priority() > p && iv_[i].b - iv_[i].a > 1e-13)
          p = iv_[i].priority(), worst = i;
      if (worst < 0)
        break;
      const Interval split = iv_[worst];
      iv_[worst] = iv_[--n_];
      const double mid = 0.5 * (split.a + split.b);
      add(split.a, mid, 0);
      add(mid, split.b, 0);
    }
    PatchIntegral out;
    double K[4] = { pool_.K[0], pool_.K[1], pool_.K[2], pool_.K[3] };
    for (int i = 0; i < n_; ++i)
      for (int c = 0; c < 4; ++c)
        K[c] += iv_[i].K[c];
    out.force = { K[0], K[1] };
    out.moment = K[2];
    out.sliding_area = K[3];
    out.utilisation2 = util2_;
    out.error = estimate();
    out.paths = paths_;
    out.work = work_;
    out.converged = out.error <= tol_;
    return out;
  }

private:
  struct Sample
  {
    double theta;
    double v[4];
    double error;
    std::uint64_t signature;
    double margin;
    double fold;  // PathIntegrals::fold
  };

  // Two paths with no change of event structure between them, as far as their samples tell: equal signatures, and
  // no fold of the onset (PathIntegrals::fold changes sign) between them.
  static bool sameStructure(const Sample& x, const Sample& y)
  {
    return x.signature == y.signature &&
           !(std::isfinite(x.fold) && std::isfinite(y.fold) && (x.fold > 0.0) != (y.fold > 0.0));
  }

  // The work budget is spent: no further path is solved, no interval refined.
  // The work budget is spent, or the next path might overrun it (as costly as the costliest so far): no further path
  // is solved, no interval refined.
  bool spent() const { return work_ >= max_work_ || work_ + largest_path_work_ > max_work_; }
  double averagePathWork() const { return paths_ > 0 ? static_cast<double>(work_) / paths_ : 0.0; }

  Sample solve(double theta)
  {
    Sample s;
    s.theta = theta;
    if (spent())
    {
      // not solved: nothing counted, bounded by the integrand's bound, its own structure (so that no rule treats
      // it as smooth)
      s.v[0] = s.v[1] = s.v[2] = s.v[3] = 0.0;
      s.error = bound_;
      s.signature = kUnsolved;
      s.margin = 1.0;
      s.fold = NAN;
      return s;
    }
    ++paths_;
    const BristlePath path = BristlePath::across(f_, theta);
    const PathIntegrals r = solvePath(f_, path, path_tol_, false, max_work_ - work_, stepper_);
    work_ += r.work;
    largest_path_work_ = std::max(largest_path_work_, r.work);
    util2_ = std::max(util2_, r.utilisation2);
    const double J = path.weight;
    s.v[0] = J * r.force.real();
    s.v[1] = J * r.force.imag();
    s.v[2] = J * r.moment;
    s.v[3] = J * r.sliding;
    // a path whose series budget ran out is not resolved: bound it by the integrand's bound
    // the computed and the exact integral each lie within bound_ (every node value obeys |u| <= the field's bound)
    s.error = r.truncated ? bound_ : std::min(J * r.error, 2.0 * bound_);
    s.signature = r.signature;
    s.margin = r.onset_margin;
    s.fold = r.fold;
    return s;
  }

  double estimate() const
  {
    double E[3] = { pool_.E[0], pool_.E[1], pool_.E[2] };
    for (int i = 0; i < n_; ++i)
      for (int c = 0; c < 3; ++c)
        E[c] += iv_[i].E[c];
    return std::max({ E[0], E[1], E[2] });
  }

  // Kept for refinement while there is room; beyond, added to a pool that is summed and bounded, never refined (no
  // interval's share is ever dropped).
  void push(const Interval& v)
  {
    if (n_ < kMaxIntervals)
    {
      iv_[n_++] = v;
      return;
    }
    for (int c = 0; c < 4; ++c)
      pool_.K[c] += v.K[c];
    for (int c = 0; c < 3; ++c)
      pool_.E[c] += v.E[c];
  }

  // Kronrod rule on [a, b]; where its nodes disagree on the event structure, the changes are located and the
  // pieces between them integrated on their own. `ends`: a and b are where the structure changes for reasons fixed in
  // the plane (structureBreakpoints) or the patch's edges; a band of other structure right beside such an end
  // (narrower than the rule's outermost spacing) is sought with a path just inside it.
  void add(double a, double b, int depth, bool ends = false)
  {
    const AcrossRule& rule = whole_ && a <= -half_pi && b >= half_pi ? *whole_ : b - a < narrow_ ? kronrod7() : kronrod15();
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    std::array<Sample, kMaxSamples> s{};  // the rule's nodes, a probe between them if their margins ask, probes at the ends
    int count = rule.n;
    for (int i = 0; i < rule.n; ++i)
      s[i] = solve(mid + half * rule.x[i]);
    double probe = 0.0;
    if (ends)
    {
      const double inset = std::max(delta_, 1e-9 * (b - a));
      if (2.0 * inset < b - a)
      {
        s[count++] = solve(a + inset);
        s[count++] = solve(b - inset);
      }
    }
    // one structure: equal signatures, and every fold on one side (equality and the sign are transitive)
    const auto oneStructure = [&] {
      int folds = 0;
      for (int i = 0; i < count; ++i)
      {
        if (s[i].signature != s[0].signature)
          return false;
        if (std::isfinite(s[i].fold))
          folds |= s[i].fold > 0.0 ? 2 : 1;
      }
      return folds != 3;
    };
    bool uniform = oneStructure();
    if (uniform && hiddenChange(rule, s, probe))
    {
      // a band of other structure between two nodes: confirm it with a path there
      s[count++] = solve(mid + half * probe);
      uniform = oneStructure();
    }
    // where the integrand's bound is far below the tolerance (tiny slips), a change of structure costs nothing to
    // leave inside: the rigorous bound below covers it
    const bool negligible = 2.0 * pi * bound_ <= 0.1 * tol_;
    if (!uniform && depth < kMaxMixedDepth && !spent() && !negligible)
    {
      // the changes between neighbouring samples, each to a gap narrower than delta_
      std::array<Sample, kMaxSamples> sorted = s;
      std::sort(sorted.begin(), sorted.begin() + count, [](const Sample& x, const Sample& y) { return x.theta < y.theta; });
      std::array<std::pair<Sample, Sample>, kMaxGaps> gaps;
      int ng = 0;
      for (int i = 0; i + 1 < count; ++i)
        if (!sameStructure(sorted[i], sorted[i + 1]))
          locate(sorted[i], sorted[i + 1], gaps.data(), ng);
      double from = a;
      for (int k = 0; k < ng; ++k)
      {
        if (gaps[k].first.theta > from)
          add(from, gaps[k].first.theta, depth + 1);
        Interval g{};
        g.a = gaps[k].first.theta;
        g.b = gaps[k].second.theta;
        g.gap = true;
        const double w = g.b - g.a;
        for (int c = 0; c < 4; ++c)
          g.K[c] = 0.5 * w * (gaps[k].first.v[c] + gaps[k].second.v[c]);
        for (int c = 0; c < 3; ++c)
          g.E[c] = gapBound(gaps[k].first, gaps[k].second, c);
        push(g);
        from = g.b;
      }
      if (b > from)
        add(from, b, depth + 1);
      return;
    }
    Interval v{};
    v.a = a;
    v.b = b;
    // three nested views of the same samples: Kronrod (degree 22 or 11), its Gauss rule (13 or 5), and the interpolatory
    // rule on the Kronrod-only nodes (7 or 3: AcrossRule)
    double G[3] = {}, R[3] = {}, path_error = 0.0;
    for (int i = 0; i < rule.n; ++i)  // the rule's nodes, in its order
    {
      for (int c = 0; c < 4; ++c)
        v.K[c] += half * rule.wk[i] * s[i].v[c];
      for (int c = 0; c < 3; ++c)
      {
        G[c] += half * rule.wg[i] * s[i].v[c];
        R[c] += half * rule.wr[i] * s[i].v[c];
      }
      path_error += half * rule.wk[i] * s[i].error;
    }
    for (int c = 0; c < 3; ++c)
    {
      // where the integrand is resolved, the rules' errors fall with their degree: |K - G| (G's error) is below
      // |K - R| (R's). Where it is not (a steep turn of the onset across the paths: a branch point close to the real
      // axis), |K - G| may be small by chance while K is still off: then the largest of the differences, doubled.
      // (A tighter test, |K - G| <= 0.1 |K - R|, costs 2.4x on the Fig. 4 set at 1e-4.)
      const double kg = std::abs(v.K[c] - G[c]), kr = std::abs(v.K[c] - R[c]), gr = std::abs(G[c] - R[c]);
      v.E[c] = (kg <= (continuous_ ? 1.0 : kRigidConvergence) * kr ? kg : 2.0 * std::max({ kg, kr, gr })) + path_error;
      if (!uniform)  // a change of structure left inside: the rigorous bound of any rule on a bounded integrand
        v.E[c] = std::max(v.E[c], 2.0 * (b - a) * bound_);
    }
    push(v);
  }

  // The nodes agree on the structure, and their margins (smooth across paths) all have one sign: does the
  // margins' interpolant change sign between them? Then returns where it is furthest on the other side.
  bool hiddenChange(const AcrossRule& rule, const std::array<Sample, kMaxSamples>& s, double& probe) const
  {
    if (f_.pressure.vanishesAtRim())
      return false;  // only the uniform pressure's onset can leave through the trailing edge
    const bool positive = s[0].margin > 0.0;
    for (int i = 1; i < rule.n; ++i)
      if ((s[i].margin > 0.0) != positive)
        return false;  // the signatures would have told
    double best = 0.0;
    for (int k = 0; k < 64; ++k)
    {
      const double x = -1.0 + (k + 0.5) / 32.0;
      double num = 0.0, den = 0.0;
      for (int j = 0; j < rule.n; ++j)
      {
        const double t = rule.bary[j] / (x - rule.x[j]);
        num += t * s[j].margin;
        den += t;
      }
      const double value = (positive ? -1.0 : 1.0) * num / den;
      if (value > best)
        best = value, probe = x;
    }
    return best > 0.0;
  }

  // What a located change of structure between two samples may hold. Under the rigid law the integrand jumps there:
  // any value the integrand's bound allows. Under eq. (4b) the field, and so each path's integrals, is continuous
  // across the paths (a sliding bristle's direction turns no faster than its tip moves; a touch of the bound slides
  // for no travel): the change between the two samples, and their own errors, over the gap's width.
  double gapBound(const Sample& lo, const Sample& hi, int c) const
  {
    const double w = hi.theta - lo.theta;
    if (!continuous_)
      return 2.0 * w * bound_;
    return w * (std::abs(hi.v[c] - lo.v[c]) + lo.error + hi.error);
  }

  // Bisection on the event structure between two samples that differ, down to delta_, or, where the integrand is
  // continuous, until the gap's bound is a small part of the tolerance.
  void locate(const Sample& lo, const Sample& hi, std::pair<Sample, Sample>* gaps, int& ng)
  {
    if (ng >= kMaxGaps)
      return;
    const bool small = continuous_ && std::max({ gapBound(lo, hi, 0), gapBound(lo, hi, 1), gapBound(lo, hi, 2) }) <=
                                          tol_ / (4.0 * kMaxGaps);
    if (hi.theta - lo.theta <= delta_ || spent() || small)
    {
      gaps[ng++] = { lo, hi };
      return;
    }
    const Sample m = solve(0.5 * (lo.theta + hi.theta));
    if (sameStructure(m, lo))
      locate(m, hi, gaps, ng);
    else if (sameStructure(m, hi))
      locate(lo, m, gaps, ng);
    else
    {
      locate(lo, m, gaps, ng);
      locate(m, hi, gaps, ng);
    }
  }

  static constexpr std::uint64_t kUnsolved = ~std::uint64_t(0);

  const BristleField& f_;
  CoulombStepper stepper_;
  double tol_;
  long max_work_;
  long work_ = 0;
  long largest_path_work_ = 0;  // the costliest path so far: one more like it must fit the budget
  double path_tol_, bound_, delta_;
  double predicted_ = INFINITY;  // the Jacobi pair's error as the pole test predicts it
  double narrow_ = 0.0;  // an interval narrower than this takes the 7-point rule (kNarrowWidth)
  const AcrossRule* whole_ = nullptr;  // the whole patch's rule where it is not kronrod15() (jacobiAcross)
  bool continuous_ = false;  // the integrand is continuous across the paths (SlidingLaw::Coulomb)
  std::array<Interval, kMaxIntervals> iv_;
  Interval pool_{};  // the intervals beyond kMaxIntervals (push)
  int n_ = 0;
  int paths_ = 0;
  double util2_ = 0.0;
};
}  // namespace

bool polePath(const BristleField& field, double& theta)
{
  if (field.phi == 0.0)
    return false;
  const std::complex<double> zp = field.pole();
  if (std::norm(zp) >= 1.0)
    return false;
  const double y0 = pathThrough(field, zp);
  if (!(std::abs(y0) < 1.0))
    return false;
  theta = std::asin(y0);
  return true;
}

int structureBreakpoints(const BristleField& field, double* theta, int max_count, StructureSearch& search)
{
  int n = 0;
  const auto add = [&](double t) {
    if (n < max_count && t > -half_pi && t < half_pi)
      theta[n++] = t;
  };
  double theta_p = 0.0;
  const bool pole = polePath(field, theta_p);
  if (pole)
    add(theta_p);
  // (Under eq. 4b the integrand is continuous across the paths, and turns steeply in a band beside the pole's path,
  // sqrt(f / |phi|) wide, where the bristles cannot follow the drive's turn. Graded splits across that band, once made
  // here, doubled the paths at the points beside a pole; without them the rules' own splitting found it: over 3.6e4
  // comparisons on random points the estimate stayed above the error.)
  if (!field.pressure.vanishesAtRim())
  {
    std::sort(theta, theta + n);
    return n;
  }
  const auto peak = [&](double t) { return reAdhesionPeak(field, BristlePath::across(field, t), &search.work); };
  const auto count = [&](double t) { return reAdhesionCount(field, BristlePath::across(field, t), &search.work); };
  // a path evaluated only where the work left pays for it (else the search stops there, cut)
  const auto affords = [&](double t) {
    if (search.work + reAdhesionWork(field, BristlePath::across(field, t)) <= search.max_work)
      return true;
    search.cut = true;
    return false;
  };
  // G around the pole (the drive vanishes there, so a front-half pole is in G): where the paths stop meeting
  // it, on either side of the pole's path. With the parabolic pressure G is one conic region, and the largest
  // margin along a path changes sign there (regula falsi); with the Hertzian pressure G also holds a band
  // along the whole leading edge, so the number of G stretches along the path tells, located by bisection.
  // Doubling steps out from the pole's path find the first change on each side.
  // (The rigid law's: under eq. 4b a sliding bristle re-adheres where its own sliding speed vanishes, which depends
  // on its history, not on a region fixed in the plane.)
  if (pole && field.pole().real() > 0.0 && field.law == SlidingLaw::Rigid && affords(theta_p))
  {
    const bool conic = field.pressure.squaredExponent() == 2;
    // at the pole's path: the conic's margin (where it is negative G has no component here) or the count of stretches
    const double at_pole = conic ? peak(theta_p) : count(theta_p);
    for (int side = -1; side <= 1 && !(conic && at_pole < 0.0); side += 2)
    {
      const double edge = side * half_pi;
      double inside = theta_p, step = 1e-4, outside = NAN, g_inside = at_pole, g_outside = NAN;
      for (int k = 0; k < 60; ++k, step *= 2.0)
      {
        const double t = theta_p + side * step;
        if ((edge - t) * side <= 0.0 || !affords(t))
          break;  // (the work spent: this end not reached)
        const double g = conic ? peak(t) : count(t);
        if (conic ? g < 0.0 : g != at_pole)
        {
          outside = t, g_outside = g;
          break;
        }
        inside = t, g_inside = g;
      }
      if (std::isnan(outside))
        continue;
      // each to the precision, or the bracket the work leaves (the next path not paid for)
      const auto stop = [&](double bracket, double next) {
        if (bracket <= search.precision)
          return true;  // (precision 0: never before the search's own end)
        return !affords(next);
      };
      if (conic)
        add(solveSignChange(peak, inside, g_inside, outside, g_outside, stop, search.bracket));
      else
      {
        for (int k = 0; k < 50 && std::abs(outside - inside) > 1e-12; ++k)
        {
          const double m = 0.5 * (inside + outside);
          if (stop(std::abs(outside - inside), m))
            break;
          (count(m) == at_pole ? inside : outside) = m;
        }
        search.bracket = std::max(search.bracket, std::abs(outside - inside));
        add(0.5 * (inside + outside));
      }
    }
  }
  // G meeting the leading edge (parabolic pressure; the Hertzian's G holds the whole front edge), where under
  // either law a bristle entering the patch starts to adhere or to slide: the margin on the edge z = e^{i psi} is a
  // quartic in t = tan(psi / 2) after multiplying by (1 + t^2)^2
  if (field.pressure.squaredExponent() == 2)
  {
    const double sx = field.sigma.real(), sy = field.sigma.imag(), ph = field.phi;
    const double S = std::norm(field.sigma) + ph * ph;
    const double c[5] = { 4.0 - S - 2.0 * ph * sy, 4.0 * ph * sx, -8.0 - 2.0 * S, 4.0 * ph * sx, 4.0 - S + 2.0 * ph * sy };
    double t[4];
    const int k = numerics::signChanges(c, 4, -1.0, 1.0, t, 4);
    for (int i = 0; i < k; ++i)
    {
      const double psi = 2.0 * std::atan(t[i]);
      const double y0 = pathThrough(field, std::polar(1.0, psi));
      if (std::abs(y0) < 1.0)
        add(std::asin(y0));
    }
  }
  std::sort(theta, theta + n);
  return n;
}

int reAdhesionBands(const BristleField& field, double* lo, double* hi, int max_count, StructureSearch& search)
{
  double cuts[18];
  cuts[0] = -half_pi;
  const int nb = structureBreakpoints(field, cuts + 1, 16, search);
  if (search.cut)
    return 0;  // not every band found (the caller bounds what they could hold)
  cuts[nb + 1] = half_pi;
  int counts[17];
  for (int i = 0; i <= nb; ++i)
  {
    const BristlePath path = BristlePath::across(field, 0.5 * (cuts[i] + cuts[i + 1]));
    if (search.work + reAdhesionWork(field, path) > search.max_work)
    {
      search.cut = true;
      return 0;
    }
    counts[i] = reAdhesionCount(field, path, &search.work);
  }
  // runs of sub-intervals with the same count (the pole's path splits G's component in two), then the runs
  // that cross more stretches of G than both runs beside them
  int n = 0;
  for (int i = 0; i <= nb && n < max_count;)
  {
    int j = i;
    while (j < nb && counts[j + 1] == counts[i])
      ++j;
    if (counts[i] > (i > 0 ? counts[i - 1] : 0) && counts[i] > (j < nb ? counts[j + 1] : 0))
    {
      lo[n] = cuts[i];
      hi[n] = cuts[j + 1];
      ++n;
    }
    i = j + 1;
  }
  return n;
}

void preparePatchRules()
{
  numerics::prepareQuadratureRules();
  kronrod15();
  kronrod7();
  jacobiRule(numerics::JacobiKronrod::kMinPoints);
}

PatchIntegral integratePatch(const BristleField& field, double tolerance, long max_work, CoulombStepper stepper)
{
  Integrator integrator(field, tolerance, max_work, stepper);
  return integrator.run();
}

}  // namespace sphere_contact_estimator
