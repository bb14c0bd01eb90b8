// Accuracy of every model against converged references, printed as JSON for scripts/benchmark_report.py.
//
// Brush: errors are max(|dF_x|, |dF_y|, |dM_z| / a) / (mu F_z). Every brush section runs under both sliding laws
// (BrushParameters::sliding_law: coulomb, eq. 4b; rigid, Sect. 6) and is keyed by the law's name. Each law has its
// own reference, the steady solver with the reference budget: the rigid law's at 1e-8 (1e-10 for the transient runs),
// eq. (4b)'s at 1e-6 (at 1e-8 its solver spends the budget at some tilted points and returns a flagged, unconverged
// answer). A reference flagged kAccuracyNotMet is counted and its point left out of every comparison.
//  - random: a seeded random set of operating points over the envelope a user reaches (a = 0.01-0.08 m,
//    F_z = 20-5000 N, mu = 0.2-1.2, k = 10^6.5-10^9 N/m^3, |sigma_x| <= 0.3, |sigma_y| <= 0.1, |a phi| <= 1,
//    tilt ratios -0.5..1.5; the three pressures, tilt and no tilt; slips and spins scaled by 10^-3..1): per law the
//    steady model at targets 1e-2, 1e-3, 1e-4 against the reference (whose agreement with an independent solver is
//    measured on a subset), the error estimate against the error, the linear model's bound, auto at its targets
//    with the inputs held (a robot rolling at 1 m/s, 100 Hz); and how far apart the two laws' forces are.
//  - figure4: the paper's Fig. 4 curves (sigma_x in [-1, 1], sigma_y in {0, 0.05, 0.1, 0.2}, phi = 3.33 1/m,
//    chi_gamma = 0.9, tilt and no tilt): per law the steady model at the three targets and the marching scheme of
//    test/support by resolution; the laws' distance over the set.
//  - transient: the transient model at held inputs, by resolution (its largest error and estimate over two lattice
//    spacings of travel after 6a), at two example points and at Fig. 4 points; over the whole Fig. 4 set and
//    random points, how many converge monotonically, the observed order and how often the estimate fell short.
//  - uncertainty: the forces' covariance from the slips' (the unscented transform through the steady model, under
//    the default law) against Monte Carlo at random operating points, at two spreads of the slips.
// Cylinder: |d mu_roll| / mu_roll on the paper's rubber (g = 10) against the exact solution of eq. 18.
//
// Progress and each section's wall time go to stderr.

// STL
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <random>
#include <string>
#include <vector>

// Eigen
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

// nlohmann
#include <nlohmann/json.hpp>

// Package
#include "brush_brute_force.h"
#include "brush_coulomb_reference.h"
#include "brush_marching.h"
#include "noisy_history.h"
#include "parked_streams.h"
#include "sample_covariance.h"
#include "whole_number.h"
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "sphere_contact_estimator/core/brush/force_covariance.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"
#include "sphere_contact_estimator/core/numerics/unscented_transform.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

namespace sce = sphere_contact_estimator;
using sce::bench::wholeNumber;

namespace
{
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

constexpr sce::SlidingLaw kLaws[] = { sce::SlidingLaw::Coulomb, sce::SlidingLaw::Rigid };
constexpr double kTargets[] = { 1e-2, 1e-3, 1e-4 };
// The marching scheme's resolutions, about sqrt(2) apart (bench/bench_models.cpp times the same list).
const std::vector<int> kMarchingResolutions{ 8, 11, 16, 23, 32, 45, 64, 91, 128, 181, 256, 362, 512 };
// Beyond the list, only while 0.1 % is not reached (BrushParameters allows up to 1024).
const std::vector<int> kMarchingExtension{ 724, 1024 };
const std::vector<int> kTransientResolutions{ 8, 16, 32, 64, 128 };

struct Point
{
  sce::BrushParameters p;
  Eigen::Vector2d sigma;
  double phi = 0.0, chi = 1.0;
  double pg() const { return chi * phi; }
  double pp() const { return phi - chi * phi; }
};

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

void progress(const std::string& what, Clock::time_point since)
{
  std::cerr << "model_accuracy: " << what << " (" << static_cast<int>(seconds(since)) << " s)" << std::endl;
}

// Eq. (4b)'s solver spends the reference budget before 1e-8 at some tilted points, so its references stop at 1e-6.
double referenceTolerance(sce::SlidingLaw law) { return law == sce::SlidingLaw::Coulomb ? 1e-6 : 1e-8; }

// The transient runs reach ~5e-5 of mu F_z at resolution 128: both tolerances are far below that.
double transientReferenceTolerance(sce::SlidingLaw law) { return law == sce::SlidingLaw::Coulomb ? 1e-6 : 1e-10; }

Point underLaw(Point q, sce::SlidingLaw law)
{
  q.p.sliding_law = law;
  return q;
}

std::vector<Point> underLaw(std::vector<Point> points, sce::SlidingLaw law)
{
  for (Point& q : points)
    q.p.sliding_law = law;
  return points;
}

bool converged(const sce::BrushForces& f) { return (f.flags & sce::brush_flags::kAccuracyNotMet) == 0; }

// Eq. (4b)'s references by the general stepper: a solution independent of the default's collocation
sce::BrushForces steadyReference(const Point& q, double tolerance)
{
  return sce::BrushSteady(q.p).evaluate(q.sigma, q.phi, q.pg(), q.pp(), tolerance, nullptr,
                                        sce::BrushSteady::kReferenceWork, sce::CoulombStepper::General);
}

double distance(const sce::BrushForces& f, const sce::BrushForces& g, const sce::BrushParameters& p)
{
  return std::max({ std::abs(f.F_x - g.F_x), std::abs(f.F_y - g.F_y), std::abs(f.M_z - g.M_z) / p.a }) / (p.mu * p.F_z);
}

// error / estimate, infinite where a zero estimate meets an error
double ratio(double error, double estimate)
{
  return estimate > 0.0 ? error / estimate : (error > 0.0 ? INFINITY : 0.0);
}

// linear interpolation between order statistics (numpy's default, as the report's)
double quantile(std::vector<double> v, double q)
{
  if (v.empty())
    return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(std::floor(pos)), j = std::min(i + 1, v.size() - 1);
  return v[i] + (v[j] - v[i]) * (pos - static_cast<double>(i));
}

std::vector<Point> randomPoints(int n, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point> out;
  for (int i = 0; i < n; ++i)
  {
    Point q;
    q.p.a = 0.01 + 0.07 * u(rng);
    q.p.F_z = std::exp(std::log(20.0) + std::log(250.0) * u(rng));
    q.p.mu = 0.2 + u(rng);
    q.p.k = std::pow(10.0, 6.5 + 2.5 * u(rng));
    q.p.pressure = static_cast<sce::PressureDistribution>(i % 3);
    q.p.tilt = (i / 3) % 2;
    const double scale = std::pow(10.0, -3.0 * u(rng) * u(rng));  // more weight near the envelope's edge
    q.sigma = scale * Eigen::Vector2d(0.3 * (2.0 * u(rng) - 1.0), 0.1 * (2.0 * u(rng) - 1.0));
    q.phi = scale * (2.0 * u(rng) - 1.0) / q.p.a;
    q.chi = -0.5 + 2.0 * u(rng);
    if (q.p.tilt && std::abs(q.pg()) * q.p.a > 1.0)
      q.chi = 0.9;
    out.push_back(q);
  }
  return out;
}

sce::BrushParameters figure4(bool tilt)
{
  sce::BrushParameters p;  // a = 0.05 m, k = 1.023e8, F_z = 3000 N, mu = 1: the paper's Fig. 4
  p.tilt = tilt;
  return p;
}

Point figure4Point(bool tilt, double sigma_x, double sigma_y)
{
  Point q;
  q.p = figure4(tilt);
  q.sigma = { sigma_x, sigma_y };
  q.phi = 3.33;
  q.chi = 0.9;
  return q;
}

// The 168 points of Fig. 4: sigma_x from -1 to 1 in steps of 0.1, sigma_y in {0, 0.05, 0.1, 0.2}, without and with tilt.
std::vector<Point> figure4Set()
{
  std::vector<Point> set;
  for (int tilt = 0; tilt < 2; ++tilt)
    for (double sy : { 0.0, 0.05, 0.1, 0.2 })
      for (int i = -10; i <= 10; ++i)
        set.push_back(figure4Point(tilt != 0, 0.1 * i, sy));
  return set;
}

Json describe(const Point& q)
{
  return Json{ { "pressure", sce::toString(q.p.pressure) },
               { "tilt", q.p.tilt },
               { "a", q.p.a },
               { "F_z", q.p.F_z },
               { "mu", q.p.mu },
               { "k", q.p.k },
               { "sigma_x", q.sigma.x() },
               { "sigma_y", q.sigma.y() },
               { "phi", q.phi },
               { "chi_gamma", q.chi } };
}

// ---------------------------------------------------------------------------------------------------------------
// References

struct References
{
  std::vector<sce::BrushForces> forces;
  double tolerance = 0.0;
  int unconverged = 0;
  double max_estimate = 0.0;  ///< over the converged ones
  bool ok(std::size_t i) const { return converged(forces[i]); }
};

References references(const std::vector<Point>& points, double tolerance)
{
  References r;
  r.tolerance = tolerance;
  for (const Point& q : points)
  {
    r.forces.push_back(steadyReference(q, tolerance));
    if (converged(r.forces.back()))
      r.max_estimate = std::max(r.max_estimate, r.forces.back().error_estimate);
    else
      ++r.unconverged;
  }
  return r;
}

Json summary(const References& r)
{
  return Json{ { "tolerance", r.tolerance }, { "unconverged", r.unconverged }, { "max_estimate", r.max_estimate } };
}

// ---------------------------------------------------------------------------------------------------------------
// Random points

// The steady model at `target` against the reference: the error, the estimate against it (beyond the reference's own
// estimate), and the time of each call.
Json steadyAtTarget(const std::vector<Point>& points, const References& ref, double target)
{
  double worst = 0.0, worst_ratio = 0.0;
  int compared = 0, below = 0, below_half = 0, over = 0, flagged = 0;
  std::size_t worst_i = 0, ratio_i = 0;
  std::vector<double> times;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const Point& q = points[i];
    const sce::BrushSteady model(q.p);
    const auto t0 = Clock::now();
    const sce::BrushForces f = model.evaluate(q.sigma, q.phi, q.pg(), q.pp(), target);
    times.push_back(1e6 * seconds(t0));
    if (!ref.ok(i))
      continue;
    ++compared;
    const double e = distance(f, ref.forces[i], q.p), slack = ref.forces[i].error_estimate;
    if (e > worst)
      worst = e, worst_i = i;
    if (ratio(e, f.error_estimate) > worst_ratio)
      worst_ratio = ratio(e, f.error_estimate), ratio_i = i;
    below += e > f.error_estimate + slack;
    below_half += e > 2.0 * f.error_estimate + slack;
    over += e > target;
    flagged += !converged(f);
  }
  return Json{ { "target", target },
               { "compared", compared },
               { "max_error", worst },
               { "over_target", over },
               { "estimate_below_error", below },
               { "estimate_below_half_error", below_half },
               { "max_error_over_estimate", worst_ratio },
               { "flagged", flagged },
               { "median_us", quantile(times, 0.5) },
               { "p99_us", quantile(times, 0.99) },
               { "worst", describe(points[worst_i]) },
               { "worst_ratio_at", describe(points[ratio_i]) } };
}

