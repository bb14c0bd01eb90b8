// Accuracy of every model against converged references, printed as JSON for scripts/benchmark_report.py.
//
// Brush: errors are max(|dF_x|, |dF_y|, |dM_z| / a) / (mu F_z).
//  - random: a seeded random set of operating points over the envelope a user reaches (a = 0.01-0.08 m,
//    F_z = 20-5000 N, mu = 0.2-1.2, k = 10^6.5-10^9 N/m^3, |sigma_x| <= 0.3, |sigma_y| <= 0.1, |a phi| <= 1,
//    tilt ratios -0.5..1.5; the three pressures, tilt and no tilt; slips and spins scaled by 10^-3..1): the steady
//    model at targets 1e-2, 1e-3, 1e-4 against itself at 1e-8 (whose own agreement with the independent
//    brute-force marcher of test/support is measured on a subset), the error estimate against the error, the
//    linear model's bound, and auto at its targets with the inputs held (a robot rolling at 1 m/s, 100 Hz).
//  - figure4: the paper's Fig. 4 curves (sigma_x in [-1, 1], sigma_y in {0, 0.05, 0.1, 0.2}, phi = 3.33 1/m,
//    chi_gamma = 0.9, tilt and no tilt): the old marching scheme by resolution.
//  - transient: the transient model at held inputs, by resolution (its largest error and estimate over two lattice
//    spacings of travel after 6a), at the example point and at Fig. 4 points; over the whole Fig. 4 set and
//    random points, how many converge monotonically, the observed order and how often the estimate fell short.
//  - uncertainty: the forces' covariance from the slips' (the unscented transform through the steady model) against
//    Monte Carlo at random operating points, at two spreads of the slips.
// Cylinder: |d mu_roll| / mu_roll on the paper's rubber (g = 10) against the exact solution of eq. 18.

// STL
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

// Eigen
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

// Package
#include "brush_brute_force.h"
#include "brush_marching.h"
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "sphere_contact_estimator/core/brush/force_covariance.h"
#include "sphere_contact_estimator/core/numerics/unscented_transform.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

namespace sce = sphere_contact_estimator;