// The reference against an independent solver on `subset` points spread over the set. Rigid law: the brute-force
// marcher with bisected events (8000 paths, 400 steps; its own error ~3e-5 of mu F_z where a re-adhering island lies
// in the patch, far less elsewhere; no estimate of its own). Eq. (4b): test::coulombReference (1000 paths, 2000
// steps, Richardson along the paths, with its own estimate; about 0.7 s a point, 3 s with tilt).
Json independentCheck(const std::vector<Point>& points, const References& ref, sce::SlidingLaw law)
{
  const bool coulomb = law == sce::SlidingLaw::Coulomb;
  const int subset = std::min<int>(static_cast<int>(points.size()), coulomb ? 24 : 48);
  const std::size_t stride = points.size() / static_cast<std::size_t>(std::max(subset, 1));
  double worst = 0.0, own = 0.0;
  int compared = 0, beyond = 0;
  std::size_t worst_i = 0;
  for (int j = 0; j < subset; ++j)
  {
    const std::size_t i = static_cast<std::size_t>(j) * stride;
    if (!ref.ok(i))
      continue;
    const Point& q = points[i];
    double estimate = 0.0;
    sce::BrushForces g;
    if (coulomb)
    {
      const sce::test::CoulombReference c = sce::test::coulombReference(q.p, q.sigma, q.phi, q.pg(), q.pp(), 1000, 2000);
      g = c.forces;
      estimate = c.error;
    }
    else
      g = sce::test::bruteForceSteady(q.p, q.sigma, q.phi, q.pg(), q.pp(), 8000, 400);
    const double d = distance(ref.forces[i], g, q.p);
    ++compared;
    own = std::max(own, estimate);
    if (coulomb)
      beyond += d > ref.forces[i].error_estimate + estimate;
    if (d > worst)
      worst = d, worst_i = i;
  }
  Json out{ { "solver", coulomb ? "test::coulombReference, 1000 paths, 2000 steps"
                                : "test::bruteForceSteady, 8000 paths, 400 steps" },
            { "points", compared },
            { "max_difference", worst },
            { "worst", describe(points[worst_i]) } };
  if (coulomb)
  {
    out["max_own_estimate"] = own;
    out["beyond_both_estimates"] = beyond;
  }
  return out;
}

// The linear model's bound where auto could pick it (at most 0.1): the error against it.
Json linearBound(const std::vector<Point>& points, const References& ref)
{
  double worst_ratio = 0.0;
  int checked = 0, over = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const Point& q = points[i];
    const double bound = sce::BrushLinear::errorBound(q.p, q.sigma, q.phi, q.pg(), q.pp());
    if (bound > 0.1 || bound <= 0.0 || !ref.ok(i))
      continue;
    const double e = distance(sce::BrushLinear(q.p).evaluate(q.sigma, q.phi), ref.forces[i], q.p);
    ++checked;
    over += e > bound + ref.forces[i].error_estimate;
    worst_ratio = std::max(worst_ratio, e / bound);
  }
  return Json{ { "points", checked }, { "error_over_bound", over }, { "max_error_over_bound", worst_ratio } };
}

// Auto at `target` with the inputs held (five updates at 100 Hz, 1 m/s): its error, its estimate, which model answered.
Json autoAtTarget(const std::vector<Point>& points, const References& ref, double target)
{
  double worst = 0.0;
  int compared = 0, over = 0, short_estimate = 0, used[3] = { 0, 0, 0 };
  std::size_t worst_i = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!ref.ok(i))
      continue;
    Point q = points[i];
    q.p.accuracy_target = target;
    sce::BrushAuto model(q.p);
    const sce::ContactKinematics k = sce::ContactKinematics::fromSlips(q.sigma, q.phi, q.chi, 1.0);
    sce::BrushForces f;
    for (int step = 0; step < 5; ++step)
      f = model.update(k, 0.01);
    const double e = distance(f, ref.forces[i], q.p);
    ++compared;
    if (e > worst)
      worst = e, worst_i = i;
    over += e > target;
    short_estimate += e > f.error_estimate + ref.forces[i].error_estimate;
    // linear, steady, transient (BrushModelKind numbers them from 1: Off is 0)
    ++used[static_cast<int>(model.lastModel()) - static_cast<int>(sce::BrushModelKind::Linear)];
  }
  return Json{ { "target", target },         { "compared", compared },         { "max_error", worst },
               { "over_target", over },      { "estimate_below_error", short_estimate },
               { "linear", used[0] },        { "steady", used[1] },            { "transient", used[2] },
               { "worst", describe(points[worst_i]) } };
}

Json randomLaw(const std::vector<Point>& points, const References& ref, sce::SlidingLaw law)
{
  Json out{ { "reference", summary(ref) } };
  for (double target : kTargets)
    out["steady"].push_back(steadyAtTarget(points, ref, target));
  out["reference_vs_independent"] = independentCheck(points, ref, law);
  out["linear_bound"] = linearBound(points, ref);
  for (double target : { 5e-2, 1e-2, 1e-3 })
    out["auto"].push_back(autoAtTarget(points, ref, target));
  return out;
}

// The distance between the laws' converged references at each point: its spread, and where it is largest and least.
Json lawDistance(const std::vector<Point>& points, const References& coulomb, const References& rigid)
{
  std::vector<std::pair<double, std::size_t>> d;  // distance, point
  for (std::size_t i = 0; i < points.size(); ++i)
    if (coulomb.ok(i) && rigid.ok(i))
      d.emplace_back(distance(coulomb.forces[i], rigid.forces[i], points[i].p), i);
  if (d.empty())
    return Json{ { "points", 0 }, { "excluded", points.size() } };
  std::sort(d.begin(), d.end());
  std::vector<double> values;
  for (const auto& [v, i] : d)
    values.push_back(v);
  return Json{ { "points", d.size() },
               { "excluded", points.size() - d.size() },
               { "min", values.front() },
               { "median", quantile(values, 0.5) },
               { "p90", quantile(values, 0.9) },
               { "max", values.back() },
               { "min_at", describe(points[d.front().second]) },
               { "max_at", describe(points[d.back().second]) } };
}

// Without spin the drive has one direction along every path, and the laws should coincide: the same points with
// phi = 0, both laws to 1e-8.
Json lawDistanceWithoutSpin(const std::vector<Point>& points)
{
  double worst = 0.0;
  int compared = 0, unconverged = 0;
  for (Point q : points)
  {
    q.phi = 0.0;
    const sce::BrushForces c = steadyReference(underLaw(q, sce::SlidingLaw::Coulomb), 1e-8);
    const sce::BrushForces r = steadyReference(underLaw(q, sce::SlidingLaw::Rigid), 1e-8);
    if (!converged(c) || !converged(r))
    {
      ++unconverged;
      continue;
    }
    ++compared;
    worst = std::max(worst, distance(c, r, q.p));
  }
  return Json{ { "points", compared }, { "unconverged", unconverged }, { "max", worst } };
}