namespace
{
struct Point
{
  sce::BrushParameters p;
  Eigen::Vector2d sigma;
  double phi = 0.0, chi = 1.0;
  double pg() const { return chi * phi; }
  double pp() const { return phi - chi * phi; }
};

double distance(const sce::BrushForces& f, const sce::BrushForces& g, const sce::BrushParameters& p)
{
  return std::max({ std::abs(f.F_x - g.F_x), std::abs(f.F_y - g.F_y), std::abs(f.M_z - g.M_z) / p.a }) / (p.mu * p.F_z);
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

std::string describe(const Point& q)
{
  char s[512];
  std::snprintf(s, sizeof(s),
                "\"pressure\": \"%s\", \"tilt\": %s, \"a\": %.6g, \"F_z\": %.6g, \"mu\": %.4g, \"k\": %.4g, "
                "\"sigma_x\": %.6g, \"sigma_y\": %.6g, \"phi\": %.6g, \"chi_gamma\": %.4g",
                sce::toString(q.p.pressure), q.p.tilt ? "true" : "false", q.p.a, q.p.F_z, q.p.mu, q.p.k, q.sigma.x(),
                q.sigma.y(), q.phi, q.chi);
  return s;
}

void randomSection(int n)
{
  const std::vector<Point> points = randomPoints(n, 2026);
  std::vector<sce::BrushForces> ref;
  for (const Point& q : points)
    ref.push_back(
        sce::BrushSteady(q.p).evaluate(q.sigma, q.phi, q.pg(), q.pp(), 1e-8, nullptr, sce::BrushSteady::kReferenceWork));

  std::printf("  \"random\": {\n    \"points\": %d,\n    \"steady\": [", n);
  bool first = true;
  for (double target : { 1e-2, 1e-3, 1e-4 })
  {
    double worst = 0.0, worst_ratio = 0.0;
    int below = 0, below_half = 0, over = 0, worst_i = 0;
    std::vector<double> times;
    for (int i = 0; i < n; ++i)
    {
      const Point& q = points[i];
      const sce::BrushSteady model(q.p);
      const auto t0 = std::chrono::steady_clock::now();
      const sce::BrushForces f = model.evaluate(q.sigma, q.phi, q.pg(), q.pp(), target);
      times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
      const double e = distance(f, ref[i], q.p);
      if (e > worst)
        worst = e, worst_i = i;
      worst_ratio = std::max(worst_ratio, f.error_estimate > 0.0 ? e / f.error_estimate : (e > 0.0 ? INFINITY : 0.0));
      below += e > f.error_estimate;
      below_half += e > 2.0 * f.error_estimate;
      over += e > target;
    }
    std::sort(times.begin(), times.end());
    std::printf("%s\n      {\"target\": %g, \"max_error\": %.3g, \"over_target\": %d, \"estimate_below_error\": %d, "
                "\"estimate_below_half_error\": %d, \"max_error_over_estimate\": %.3g, \"median_us\": %.3g, "
                "\"p99_us\": %.3g, \"worst\": {%s}}",
                first ? "" : ",", target, worst, over, below, below_half, worst_ratio, times[n / 2], times[n * 99 / 100],
                describe(points[worst_i]).c_str());
    first = false;
  }
  // the reference against the independent brute-force marcher on a subset (8000 paths, 400 steps: its own error
  // is ~3e-5 of mu F_z where a re-adhering island lies in the patch, far less elsewhere)
  double bf_worst = 0.0;
  const int subset = std::min(n, 48);
  for (int i = 0; i < subset; ++i)
  {
    const Point& q = points[i * (n / subset)];
    bf_worst = std::max(bf_worst, distance(ref[i * (n / subset)],
                                           sce::test::bruteForceSteady(q.p, q.sigma, q.phi, q.pg(), q.pp(), 8000, 400), q.p));
  }
  // the reference's own estimate: it is converged only if every evaluation met 1e-8 within the reference budget
  int ref_unconverged = 0;
  double ref_estimate = 0.0;
  for (const sce::BrushForces& r : ref)
  {
    ref_unconverged += (r.flags & sce::brush_flags::kAccuracyNotMet) != 0;
    ref_estimate = std::max(ref_estimate, r.error_estimate);
  }
  std::printf("\n    ],\n    \"reference_vs_brute_force\": {\"points\": %d, \"max_difference\": %.3g},\n", subset, bf_worst);
  std::printf("    \"reference\": {\"unconverged\": %d, \"max_estimate\": %.3g},\n", ref_unconverged, ref_estimate);

  // the linear model's bound where auto could pick it
  double lin_ratio = 0.0;
  int lin_checked = 0, lin_over = 0;
  for (int i = 0; i < n; ++i)
  {
    const Point& q = points[i];
    const double bound = sce::BrushLinear::errorBound(q.p, q.sigma, q.phi, q.pg(), q.pp());
    if (bound > 0.1 || bound <= 0.0)
      continue;
    const double e = distance(sce::BrushLinear(q.p).evaluate(q.sigma, q.phi), ref[i], q.p);
    ++lin_checked;
    lin_over += e > bound;
    lin_ratio = std::max(lin_ratio, e / bound);
  }
  std::printf("    \"linear_bound\": {\"points\": %d, \"error_over_bound\": %d, \"max_error_over_bound\": %.3g},\n",
              lin_checked, lin_over, lin_ratio);

  // auto with held inputs
  std::printf("    \"auto\": [");
  first = true;
  for (double target : { 1e-3, 1e-2, 5e-2 })
  {
    double worst = 0.0;
    int over = 0, short_estimate = 0, worst_i = 0, used[3] = { 0, 0, 0 };
    for (int i = 0; i < n; ++i)
    {
      Point q = points[i];
      q.p.accuracy_target = target;
      sce::BrushAuto model(q.p);
      const sce::ContactKinematics k = sce::ContactKinematics::fromSlips(q.sigma, q.phi, q.chi, 1.0);
      sce::BrushForces f;
      for (int step = 0; step < 5; ++step)
        f = model.update(k, 0.01);
      const double e = distance(f, ref[i], q.p);
      if (e > worst)
        worst = e, worst_i = i;
      over += e > target;
      short_estimate += e > f.error_estimate;
      // linear, steady, transient (BrushModelKind numbers them from 1: Off is 0)
      ++used[static_cast<int>(model.lastModel()) - static_cast<int>(sce::BrushModelKind::Linear)];
    }
    std::printf("%s\n      {\"target\": %g, \"max_error\": %.3g, \"over_target\": %d, \"estimate_below_error\": %d, "
                "\"linear\": %d, \"steady\": %d, \"transient\": %d, \"worst\": {%s}}",
                first ? "" : ",", target, worst, over, short_estimate, used[0], used[1], used[2],
                describe(points[worst_i]).c_str());
    first = false;
  }
  std::printf("\n    ]\n  },\n");
}

sce::BrushParameters figure4(bool tilt)
{
  sce::BrushParameters p;  // a = 0.05 m, k = 1.023e8, F_z = 3000 N, mu = 1: the paper's Fig. 4
  p.tilt = tilt;
  return p;
}

void figure4Section()
{
  // the old marching scheme over the Fig. 4 set, by resolution
  std::vector<Point> set;
  for (int tilt = 0; tilt < 2; ++tilt)
    for (double sy : { 0.0, 0.05, 0.1, 0.2 })
      for (int i = 0; i <= 20; ++i)
      {
        Point q;
        q.p = figure4(tilt);
        q.sigma = Eigen::Vector2d(-1.0 + 0.1 * i, sy);
        q.phi = 3.33;
        q.chi = 0.9;
        set.push_back(q);
      }
  std::vector<sce::BrushForces> ref;
  for (const Point& q : set)
    ref.push_back(
        sce::BrushSteady(q.p).evaluate(q.sigma, q.phi, q.pg(), q.pp(), 1e-8, nullptr, sce::BrushSteady::kReferenceWork));
  std::printf("  \"figure4\": {\"points\": %zu, \"steady\": [", set.size());
  for (double target : { 1e-2, 1e-3, 1e-4 })
  {
    double worst[2] = { 0.0, 0.0 };
    int below = 0;
    for (std::size_t i = 0; i < set.size(); ++i)
    {
      const sce::BrushForces f = sce::BrushSteady(set[i].p).evaluate(set[i].sigma, set[i].phi, set[i].pg(), set[i].pp(), target);
      const double e = distance(f, ref[i], set[i].p);
      worst[set[i].p.tilt] = std::max(worst[set[i].p.tilt], e);
      below += e > f.error_estimate;
    }
    std::printf("%s\n    {\"target\": %g, \"max_error\": %.3g, \"max_error_tilt\": %.3g, \"estimate_below_error\": %d}",
                target == 1e-2 ? "" : ",", target, worst[0], worst[1], below);
  }
  std::printf("\n  ], \"marching\": [");
  bool first = true;
  for (int n : { 4, 8, 12, 16, 24, 32, 48, 64, 96, 128 })
  {
    double worst[2] = { 0.0, 0.0 };
    for (std::size_t i = 0; i < set.size(); ++i)
    {
      sce::BrushParameters p = set[i].p;
      p.resolution = n;
      const sce::BrushForces f = sce::test::BrushMarching(p).evaluate(set[i].sigma, set[i].phi, set[i].pg(), set[i].pp());
      worst[p.tilt] = std::max(worst[p.tilt], distance(f, ref[i], p));
    }
    std::printf("%s\n    {\"resolution\": %d, \"max_error\": %.3g, \"max_error_tilt\": %.3g}", first ? "" : ",", n, worst[0],
                worst[1]);
    first = false;
  }
  std::printf("\n  ]},\n");
}

// The transient model at held inputs (1 m/s): after 6a of travel and then over two lattice spacings more, the largest
// error against `ref` and the largest estimate; and whether the estimate covered the error at every one of those
// updates (its error moves with where the lattice stands, so one sample can be lucky).
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
    if (f.error_estimate < e)
    {
      ++run.short_count;
      run.worst_ratio = std::max(run.worst_ratio, e / f.error_estimate);
    }
  }
  return run;
}

// Over a set of points: how many converge monotonically over the resolutions (largest error over the lattice
// positions), the largest rise where not and where, the median observed order from 32 to 128, and the estimate.
void convergenceSummary(const char* name, const std::vector<Point>& points, const std::vector<int>& resolutions)
{
  int monotone = 0, short_count = 0, updates = 0;
  double worst_rise = 0.0, worst_ratio = 0.0;
  std::string worst_at = "null";
  std::vector<double> orders;
  for (const Point& q : points)
  {
    const sce::BrushForces ref =
        sce::BrushSteady(q.p).evaluate(q.sigma, q.phi, q.pg(), q.pp(), 1e-10, nullptr, sce::BrushSteady::kReferenceWork);
    std::vector<double> e;
    for (int n : resolutions)
    {
      const HeldRun run = runHeld(q, n, ref);
      e.push_back(run.error);
      short_count += run.short_count;
      updates += run.updates;
      worst_ratio = std::max(worst_ratio, run.worst_ratio);
    }
    bool ok = true;
    for (std::size_t i = 1; i < e.size(); ++i)
      if (e[i] >= e[i - 1] && e[i] > 1e-12)
      {
        ok = false;
        if (e[i] / e[i - 1] > worst_rise)
        {
          worst_rise = e[i] / e[i - 1];
          worst_at = "{" + describe(q) + ", \"resolution\": " + std::to_string(resolutions[i]) + "}";
        }
      }
    monotone += ok;
    if (e.size() >= 5 && e[2] > 1e-12 && e[4] > 1e-12)
      orders.push_back(std::log2(e[2] / e[4]) / 2.0);
  }
  std::sort(orders.begin(), orders.end());
  std::printf("    {\"name\": \"%s\", \"points\": %zu, \"monotone\": %d, \"worst_rise\": %.3g, \"worst_rise_at\": %s, "
              "\"median_order\": %.3g, \"estimate_short\": %d, \"updates\": %d, \"worst_error_over_estimate\": %.3g}",
              name, points.size(), monotone, worst_rise, worst_at.c_str(), orders.empty() ? 0.0 : orders[orders.size() / 2],
              short_count, updates, worst_ratio);
}