Json randomSection(int n, Clock::time_point start)
{
  const std::vector<Point> base = randomPoints(n, 2026);
  Json out{ { "points", n } };
  std::vector<References> refs;
  for (sce::SlidingLaw law : kLaws)
  {
    const std::vector<Point> points = underLaw(base, law);
    refs.push_back(references(points, referenceTolerance(law)));
    out["laws"][sce::toString(law)] = randomLaw(points, refs.back(), law);
    progress(std::string("random points, ") + sce::toString(law), start);
  }
  out["law_difference"] = lawDistance(base, refs[0], refs[1]);
  out["law_difference"]["without_spin"] = lawDistanceWithoutSpin(base);
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Fig. 4 set

Json figure4Steady(const std::vector<Point>& set, const References& ref, double target)
{
  double worst[2] = { 0.0, 0.0 };
  int below = 0, flagged = 0;
  for (std::size_t i = 0; i < set.size(); ++i)
  {
    if (!ref.ok(i))
      continue;
    const Point& q = set[i];
    const sce::BrushForces f = sce::BrushSteady(q.p).evaluate(q.sigma, q.phi, q.pg(), q.pp(), target);
    const double e = distance(f, ref.forces[i], q.p);
    worst[q.p.tilt] = std::max(worst[q.p.tilt], e);
    below += e > f.error_estimate + ref.forces[i].error_estimate;
    flagged += !converged(f);
  }
  return Json{ { "target", target },
               { "max_error", worst[0] },
               { "max_error_tilt", worst[1] },
               { "estimate_below_error", below },
               { "flagged", flagged } };
}

// The marching scheme of test/support at `resolution` over the set: its largest error without and with tilt.
Json marchingAt(const std::vector<Point>& set, const References& ref, int resolution)
{
  double worst[2] = { 0.0, 0.0 };
  for (std::size_t i = 0; i < set.size(); ++i)
  {
    if (!ref.ok(i))
      continue;
    sce::BrushParameters p = set[i].p;
    p.resolution = resolution;
    const sce::BrushForces f = sce::test::BrushMarching(p).evaluate(set[i].sigma, set[i].phi, set[i].pg(), set[i].pp());
    worst[p.tilt] = std::max(worst[p.tilt], distance(f, ref.forces[i], p));
  }
  return Json{ { "resolution", resolution }, { "max_error", worst[0] }, { "max_error_tilt", worst[1] } };
}

double worstOfBoth(const Json& row) { return std::max(row["max_error"].get<double>(), row["max_error_tilt"].get<double>()); }

// The smallest listed resolution whose largest error over the whole set (both tilt values) is within `error`, and
// the smallest from which every larger listed one stays within it (the scheme's error is not monotone).
Json reaching(const Json& rows, double error)
{
  Json first = nullptr, stays = nullptr;
  for (const Json& row : rows)
    if (worstOfBoth(row) <= error)
    {
      if (first.is_null())
        first = row["resolution"];
      if (stays.is_null())
        stays = row["resolution"];
    }
    else
      stays = nullptr;
  return Json{ { "error", error }, { "resolution", first }, { "stays_from", stays } };
}

Json marchingByResolution(const std::vector<Point>& set, const References& ref)
{
  Json rows = Json::array();
  for (int n : kMarchingResolutions)
    rows.push_back(marchingAt(set, ref, n));
  for (int n : kMarchingExtension)
    if (reaching(rows, 1e-3)["resolution"].is_null())
      rows.push_back(marchingAt(set, ref, n));
  return Json{ { "rows", rows }, { "reaches", Json::array({ reaching(rows, 1e-2), reaching(rows, 1e-3) }) } };
}

Json figure4Section(Clock::time_point start)
{
  const std::vector<Point> base = figure4Set();
  Json out{ { "points", base.size() } };
  std::vector<References> refs;
  for (sce::SlidingLaw law : kLaws)
  {
    const std::vector<Point> set = underLaw(base, law);
    refs.push_back(references(set, referenceTolerance(law)));
    Json& section = out["laws"][sce::toString(law)];
    section["reference"] = summary(refs.back());
    for (double target : kTargets)
      section["steady"].push_back(figure4Steady(set, refs.back(), target));
    const Json marching = marchingByResolution(set, refs.back());
    section["marching"] = marching["rows"];
    section["marching_reaches"] = marching["reaches"];
    progress(std::string("Fig. 4 set, ") + sce::toString(law), start);
  }
  out["law_difference"] = lawDistance(base, refs[0], refs[1]);
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Transient model

// The transient model at held inputs (1 m/s): after 6a of travel and then over two lattice spacings more, the largest
// error against `ref` and the largest estimate; and how often the estimate fell short of the error beyond the
// reference's own estimate (its error moves with where the lattice stands, so one sample can be lucky).
struct HeldRun
{
  double error = 0.0, estimate = 0.0;
  int short_count = 0, updates = 0;
  double worst_ratio = 0.0;  // error / estimate where it fell short
};

HeldRun runHeld(const Point& q, int resolution, const sce::BrushForces& ref)
{
  sce::BrushParameters p = q.p;
  p.resolution = resolution;
  sce::BrushTransient model(p);
  const sce::ContactKinematics k = sce::ContactKinematics::fromSlips(q.sigma, q.phi, q.chi, 1.0);
  model.update(k, 6.0 * p.a);
  HeldRun run;
  for (int i = 0; i < 16; ++i)
  {
    const sce::BrushForces f = model.update(k, 2.0 * p.a / resolution / 8.0);
    const double e = distance(f, ref, p);
    run.error = std::max(run.error, e);
    run.estimate = std::max(run.estimate, f.error_estimate);
    ++run.updates;
    if (e > f.error_estimate + ref.error_estimate)
    {
      ++run.short_count;
      run.worst_ratio = std::max(run.worst_ratio, ratio(e, f.error_estimate));
    }
  }
  return run;
}

// Falls at every doubling (an error already at the reference's estimate counts as converged).
bool monotone(const std::vector<double>& e, double floor)
{
  for (std::size_t i = 1; i < e.size(); ++i)
    if (e[i] >= e[i - 1] && e[i] > floor)
      return false;
  return true;
}

// observed order between resolutions i and j (j > i, each a doubling apart)
double observedOrder(const std::vector<double>& e, std::size_t i, std::size_t j)
{
  return std::log2(e[i] / e[j]) / static_cast<double>(j - i);
}

Json transientCase(const std::string& name, const Point& q, sce::SlidingLaw law)
{
  const sce::BrushForces ref = steadyReference(q, transientReferenceTolerance(law));
  Json out{ { "name", name }, { "reference_converged", converged(ref) }, { "reference_estimate", ref.error_estimate } };
  std::vector<double> e;
  int short_count = 0, updates = 0;
  for (int n : kTransientResolutions)
  {
    const HeldRun run = runHeld(q, n, ref);
    out["runs"].push_back(Json{ { "resolution", n },
                                { "error", run.error },
                                { "estimate", run.estimate },
                                { "estimate_short", run.short_count } });
    e.push_back(run.error);
    short_count += run.short_count;
    updates += run.updates;
  }
  out["monotone"] = monotone(e, 1e-12 + ref.error_estimate);
  out["estimate_short"] = short_count;
  out["updates"] = updates;
  out["order_8_128"] = observedOrder(e, 0, e.size() - 1);
  out["order_32_128"] = observedOrder(e, 2, e.size() - 1);
  return out;
}

// Over a set of points: how many converge monotonically over the resolutions (largest error over the lattice
// positions), the largest rise where not and where, the median observed orders, and the estimate.
Json convergenceSummary(const std::string& name, const std::vector<Point>& points, sce::SlidingLaw law)
{
  int monotone_count = 0, short_count = 0, updates = 0, unconverged = 0;
  double worst_rise = 0.0, worst_ratio = 0.0;
  Json worst_at = nullptr;
  std::vector<double> orders_32, orders_8;
  for (const Point& q : points)
  {
    const sce::BrushForces ref = steadyReference(q, transientReferenceTolerance(law));
    if (!converged(ref))
    {
      ++unconverged;
      continue;
    }
    const double floor = 1e-12 + ref.error_estimate;
    std::vector<double> e;
    for (int n : kTransientResolutions)
    {
      const HeldRun run = runHeld(q, n, ref);
      e.push_back(run.error);
      short_count += run.short_count;
      updates += run.updates;
      worst_ratio = std::max(worst_ratio, run.worst_ratio);
    }
    for (std::size_t i = 1; i < e.size(); ++i)
      if (e[i] >= e[i - 1] && e[i] > floor && e[i] / e[i - 1] > worst_rise)
      {
        worst_rise = e[i] / e[i - 1];
        worst_at = describe(q);
        worst_at["resolution"] = kTransientResolutions[i];
      }
    monotone_count += monotone(e, floor);
    if (e[2] > floor && e[4] > floor)
      orders_32.push_back(observedOrder(e, 2, 4));
    if (e[0] > floor && e[4] > floor)
      orders_8.push_back(observedOrder(e, 0, 4));
  }
  return Json{ { "name", name },
               { "points", points.size() },
               { "reference_unconverged", unconverged },
               { "monotone", monotone_count },
               { "worst_rise", worst_rise },
               { "worst_rise_at", worst_at },
               { "median_order", orders_32.empty() ? NAN : quantile(orders_32, 0.5) },
               { "median_order_8_128", orders_8.empty() ? NAN : quantile(orders_8, 0.5) },
               { "min_order_8_128", orders_8.empty() ? NAN : quantile(orders_8, 0.0) },
               { "estimate_short", short_count },
               { "updates", updates },
               { "worst_error_over_estimate", worst_ratio } };
}

// The example point of issue 11: a spin pole in the front of the patch, a re-adhering streak of 0.5 % of the patch.
Point issue11Example(bool tilt)
{
  Point q;
  q.p.a = 0.030132135540406;
  q.p.F_z = 721.6240066650845;
  q.p.mu = 0.8447950430510605;
  q.p.k = 195451215.1840554;
  q.p.tilt = tilt;
  q.sigma = { -0.009505213968784471, 0.004217246676809281 };
  q.phi = -9.057291504918961;
  q.chi = 0.9;
  return q;
}

Json transientLaw(sce::SlidingLaw law)
{
  const std::vector<std::pair<std::string, Point>> cases{
    { "example point", issue11Example(false) },
    { "example point, tilt", issue11Example(true) },
    // the sliding-law issue's example point: Fig. 4's parameters in pure spin, where the laws are 16 % apart
    { "pure spin (eq. 4b's example point)", figure4Point(false, 0.0, 0.0) },
    { "pure spin, tilt", figure4Point(true, 0.0, 0.0) },
    { "Fig. 4, (0.05, 0.02)", figure4Point(false, 0.05, 0.02) },
    { "Fig. 4, (-0.02, 0.05)", figure4Point(false, -0.02, 0.05) },
    { "Fig. 4, (0.2, 0.1)", figure4Point(false, 0.2, 0.1) },
    { "Fig. 4, (0.05, 0.02), tilt", figure4Point(true, 0.05, 0.02) },
    { "Fig. 4, (0.01, 0), tilt", figure4Point(true, 0.01, 0.0) }
  };
  Json out{ { "reference_tolerance", transientReferenceTolerance(law) } };
  for (const auto& [name, q] : cases)
    out["cases"].push_back(transientCase(name, underLaw(q, law), law));
  return out;
}

Json transientConvergence(sce::SlidingLaw law)
{
  Json out = Json::array();
  std::vector<Point> fig4[2];
  for (const Point& q : underLaw(figure4Set(), law))
    fig4[q.p.tilt].push_back(q);
  out.push_back(convergenceSummary("Fig. 4 set", fig4[0], law));
  out.push_back(convergenceSummary("Fig. 4 set, tilt", fig4[1], law));
  // random points over the envelope (the tilting radius outside the patch, where a steady state exists)
  std::vector<Point> random[2];
  for (const Point& q : underLaw(randomPoints(120, 7), law))
    if (!(q.p.tilt && std::abs(q.pg()) * q.p.a > 1.0))
      random[q.p.tilt].push_back(q);
  out.push_back(convergenceSummary("random points", random[0], law));
  out.push_back(convergenceSummary("random points, tilt", random[1], law));
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Uncertainty

// The brush forces' covariance from the slips' against Monte Carlo at random operating points, under the default
// sliding law: the slips spread by `relative` of their size (plus a floor) with a random correlation; the unscented
// transform through the steady model against 2000 draws of it (each to 1/200 of the spread): the largest relative
// error of a standard deviation and of a correlation, and where.
Json uncertaintySection()
{
  std::mt19937_64 rng(2027);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  // 60 points and 1000 draws: eq. (4b)'s steady solver at 1/200 of the spread costs ~10 ms an evaluation on random
  // points, so the rigid law's 200 x 2000 would take hours; the sampling error of a standard deviation is ~2.2 %
  constexpr int kPoints = 60, kDraws = 1000;
  const std::vector<Point> points = randomPoints(kPoints, 2027);
  const char* law = sce::toString(sce::BrushParameters{}.sliding_law);
  Json out = Json::array();
  for (double relative : { 0.02, 0.1 })
  {
    double worst_sd = 0.0, worst_corr = 0.0, sum_us = 0.0, worst_linearised = 0.0;
    double worst_sd_flagged = 0.0;  // where the transform said the forces are not smooth over the spread
    int count = 0, evaluations = 0, over = 0, flagged = 0, over_flagged = 0;
    Json worst_at = nullptr;
    for (const Point& q : points)
    {
      if (q.p.tilt && std::abs(q.pg()) * q.p.a > 0.9)
        continue;
      const Eigen::Vector3d sd(relative * std::abs(q.sigma.x()) + 1e-5, relative * std::abs(q.sigma.y()) + 1e-5,
                               relative * std::abs(q.phi) + 1e-5 / q.p.a);
      Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
      R(0, 1) = R(1, 0) = 0.6 * (2.0 * u(rng) - 1.0);
      R(1, 2) = R(2, 1) = 0.3 * (2.0 * u(rng) - 1.0);
      const Eigen::Matrix3d S = sd.asDiagonal() * R * sd.asDiagonal();
      const auto start = Clock::now();
      const sce::ForceCovariance c = sce::propagateSlipCovariance(sce::BrushModelKind::Steady, q.p, q.sigma, q.phi, q.chi, S);
      sum_us += 1e6 * seconds(start);
      evaluations += c.evaluations;
      if (!c.defined)
        continue;
      const sce::BrushSteady steady(q.p);
      const double tolerance = std::max(1e-6, 0.005 * c.spread(q.p));
      // the alternative: linearised by central differences along the principal axes (a hundredth of a standard
      // deviation each way, the steady model to 1/1000 of the spread), as cheap in evaluations
      Eigen::Matrix3d linearised = Eigen::Matrix3d::Zero();
      {
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
        const double tight = std::max(1e-9, 1e-3 * c.spread(q.p));
        const auto F = [&](const Eigen::Vector3d& x) {
          const sce::BrushForces f = steady.evaluate({ x(0), x(1) }, x(2), q.chi * x(2), (1.0 - q.chi) * x(2), tight);
          return Eigen::Vector3d(f.F_x, f.F_y, f.M_z);
        };
        const Eigen::Vector3d x0(q.sigma.x(), q.sigma.y(), q.phi);
        for (int i = 0; i < 3; ++i)
        {
          const double sd_i = std::sqrt(std::max(0.0, eig.eigenvalues()(i)));
          if (!(sd_i > 0.0))
            continue;
          const Eigen::Vector3d h = 1e-2 * sd_i * eig.eigenvectors().col(i);
          const Eigen::Vector3d d = (F(x0 + h) - F(x0 - h)) / (2e-2);  // the output's change per standard deviation
          linearised += d * d.transpose();
        }
      }
      const Eigen::LLT<Eigen::Matrix3d> llt(S);
      const Eigen::Matrix3d L = llt.matrixL();
      const int draws = kDraws;
      std::vector<Eigen::Vector3d> y;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int i = 0; i < draws; ++i)
      {
        const Eigen::Vector3d x = Eigen::Vector3d(q.sigma.x(), q.sigma.y(), q.phi) + L * Eigen::Vector3d(g(rng), g(rng), g(rng));
        const sce::BrushForces f = steady.evaluate({ x(0), x(1) }, x(2), q.chi * x(2), (1.0 - q.chi) * x(2), tolerance);
        y.emplace_back(f.F_x, f.F_y, f.M_z);
        mean += y.back();
      }
      mean /= draws;
      Eigen::Matrix3d mc = Eigen::Matrix3d::Zero();
      for (const Eigen::Vector3d& v : y)
        mc += (v - mean) * (v - mean).transpose();
      mc /= draws - 1;
      const double limit = q.p.mu * q.p.F_z;
      const Eigen::Vector3d floor(1e-5 * limit, 1e-5 * limit, 1e-5 * limit * q.p.a);
      // each standard deviation against the larger of itself and a fifth of the largest one (M_z over a): the sigma
      // points resolve the largest spread, and a component far smaller only to that
      const Eigen::Vector3d unit(1.0, 1.0, 1.0 / q.p.a);
      const double largest = mc.diagonal().cwiseSqrt().cwiseProduct(unit).maxCoeff();
      double sd_err = 0.0, corr_err = 0.0;
      for (int i = 0; i < 3; ++i)
      {
        const double b = std::sqrt(mc(i, i)), a = std::sqrt(std::max(0.0, c.covariance(i, i)));
        if (!(b > floor(i)))
          continue;
        sd_err = std::max(sd_err, std::abs(a - b) / std::max(b, 0.2 * largest / unit(i)));
        if (b < 0.2 * largest / unit(i))
          continue;  // a correlation of a component below the resolved spread: not resolved
        for (int j = i + 1; j < 3; ++j)
        {
          const double bj = std::sqrt(mc(j, j)), aj = std::sqrt(std::max(0.0, c.covariance(j, j)));
          if (bj > floor(j) && bj >= 0.2 * largest / unit(j) && a > 0.0 && aj > 0.0)
            corr_err = std::max(corr_err, std::abs(c.covariance(i, j) / (a * aj) - mc(i, j) / (b * bj)));
        }
      }
      if (!c.smooth)
      {
        ++flagged;
        over_flagged += sd_err > 0.1 || corr_err > 0.1;
        worst_sd_flagged = std::max(worst_sd_flagged, sd_err);
        ++count;
        continue;
      }
      over += sd_err > 0.1 || corr_err > 0.1;
      for (int i = 0; i < 3; ++i)
      {
        const double b = std::sqrt(mc(i, i));
        if (b > floor(i))
          worst_linearised = std::max(worst_linearised,
                                      std::abs(std::sqrt(linearised(i, i)) - b) / std::max(b, 0.2 * largest / unit(i)));
      }
      if (sd_err > worst_sd)
      {
        worst_sd = sd_err;
        worst_at = describe(q);
      }
      worst_corr = std::max(worst_corr, corr_err);
      ++count;
    }
    out.push_back(Json{ { "relative_spread", relative },
                        { "sliding_law", law },
                        { "points", count },
                        { "draws", kDraws },
                        { "worst_sd_error", worst_sd },
                        { "worst_correlation_error", worst_corr },
                        { "over_tolerance", over },
                        { "worst_at", worst_at },
                        { "mean_evaluations", count ? static_cast<double>(evaluations) / count : 0.0 },
                        { "mean_time_us", count ? sum_us / count : 0.0 },
                        { "worst_sd_error_linearised", worst_linearised },
                        { "flagged", flagged },
                        { "over_tolerance_flagged", over_flagged },
                        { "worst_sd_error_flagged", worst_sd_flagged } });
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Cylinder

void cylinderSection(Json& out)
{
  // the paper's rubber, below, at and past v*, and past the critical speed
  sce::CylinderParameters c;
  c.g = 10.0;
  const sce::CylinderExact exact(c);
  const double v_star = *exact.scales().v_star, v_c = exact.scales().v_critical;
  const std::vector<std::pair<std::string, double>> speeds{ { "0.05 m/s", 0.05 },       { "v*/2", 0.5 * v_star },
                                                            { "v*", v_star },            { "2 v*", 2.0 * v_star },
                                                            { "10 v*", 10.0 * v_star },  { "0.99 v_c", 0.99 * v_c },
                                                            { "2 v_c", 2.0 * v_c } };
  const sce::CylinderExpansion expansion(c);
  const sce::CylinderTable table(c);
  out["cylinder_speeds"] = Json{ { "v_star", v_star }, { "v_critical", v_c } };
  for (int m = 0; m < 2; ++m)
  {
    const sce::CylinderModel& model = m == 0 ? static_cast<const sce::CylinderModel&>(expansion) : table;
    Json row{ { "model", m == 0 ? "expansion" : "table" } };
    double worst = 0.0;
    for (const auto& [name, v] : speeds)
    {
      const double ref = exact.solve(v).mu_roll;
      const double e = std::abs(model.solve(v).mu_roll - ref) / ref;
      row["errors"][name] = e;
      worst = std::max(worst, e);
    }
    row["max"] = worst;
    out["cylinder"].push_back(row);
  }
}
}  // namespace

// `model_accuracy --sweep SEED N [--law coulomb|rigid]`: the steady solver's estimate against its error on N further
// random points drawn with SEED (the same draw as the random section, which uses seed 2026), at targets 1e-2, 1e-3,
// 1e-4 against the law's reference (rigid 1e-8, coulomb 1e-6; flagged references counted and left out): how often the
// estimate is below the error (beyond the reference's own estimate), the largest error / estimate and where. The
// docs/speed_and_accuracy.md's sweep figures (rigid law) come from seeds 11, 15, 16, 17 with N = 7500.
int sweep(unsigned seed, int n, sce::SlidingLaw law)
{
  const std::vector<Point> points = underLaw(randomPoints(n, seed), law);
  const double tolerance = referenceTolerance(law);
  int below = 0, unconverged = 0, comparisons = 0;
  double worst = 0.0;
  Json where = nullptr;
  for (const Point& q : points)
  {
    const sce::BrushSteady model(q.p);
    const sce::BrushForces ref = steadyReference(q, tolerance);
    if (!converged(ref))
    {
      ++unconverged;
      continue;
    }
    for (double target : kTargets)
    {
      const sce::BrushForces f = model.evaluate(q.sigma, q.phi, q.pg(), q.pp(), target);
      const double e = distance(f, ref, q.p);
      ++comparisons;
      below += e > f.error_estimate + ref.error_estimate;
      if (ratio(e, f.error_estimate) > worst)
      {
        worst = ratio(e, f.error_estimate);
        where = describe(q);
        where["target"] = target;
      }
    }
  }
  std::cout << Json{ { "seed", seed },
                     { "sliding_law", sce::toString(law) },
                     { "reference_tolerance", tolerance },
                     { "points", n },
                     { "comparisons", comparisons },
                     { "estimate_below_error", below },
                     { "max_error_over_estimate", worst },
                     { "reference_unconverged", unconverged },
                     { "worst", where } }
                   .dump()
            << "\n";
  return below == 0 ? 0 : 1;
}

// `model_accuracy --robot-histories SEED N [RES [REF]]`: the transient model's estimate at the default robot's
// parameters (config/contact_estimator.yaml: a = 1 cm, 5 kg, mu = 0.8, k = 2e8 N/m^3, parabolic pressure, no tilt) at
// resolution RES (32, auto's configured one) against REF (256) on N random noisy histories drawn with SEED, each of 24
// messages (the last 12 compared): slips and spins from 1e-3 of the envelope to all of it, noise 1e-3 to 1e-1, 0.03-2.5
// patch radii a message at 1 m/s, a third ending parked. How often the error beyond the reference's own estimate passes
// the estimate, the largest (error - reference's estimate) / estimate and where. docs/speed_and_accuracy.md's figures:
// seeds 404 (N = 300), 606 and 707 (N = 400 each).
int robotHistories(unsigned seed, int n, int resolution, int reference)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  int messages = 0, below = 0;
  double worst = -INFINITY;
  Json where = nullptr;
  std::vector<double> ratios;  // estimate / error where the error is well above the reference's estimate
  for (int h = 0; h < n; ++h)
  {
    for (int i = 0; i < 4; ++i)
      u(rng);  // (where the envelope's histories draw a, F_z, mu and k: the robot's values replace them)
    sce::BrushParameters p;
    p.a = 0.01, p.F_z = 5.0 * 9.81, p.mu = 0.8, p.k = 2e8;
    p.pressure = sce::PressureDistribution::Parabolic;
    p.tilt = false;
    p.sliding_law = sce::SlidingLaw::Coulomb;
    p.standstill_speed = 0.05;
    const sce::test::NoisyHistoryDraw draw = sce::test::drawNoisyHistory(rng, p);
    const double dt = draw.dt, noise = draw.history.noise;
    sce::BrushParameters fine = p;
    p.resolution = resolution;
    fine.resolution = reference;
    sce::BrushTransient coarse(p), exact(fine);
    for (int m = 0; m < 24; ++m)
    {
      const bool parked = draw.parked && m >= 16;
      const sce::ContactKinematics k = draw.history.message(rng, g, parked, p);  // (one g for the run: its spare draw)
      const double step = m == 0 ? 0.0 : dt;
      const sce::BrushForces c = coarse.update(k, step), f = exact.update(k, step);
      if (m < 12)
        continue;
      ++messages;
      const double e = distance(c, f, p), r = (e - f.error_estimate) / (c.error_estimate + 1e-300);
      below += r > 1.0;
      if (e > 3.0 * f.error_estimate)
        ratios.push_back(c.error_estimate / e);
      if (r > worst)
      {
        worst = r;
        where = Json{ { "history", h },         { "message", m },
                      { "roll_over_a", dt / p.a }, { "noise", noise },
                      { "parked", parked },     { "error", e },
                      { "estimate", c.error_estimate },
                      { "reference_estimate", f.error_estimate } };
      }
    }
    if (h % 50 == 49)
      std::cerr << "robot histories: " << h + 1 << " of " << n << "\n";
  }
  std::sort(ratios.begin(), ratios.end());
  std::cout << Json{ { "seed", seed },
                     { "histories", n },
                     { "resolution", resolution },
                     { "reference_resolution", reference },
                     { "messages", messages },
                     { "estimate_below_error", below },
                     { "max_error_beyond_reference_over_estimate", worst },
                     { "worst", where },
                     { "clear_errors", ratios.size() },
                     { "min_estimate_over_clear_error", ratios.empty() ? NAN : ratios.front() },
                     { "median_estimate_over_clear_error", ratios.empty() ? NAN : ratios[ratios.size() / 2] } }
                   .dump()
            << "\n";
  return below == 0 ? 0 : 1;
}

// `model_accuracy --held-transient SEED N`: the transient model at held inputs against the steady solver, on N random
// robots of stream_sweep.py's envelope (patch radius 4-50 mm, k 3e7-1e9 N/m^3, mass 1-40 kg, mu 0.3-1.2, any pressure,
// either law, no tilt) at any resolution a user may set up to 512, slips and spins from 1e-3 of |sigma| <= 0.3,
// |a phi| <= 1.5 to all of it, rolled 4a at 1 m/s in 3 to 12 updates (the bristles' paths are the same however the
// travel is split; the steps and events within each update are not). The steady solver at 1e-8 (rigid) or 1e-6
// (eq. 4b, by the general stepper: steadyReference), its own estimate as the slack; a reference flagged is counted and
// its point left out. How often the
// estimate falls below the error, the largest error / estimate and where. Seeds 1-3 found two estimates short (a long
// stiff step through a re-adhesion; the Hertzian trailing layer), docs/speed_and_accuracy.md.
int heldTransient(unsigned seed, int n)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int compared = 0, below = 0, references_flagged = 0;
  double worst = -INFINITY;
  Json where = nullptr;
  for (int i = 0; i < n; ++i)
  {
    sce::BrushParameters p;
    p.a = 0.004 * std::pow(50.0 / 4.0, u(rng));
    p.k = 3e7 * std::pow(1e9 / 3e7, u(rng));
    p.F_z = 9.81 * (1.0 + 39.0 * u(rng));
    p.mu = 0.3 + 0.9 * u(rng);
    p.pressure = static_cast<sce::PressureDistribution>(static_cast<int>(3.0 * u(rng)) % 3);
    p.sliding_law = u(rng) < 0.5 ? sce::SlidingLaw::Coulomb : sce::SlidingLaw::Rigid;
    const double scale = std::pow(10.0, -3.0 * u(rng)), heading = 2.0 * M_PI * u(rng), slip = 0.3 * scale * u(rng);
    const Eigen::Vector2d sigma = slip * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    const double phi = 1.5 * scale * (2.0 * u(rng) - 1.0) / p.a;
    p.resolution = 32 + static_cast<int>(480.0 * u(rng));
    const int updates = 3 + static_cast<int>(10.0 * u(rng)) % 10;
    const double target = p.sliding_law == sce::SlidingLaw::Rigid ? 1e-8 : 1e-6;
    const sce::BrushForces ref = sce::BrushSteady(p).evaluate(sigma, phi, phi, 0.0, target, nullptr,
                                                              sce::BrushSteady::kReferenceWork,
                                                              sce::CoulombStepper::General);
    if (!converged(ref))
    {
      ++references_flagged;
      continue;
    }
    sce::BrushTransient model(p);
    const sce::ContactKinematics k = sce::ContactKinematics::fromSlips(sigma, phi, 1.0, 1.0);
    sce::BrushForces f;
    for (int m = 0; m < updates; ++m)
      f = model.update(k, 4.0 * p.a / updates);  // 1 m/s
    ++compared;
    const double e = distance(f, ref, p), r = (e - ref.error_estimate) / (f.error_estimate + 1e-300);
    below += r > 1.0;
    if (r > worst)
    {
      worst = r;
      where = Json{ { "point", i },           { "a", p.a },
                    { "k", p.k },             { "F_z", p.F_z },
                    { "mu", p.mu },           { "pressure", sce::toString(p.pressure) },
                    { "law", sce::toString(p.sliding_law) },
                    { "sigma", { sigma.x(), sigma.y() } },
                    { "a_phi", phi * p.a },   { "resolution", p.resolution },
                    { "updates", updates },   { "error", e },
                    { "estimate", f.error_estimate } };
    }
    if (i % 100 == 99)
      std::cerr << "held transient: " << i + 1 << " of " << n << "\n";
  }
  std::cout << Json{ { "seed", seed },
                     { "points", n },
                     { "compared", compared },
                     { "references_flagged", references_flagged },
                     { "estimate_below_error", below },
                     { "max_error_beyond_reference_over_estimate", worst },
                     { "worst", where } }
                   .dump()
            << "\n";
  return below == 0 ? 0 : 1;
}

// `model_accuracy --parked-walk SEED N [DRAWS] [--without-roll-noise] [--after-skid]`: the forces' covariance while parked
// (StandstillCovariance, a random
// walk through the adhering bristles) against Monte Carlo, over N random robots of stream_sweep.py's envelope (patch
// radius 4-50 mm, k 3e7-1e9 N/m^3, mass 1-40 kg, mu 0.3-1.2, any pressure; the rest the defaults, auto) parked from
// the estimator's own start at 30, 100 or 1000 Hz for half a second (at most 300 messages) with 0.5-2 times the demo's
// noise, each over DRAWS (300) noise realisations: at a sixth, a half and the end of it, the walked standard deviations
// (F_x, F_y, M_z) over the realisations' sample ones, where every realisation walked there (not where more than half
// the bristles slide). The ratios' range, median and 5th and 95th percentiles, and where the extremes are.
// --without-roll-noise: no noise in omega_x, omega_y (the roll of the roots it gives left out, StandstillCovariance).
// --after-skid: parked after 0.1 s at 0.5 m/s with a lateral slip of 2-8 % either way, without noise (a rolled field
// whose rear bristles lie on their bounds: StandstillCovariance::band); and the walked correlations against the
// realisations' too, where both standard deviations are above a hundredth of the largest.
// docs/uncertainty.md's figures: seed 7, N = 60.
int parkedWalk(unsigned seed, int n, int draws, bool roll_noise, bool after_skid)
{
  std::mt19937_64 r(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> ratios, correlation_errors;
  Json lowest = nullptr, highest = nullptr, worst_correlation = nullptr;
  double lo = INFINITY, hi = -INFINITY;
  int checks = 0, not_walked = 0;
  for (int point = 0; point < n; ++point)
  {
    sce::EstimatorSettings s;
    double rate, scale;
    sce::test::randomParkedRobot(r, s, rate, scale);
    // the spread of the state the noise moves: with the hold (the default) a parked robot's noise moves nothing, and
    // the realisations would not spread (parkedTruth checks the held band against the truth instead)
    s.hold_within_noise = false;
    const int messages = std::min(300, static_cast<int>(0.5 * rate) + 2);
    double skid = 0.0;
    if (after_skid)
    {
      const double side = u(r) < 0.5 ? -1.0 : 1.0;
      skid = side * (0.02 + 0.06 * u(r));
    }
    Eigen::Matrix<double, 6, 1> sd;
    sd << 0.005 * scale, 0.005 * scale, 0.0, 0.02 * scale, 0.02 * scale, 0.02 * scale;  // the demo's, scaled
    if (!roll_noise)
      sd(3) = sd(4) = 0.0;
    const sce::TwistCovariance twist = sd.cwiseAbs2().asDiagonal();
    const int at[3] = { messages / 6, messages / 2, messages - 1 };
    std::vector<Eigen::Vector3d> F[3];
    Eigen::Matrix3d walked[3] = { Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero() };
    int walks[3] = { 0, 0, 0 };
    std::mt19937_64 noise(seed * 1000003ULL + point);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int d = 0; d < draws; ++d)
    {
      sce::ContactEstimator e(s);
      const int rolled = after_skid ? static_cast<int>(0.1 * rate) : 0;
      for (int k = 0; k < rolled; ++k)
      {
        // rolling at 0.5 m/s along x (ROS), sliding sideways by skid times that: V_r = R (omega_y, -omega_x)
        sce::EstimatorInput in;
        in.stamp = k / rate;
        in.omega = Eigen::Vector3d(0.0, 0.5 / s.rolling_radius, 0.0);
        in.v_contact = Eigen::Vector3d(0.5, -0.5 * skid, 0.0);
        in.twist_covariance = sce::TwistCovariance::Zero();  // the state at the stop is known
        e.update(in);
      }
      for (int k = 0; k < messages; ++k)
      {
        sce::EstimatorInput in;
        in.stamp = (rolled + k) / rate;
        in.v_contact = Eigen::Vector3d(sd(0) * g(noise), sd(1) * g(noise), 0.0);
        in.omega = Eigen::Vector3d(sd(3) * g(noise), sd(4) * g(noise), sd(5) * g(noise));
        in.twist_covariance = twist;
        const sce::ContactEstimateData* o = e.update(in);
        for (int i = 0; i < 3; ++i)
          if (o && k == at[i])
          {
            F[i].emplace_back(o->brush.F_x, o->brush.F_y, o->brush.M_z);
            if (o->covariance.brush_method == sce::CovarianceMethod::RandomWalk)
            {
              walked[i] += o->covariance.brush / draws;
              ++walks[i];
            }
          }
      }
    }
    for (int i = 0; i < 3; ++i)
    {
      ++checks;
      if (walks[i] < draws || static_cast<int>(F[i].size()) < draws)
      {
        ++not_walked;
        continue;
      }
      const Eigen::Matrix3d mc = sce::sampleCovariance(F[i]);
      const double largest = mc.diagonal().maxCoeff();
      for (int j = 0; j < 3; ++j)
        for (int l = j + 1; l < 3; ++l)
        {
          if (!(mc(j, j) > 1e-4 * largest && mc(l, l) > 1e-4 * largest))
            continue;
          const double error = std::abs(walked[i](j, l) / std::sqrt(walked[i](j, j) * walked[i](l, l)) -
                                        mc(j, l) / std::sqrt(mc(j, j) * mc(l, l)));
          correlation_errors.push_back(error);
          if (worst_correlation.is_null() || error > worst_correlation["error"].get<double>())
            worst_correlation = Json{ { "point", point }, { "message", at[i] }, { "pair", std::to_string(j) + std::to_string(l) },
                                      { "error", error }, { "rate", rate }, { "skid", skid } };
        }
      for (int j = 0; j < 3; ++j)
      {
        if (!(mc(j, j) > 0.0))
          continue;
        const double q = std::sqrt(walked[i](j, j) / mc(j, j));
        ratios.push_back(q);
        const Json where{ { "point", point },
                          { "message", at[i] },
                          { "component", j },
                          { "ratio", q },
                          { "patch_radius", s.patch_radius },
                          { "bristle_stiffness", s.bristle_stiffness },
                          { "robot_mass", s.robot_mass },
                          { "friction", s.friction },
                          { "pressure", sce::toString(s.pressure) },
                          { "rate", rate },
                          { "noise_scale", scale },
                          { "skid", skid },
                          { "spread", s.friction > 0.0 ? std::sqrt(walked[i](j, j)) /
                                                             (s.friction * s.verticalLoad() * (j == 2 ? s.patch_radius : 1.0))
                                                       : 0.0 } };
        if (q < lo)
          lo = q, lowest = where;
        if (q > hi)
          hi = q, highest = where;
      }
    }
    std::cerr << "parked walk: " << point + 1 << " of " << n << "\n";
  }
  std::sort(ratios.begin(), ratios.end());
  const auto percentile = [&](double q) {
    return ratios.empty() ? NAN : ratios[std::min(ratios.size() - 1, static_cast<std::size_t>(q * ratios.size()))];
  };
  std::sort(correlation_errors.begin(), correlation_errors.end());
  std::cout << Json{ { "seed", seed },
                     { "robots", n },
                     { "draws", draws },
                     { "roll_noise", roll_noise },
                     { "after_skid", after_skid },
                     { "correlation_error_median",
                       correlation_errors.empty() ? NAN : correlation_errors[correlation_errors.size() / 2] },
                     { "correlation_error_p95",
                       correlation_errors.empty()
                           ? NAN
                           : correlation_errors[std::min(correlation_errors.size() - 1,
                                                         static_cast<std::size_t>(0.95 * correlation_errors.size()))] },
                     { "worst_correlation", worst_correlation },
                     { "p05", percentile(0.05) },
                     { "p95", percentile(0.95) },
                     { "checks", checks },
                     { "not_walked", not_walked },
                     { "ratios", ratios.size() },
                     { "min", lo },
                     { "median", ratios.empty() ? NAN : ratios[ratios.size() / 2] },
                     { "max", hi },
                     { "lowest", lowest },
                     { "highest", highest } }
                   .dump(1)
            << "\n";
  return 0;
}

// `model_accuracy --parked-truth SEED N`: the held estimate's band against the truth over N random robots
// (test::ParkedStreams: the envelope, a noise-free motion, then a second parked with noise; docs/uncertainty.md, "Held:
// the band about the truth"). At every parked message each of F_x, F_y and M_z must lie within 2 sd of the truth's
// (the covariance published, where there is one; else equal to it). The same with hold_within_noise off, for contrast
// (the noise ratchets the bristles off their bounds). Exit 1 where a message with the hold lies outside.
int parkedTruth(unsigned seed, int n)
{
  std::mt19937_64 r(seed);
  long messages = 0, held = 0, no_band = 0, outside[2] = { 0, 0 };
  int robots_outside[2] = { 0, 0 };
  // the largest miss beyond 2 sd and the largest error, in mu F_z (M_z: mu F_z a)
  double worst_excess[2] = { 0.0, 0.0 }, worst_error[2] = { 0.0, 0.0 };
  Json worst[2] = { nullptr, nullptr };
  for (int point = 0; point < n; ++point)
  {
    const sce::test::ParkedStreams streams(r, seed * 1000003U + static_cast<unsigned>(point));
    sce::EstimatorSettings s = streams.settings;
    for (int hold = 1; hold >= 0; --hold)
    {
      s.hold_within_noise = hold != 0;
      sce::ContactEstimator e(s), truth(s);
      bool robot_outside = false;
      for (std::size_t k = 0; k < streams.noisy.size(); ++k)
      {
        const sce::ContactEstimateData o = *e.update(streams.noisy[k]);
        const sce::ContactEstimateData& t = *truth.update(streams.clean[k]);
        if (static_cast<int>(k) < streams.moving)
          continue;
        const sce::test::ParkedStreams::Band band = streams.band(o, t);
        if (hold)
        {
          ++messages;
          held += (o.flags & sce::estimate_flags::kMotionHeld) != 0;
          no_band += !band.published;
        }
        Eigen::Index j = 0;
        const double miss = band.largestMiss(&j);
        outside[hold] += miss > 1e-12;
        robot_outside = robot_outside || miss > 1e-12;
        worst_error[hold] = std::max(worst_error[hold], band.error.cwiseAbs().maxCoeff());
        if (miss > worst_excess[hold])
        {
          worst_excess[hold] = miss;
          worst[hold] = Json{ { "point", point },
                              { "kind", sce::test::ParkedStreams::kindName(streams.kind) },
                              { "message", static_cast<long>(k) - streams.moving },
                              { "component", static_cast<int>(j) },
                              { "error_over_mu_F_z", std::abs(band.error(j)) },
                              { "sd_over_mu_F_z", band.sd(j) },
                              { "covariance_method", sce::toString(o.covariance.brush_method) },
                              { "patch_radius", s.patch_radius },
                              { "bristle_stiffness", s.bristle_stiffness },
                              { "robot_mass", s.robot_mass },
                              { "friction", s.friction },
                              { "pressure", sce::toString(s.pressure) },
                              { "rate", streams.rate },
                              { "noise_scale", streams.noise_scale } };
        }
      }
      robots_outside[hold] += robot_outside;
    }
    if ((point + 1) % 50 == 0 || point + 1 == n)
      std::cerr << "parked truth: " << point + 1 << " of " << n << "\n";
  }
  std::cout << Json{ { "seed", seed },
                     { "robots", n },
                     { "parked_messages", messages },
                     { "held", held },
                     { "without_band", no_band },
                     { "outside_with_hold", outside[1] },
                     { "robots_outside_with_hold", robots_outside[1] },
                     { "largest_miss_beyond_2sd_over_mu_F_z_with_hold", worst_excess[1] },
                     { "largest_error_over_mu_F_z_with_hold", worst_error[1] },
                     { "worst_with_hold", worst[1] },
                     { "outside_without_hold", outside[0] },
                     { "robots_outside_without_hold", robots_outside[0] },
                     { "largest_miss_beyond_2sd_over_mu_F_z_without_hold", worst_excess[0] },
                     { "largest_error_over_mu_F_z_without_hold", worst_error[0] },
                     { "worst_without_hold", worst[0] } }
                   .dump(1)
            << "\n";
  return outside[1] == 0 ? 0 : 1;
}

int usage()
{
  std::cerr << "usage: model_accuracy [N] | --sweep SEED N [--law coulomb|rigid] | --robot-histories SEED N "
               "[RES [REF]] | --held-transient SEED N | --uncertainty | --parked-walk SEED N [DRAWS] [--without-roll-noise] [--after-skid] | --parked-truth SEED N\n";
  return 2;
}

// A whole decimal number in [lo, hi], or nothing (no exception on text).
int main(int argc, char** argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h"))
  {
    std::cout << "usage: model_accuracy [N] | --sweep SEED N [--law coulomb|rigid] | --robot-histories SEED N "
                 "[RES [REF]] | --held-transient SEED N | --uncertainty | --parked-walk SEED N [DRAWS] [--without-roll-noise] [--after-skid] | --parked-truth SEED N\n"
                 "  N: random operating points (default 1000); JSON on stdout, progress on stderr\n";
    return 0;
  }
  if (!args.empty() && args[0] == "--sweep")
  {
    if (args.size() != 3 && !(args.size() == 5 && args[3] == "--law"))
      return usage();
    const std::optional<sce::SlidingLaw> law =
        args.size() == 5 ? sce::parseSlidingLaw(args[4]) : std::optional<sce::SlidingLaw>(sce::SlidingLaw::Coulomb);
    const std::optional<long> seed = wholeNumber(args[1], 0, 4294967295L), n = wholeNumber(args[2], 1, 10000000);
    if (!law || !seed || !n)
      return usage();
    return sweep(static_cast<unsigned>(*seed), static_cast<int>(*n), *law);
  }
  if (!args.empty() && args[0] == "--robot-histories")
  {
    if (args.size() < 3 || args.size() > 5)
      return usage();
    const std::optional<long> seed = wholeNumber(args[1], 0, 4294967295L), n = wholeNumber(args[2], 1, 1000000);
    const std::optional<long> res = args.size() > 3 ? wholeNumber(args[3], 8, 512) : std::optional<long>(32);
    const std::optional<long> ref = args.size() > 4 ? wholeNumber(args[4], 16, 1024) : std::optional<long>(256);
    if (!seed || !n || !res || !ref || *ref <= *res)
      return usage();
    return robotHistories(static_cast<unsigned>(*seed), static_cast<int>(*n), static_cast<int>(*res),
                          static_cast<int>(*ref));
  }
  // MODE SEED N
  const auto seedAndCount = [&](const char* mode, long max_n, int (*run)(unsigned, int)) -> std::optional<int> {
    if (args.empty() || args[0] != mode)
      return std::nullopt;
    const std::optional<long> seed = args.size() == 3 ? wholeNumber(args[1], 0, 4294967295L) : std::nullopt;
    const std::optional<long> n = args.size() == 3 ? wholeNumber(args[2], 1, max_n) : std::nullopt;
    if (!seed || !n)
      return usage();
    return run(static_cast<unsigned>(*seed), static_cast<int>(*n));
  };
  if (const std::optional<int> status = seedAndCount("--held-transient", 1000000, heldTransient))
    return *status;
  if (const std::optional<int> status = seedAndCount("--parked-truth", 100000, parkedTruth))
    return *status;
  if (!args.empty() && args[0] == "--parked-walk")
  {
    std::vector<std::string> rest(args.begin() + 1, args.end());
    const bool roll_noise = std::find(rest.begin(), rest.end(), "--without-roll-noise") == rest.end();
    rest.erase(std::remove(rest.begin(), rest.end(), "--without-roll-noise"), rest.end());
    const bool after_skid = std::find(rest.begin(), rest.end(), "--after-skid") != rest.end();
    rest.erase(std::remove(rest.begin(), rest.end(), "--after-skid"), rest.end());
    if (rest.size() < 2 || rest.size() > 3)
      return usage();
    const std::optional<long> seed = wholeNumber(rest[0], 0, 4294967295L), n = wholeNumber(rest[1], 1, 100000);
    const std::optional<long> draws = rest.size() > 2 ? wholeNumber(rest[2], 10, 100000) : std::optional<long>(300);
    if (!seed || !n || !draws)
      return usage();
    return parkedWalk(static_cast<unsigned>(*seed), static_cast<int>(*n), static_cast<int>(*draws), roll_noise,
                      after_skid);
  }
  const auto start = Clock::now();
  Json out;
  if (!args.empty() && args[0] == "--uncertainty")
  {
    out["uncertainty"] = uncertaintySection();
    std::cout << out.dump(1) << "\n";
    return 0;
  }
  const std::optional<long> n = args.empty() ? std::optional<long>(1000) : wholeNumber(args[0], 1, 10000000);
  if (!n || args.size() > 1)
    return usage();
  out["random"] = randomSection(static_cast<int>(*n), start);
  out["figure4"] = figure4Section(start);
  for (sce::SlidingLaw law : kLaws)
  {
    out["transient"][sce::toString(law)] = transientLaw(law);
    out["transient_convergence"][sce::toString(law)] = transientConvergence(law);
    progress(std::string("transient, ") + sce::toString(law), start);
  }
  out["uncertainty"] = uncertaintySection();
  progress("uncertainty", start);
  cylinderSection(out);
  out["run_seconds"] = seconds(start);
  std::cout << out.dump(1) << "\n";
  return 0;
}