void transientSection()
{
  Point example;
  example.p.a = 0.030132135540406;
  example.p.F_z = 721.6240066650845;
  example.p.mu = 0.8447950430510605;
  example.p.k = 195451215.1840554;
  example.sigma = { -0.009505213968784471, 0.004217246676809281 };
  example.phi = -9.057291504918961;
  example.chi = 0.9;
  const auto fig4 = [](bool tilt, double sx, double sy) {
    Point q;
    q.p = figure4(tilt);
    q.sigma = { sx, sy };
    q.phi = 3.33;
    q.chi = 0.9;
    return q;
  };
  Point example_tilt = example;
  example_tilt.p.tilt = true;
  const std::vector<std::pair<const char*, Point>> cases{
    { "example point", example },
    { "example point, tilt", example_tilt },
    { "Fig. 4, (0.05, 0.02)", fig4(false, 0.05, 0.02) },
    { "Fig. 4, (-0.02, 0.05)", fig4(false, -0.02, 0.05) },
    { "Fig. 4, (0.2, 0.1)", fig4(false, 0.2, 0.1) },
    { "Fig. 4, (0.05, 0.02), tilt", fig4(true, 0.05, 0.02) },
    { "Fig. 4, (0.01, 0), tilt", fig4(true, 0.01, 0.0) }
  };
  const std::vector<int> resolutions{ 8, 16, 32, 64, 128 };
  std::printf("  \"transient\": [");
  bool first = true;
  for (const auto& [name, q] : cases)
  {
    const sce::BrushForces ref =
        sce::BrushSteady(q.p).evaluate(q.sigma, q.phi, q.pg(), q.pp(), 1e-10, nullptr, sce::BrushSteady::kReferenceWork);
    std::printf("%s\n    {\"name\": \"%s\", \"runs\": [", first ? "" : ",", name);
    bool first_run = true;
    for (int n : resolutions)
    {
      const HeldRun run = runHeld(q, n, ref);
      std::printf("%s{\"resolution\": %d, \"error\": %.3g, \"estimate\": %.3g}", first_run ? "" : ", ", n, run.error,
                  run.estimate);
      first_run = false;
    }
    std::printf("]}");
    first = false;
  }
  std::printf("\n  ],\n  \"transient_convergence\": [\n");
  for (int tilt = 0; tilt < 2; ++tilt)
  {
    std::vector<Point> set;
    for (double sy : { 0.0, 0.05, 0.1, 0.2 })
      for (int i = -10; i <= 10; ++i)
        set.push_back(fig4(tilt, 0.1 * i, sy));
    convergenceSummary(tilt ? "Fig. 4 set, tilt" : "Fig. 4 set", set, resolutions);
    std::printf(",\n");
  }
  // random points over the envelope (the tilting radius outside the patch, where a steady state exists)
  std::vector<Point> random[2];
  for (const Point& q : randomPoints(120, 7))
    if (!(q.p.tilt && std::abs(q.pg()) * q.p.a > 1.0))
      random[q.p.tilt].push_back(q);
  convergenceSummary("random points", random[0], resolutions);
  std::printf(",\n");
  convergenceSummary("random points, tilt", random[1], resolutions);
  std::printf("\n  ],\n");
}

// The brush forces' covariance from the slips' against Monte Carlo at random operating points: the slips spread by
// `relative` of their size (plus a floor) with a random correlation; the unscented transform through the steady
// model against `draws` draws of it (each to 1/200 of the spread): the largest relative error of a standard
// deviation and of a correlation, and where.
void uncertaintySection()
{
  std::mt19937_64 rng(2027);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  const std::vector<Point> points = randomPoints(200, 2027);
  std::printf("  \"uncertainty\": [");
  bool first = true;
  for (double relative : { 0.02, 0.1 })
  {
    double worst_sd = 0.0, worst_corr = 0.0, sum_us = 0.0, worst_linearised = 0.0;
    double worst_sd_flagged = 0.0;  // where the transform said the forces are not smooth over the spread
    int count = 0, evaluations = 0, over = 0, flagged = 0, over_flagged = 0;
    std::string worst_at = "null";
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
      const auto start = std::chrono::steady_clock::now();
      const sce::ForceCovariance c = sce::propagateSlipCovariance(sce::BrushModelKind::Steady, q.p, q.sigma, q.phi, q.chi, S);
      sum_us += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
      evaluations += c.evaluations;
      if (!c.defined)
        continue;
      const sce::BrushSteady steady(q.p);
      const double tolerance = std::max(1e-7, 0.005 * c.spread(q.p));
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
      const int draws = 2000;
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
        worst_at = "{" + describe(q) + "}";
      }
      worst_corr = std::max(worst_corr, corr_err);
      ++count;
    }
    std::printf("%s\n    {\"relative_spread\": %g, \"points\": %d, \"draws\": 2000, \"worst_sd_error\": %.3g, "
                "\"worst_correlation_error\": %.3g, \"over_tolerance\": %d, \"worst_at\": %s, \"mean_evaluations\": %.2f, "
                "\"mean_time_us\": %.1f, \"worst_sd_error_linearised\": %.3g, \"flagged\": %d, \"over_tolerance_flagged\": %d, "
                "\"worst_sd_error_flagged\": %.3g}",
                first ? "" : ",", relative, count, worst_sd, worst_corr, over, worst_at.c_str(),
                count ? static_cast<double>(evaluations) / count : 0.0, count ? sum_us / count : 0.0, worst_linearised,
                flagged, over_flagged, worst_sd_flagged);
    first = false;
  }
  std::printf("\n  ],\n");
}

void cylinderSection()
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
  std::printf("  \"cylinder_speeds\": {\"v_star\": %.6g, \"v_critical\": %.6g},\n  \"cylinder\": [\n", v_star, v_c);
  for (int m = 0; m < 2; ++m)
  {
    const sce::CylinderModel& model = m == 0 ? static_cast<const sce::CylinderModel&>(expansion) : table;
    std::printf("%s    {\"model\": \"%s\", \"errors\": {", m ? ",\n" : "", m == 0 ? "expansion" : "table");
    double worst = 0.0;
    for (std::size_t i = 0; i < speeds.size(); ++i)
    {
      const double ref = exact.solve(speeds[i].second).mu_roll;
      const double e = std::abs(model.solve(speeds[i].second).mu_roll - ref) / ref;
      std::printf("%s\"%s\": %.6g", i ? ", " : "", speeds[i].first.c_str(), e);
      worst = std::max(worst, e);
    }
    std::printf("}, \"max\": %.6g}", worst);
  }
  std::printf("\n  ]\n");
}
}  // namespace

// `model_accuracy --sweep SEED N`: the steady solver's estimate against its error on N further random points drawn
// with SEED (the same draw as the random section, which uses seed 2026), at targets 1e-2, 1e-3, 1e-4 against the
// reference at 1e-8: how often the estimate is below the error (beyond the reference's own estimate), the largest
// error / estimate and where. The README's sweep figures come from seeds 11, 15, 16, 17 with N = 7500.
int sweep(unsigned seed, int n)
{
  const std::vector<Point> points = randomPoints(n, seed);
  int below = 0, unconverged = 0;
  double worst = 0.0;
  std::string where = "none";
  for (const Point& q : points)
  {
    const sce::BrushSteady model(q.p);
    const sce::BrushForces ref =
        model.evaluate(q.sigma, q.phi, q.pg(), q.pp(), 1e-8, nullptr, sce::BrushSteady::kReferenceWork);
    unconverged += (ref.flags & sce::brush_flags::kAccuracyNotMet) != 0;
    for (double target : { 1e-2, 1e-3, 1e-4 })
    {
      const sce::BrushForces f = model.evaluate(q.sigma, q.phi, q.pg(), q.pp(), target);
      const double e = distance(f, ref, q.p);
      below += e > f.error_estimate + ref.error_estimate;
      const double ratio = f.error_estimate > 0.0 ? e / f.error_estimate : (e > 0.0 ? INFINITY : 0.0);
      if (ratio > worst)
      {
        worst = ratio;
        where = describe(q) + ", \"target\": " + std::to_string(target);
      }
    }
  }
  std::printf("{\"seed\": %u, \"points\": %d, \"comparisons\": %d, \"estimate_below_error\": %d, "
              "\"max_error_over_estimate\": %.3g, \"reference_unconverged\": %d, \"worst\": {%s}}\n",
              seed, n, 3 * n, below, worst, unconverged, where.c_str());
  return below == 0 ? 0 : 1;
}

int main(int argc, char** argv)
{
  if (argc == 4 && std::string(argv[1]) == "--sweep")
    return sweep(static_cast<unsigned>(std::atoi(argv[2])), std::atoi(argv[3]));
  if (argc == 2 && std::string(argv[1]) == "--uncertainty")
  {
    std::printf("{\n");
    uncertaintySection();
    std::printf("  \"end\": null\n}\n");
    return 0;
  }
  const int n = argc > 1 ? std::atoi(argv[1]) : 1000;
  std::printf("{\n");
  randomSection(n);
  figure4Section();
  transientSection();
  uncertaintySection();
  cylinderSection();
  std::printf("}\n");
  return 0;
}
