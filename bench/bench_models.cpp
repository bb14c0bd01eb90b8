// Time per evaluation of every model and resolution (Google Benchmark). Accuracy is measured separately
// (bench/model_accuracy.cpp); scripts/benchmark.sh joins the two into docs/benchmarks.md.

// STL
#include <algorithm>
#include <cmath>
#include <random>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

// Google Benchmark
#include <benchmark/benchmark.h>

// Package
#include "brush_marching.h"
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "sphere_contact_estimator/core/brush/force_covariance.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

namespace sce = sphere_contact_estimator;

namespace
{
// The sliding law as a benchmark argument: SlidingLaw's number (0 coulomb, 1 rigid), as the node's parameter.
constexpr sce::SlidingLaw kLaws[] = { sce::SlidingLaw::Coulomb, sce::SlidingLaw::Rigid };
const std::vector<int64_t> kLawArgs{ 0, 1 };

sce::SlidingLaw lawArg(int64_t arg) { return static_cast<sce::SlidingLaw>(arg); }

sce::BrushParameters figure4(int resolution, bool tilt, sce::SlidingLaw law = sce::SlidingLaw::Coulomb)
{
  sce::BrushParameters p;  // a = 0.05 m, k = 1.023e8, F_z = 3000 N, mu = 1: the paper's Fig. 4
  p.resolution = resolution;
  p.tilt = tilt;
  p.sliding_law = law;
  return p;
}

// partial sliding with spin, the hardest of the operating points
const sce::ContactKinematics kKinematics = sce::ContactKinematics::fromSlips({ 0.05, 0.02 }, 3.33, 0.9, 1.0);

sce::CylinderParameters rubber()
{
  sce::CylinderParameters c;  // the paper's rubber: R = 0.1, M = 250, k = 1e7, gamma = 5e5, m = 100
  c.g = 10.0;
  return c;
}

void BM_BrushLinear(benchmark::State& state)
{
  sce::BrushLinear model(figure4(16, false));
  for (auto _ : state)
    benchmark::DoNotOptimize(model.update(kKinematics, 0.0));
}
BENCHMARK(BM_BrushLinear);

// The steady model at each point of the paper's Fig. 4 curves (sigma_x from -1 to 1 in steps of 0.1, sigma_y in
// {0, 0.05, 0.1, 0.2}, phi = 3.33 1/m, chi_gamma = 0.9), without and with tilt, under each sliding law, at three
// targets: one benchmark per point, so that the report takes the median over the set.
void BM_BrushSteadyFigure4(benchmark::State& state, sce::SlidingLaw law, double target, bool tilt, double sigma_x,
                           double sigma_y)
{
  sce::BrushParameters p = figure4(16, tilt, law);
  p.accuracy_target = target;
  const sce::BrushSteady model(p);
  for (auto _ : state)
    benchmark::DoNotOptimize(model.evaluate({ sigma_x, sigma_y }, 3.33, 0.9 * 3.33, 0.1 * 3.33));
}

// The package's first steady solver (marching with a cap per cell, test/support; under eq. 4b the FASTSIM-like return
// mapping) over the same set: its cost does not depend on the point, so one benchmark cycles through the set. The
// resolutions are model_accuracy's list, about sqrt(2) apart, so that the report finds the time of the one that
// reaches 1 % and 0.1 % in the same run as the steady solver's.
void BM_BrushMarchingFigure4(benchmark::State& state)
{
  const sce::test::BrushMarching model(
      figure4(static_cast<int>(state.range(0)), state.range(1) != 0, lawArg(state.range(2))));
  const double sigma_ys[] = { 0.0, 0.05, 0.1, 0.2 };
  std::size_t i = 0;
  for (auto _ : state)
  {
    const double sigma_x = -1.0 + 0.1 * static_cast<double>(i % 21), sigma_y = sigma_ys[(i / 21) % 4];
    benchmark::DoNotOptimize(model.evaluate({ sigma_x, sigma_y }, 3.33, 0.9 * 3.33, 0.1 * 3.33));
    ++i;
  }
}
BENCHMARK(BM_BrushMarchingFigure4)
    ->ArgsProduct({ { 8, 11, 16, 23, 32, 45, 64, 91, 128, 181, 256, 362, 512 }, { 0, 1 }, kLawArgs })
    ->ArgNames({ "resolution", "tilt", "law" });

// The old operating points' hardest one, spin against slip (sigma = (0, -0.05), phi = 10 1/m), at each target.
void BM_BrushSteadySpinAgainstSlip(benchmark::State& state)
{
  sce::BrushParameters p = figure4(16, false, lawArg(state.range(1)));
  p.accuracy_target = std::pow(10.0, -static_cast<double>(state.range(0)));
  const sce::BrushSteady model(p);
  for (auto _ : state)
    benchmark::DoNotOptimize(model.evaluate({ 0.0, -0.05 }, 10.0, 0.0, 0.0));
}
BENCHMARK(BM_BrushSteadySpinAgainstSlip)->ArgsProduct({ { 2, 3, 4 }, kLawArgs })->ArgNames({ "target_exponent", "law" });

// One odometry step of 1 ms at 1 m/s (a 1 kHz driver), in steady rolling.
void BM_BrushTransientStep(benchmark::State& state)
{
  sce::BrushTransient model(figure4(static_cast<int>(state.range(0)), state.range(1) != 0, lawArg(state.range(2))));
  model.update(kKinematics, 0.2);  // settle
  for (auto _ : state)
    benchmark::DoNotOptimize(model.update(kKinematics, 1e-3));
}
BENCHMARK(BM_BrushTransientStep)
    ->ArgsProduct({ { 8, 12, 16, 24, 32, 48 }, { 0, 1 }, kLawArgs })
    ->ArgNames({ "resolution", "tilt", "law" });

// Steps of recorded odometry at the Fig. 4 point: noise on the slips and the spin at every one
std::vector<sce::ContactKinematics> noisyFigure4Steps(unsigned seed, int count)
{
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<sce::ContactKinematics> steps;
  for (int i = 0; i < count; ++i)
    steps.push_back(sce::ContactKinematics::fromSlips({ 0.05 + 0.005 * noise(rng), 0.02 + 0.005 * noise(rng) },
                                                      3.33 + 0.1 * noise(rng), 0.9, 1.0));
  return steps;
}

// The same with noise on the slips and the spin at every step (recorded odometry): the inputs are never held, so the
// rows' correction (no tilt) is re-evaluated each patch diameter of travel.
void BM_BrushTransientNoisyStep(benchmark::State& state)
{
  sce::BrushTransient model(figure4(static_cast<int>(state.range(0)), state.range(1) != 0, lawArg(state.range(2))));
  model.update(kKinematics, 0.2);  // settle
  const std::vector<sce::ContactKinematics> steps = noisyFigure4Steps(5, 1000);
  std::size_t i = 0;
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(model.update(steps[i], 1e-3));
    i = (i + 1) % steps.size();
  }
}
BENCHMARK(BM_BrushTransientNoisyStep)
    ->ArgsProduct({ { 8, 12, 16, 24, 32, 48 }, { 0, 1 }, kLawArgs })
    ->ArgNames({ "resolution", "tilt", "law" });

// One 10-ms message at 1 m/s with spin (issue 21's measure: a 100 Hz driver on the Fig. 4 parameters, partial sliding,
// noise on the slips and the spin at every message), each bristle over the whole message (stepping 0) against the
// lattice's half-spacing substeps (stepping 1), in one run.
void BM_BrushTransientMessage(benchmark::State& state)
{
  sce::BrushTransient model(figure4(static_cast<int>(state.range(0)), false, lawArg(state.range(2))));
  model.setStepping(state.range(1) == 0 ? sce::TransientStepping::WholeStep : sce::TransientStepping::Substeps);
  model.update(kKinematics, 0.2);  // settle
  const std::vector<sce::ContactKinematics> steps = noisyFigure4Steps(7, 200);
  std::size_t i = 0;
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(model.update(steps[i], 0.01));
    i = (i + 1) % steps.size();
  }
}
BENCHMARK(BM_BrushTransientMessage)
    ->ArgsProduct({ { 32, 64, 128 }, { 0, 1 }, kLawArgs })
    ->ArgNames({ "resolution", "stepping", "law" })
    ->Unit(benchmark::kMicrosecond);

// The forces' covariance from the slips' (the unscented transform through the steady model), against one steady
// evaluation at the tolerance the sigma points use, on the Fig. 4 parameters (partial sliding with spin) and on the
// demo robot (config/contact_estimator.yaml: a = 1 cm, k = 2e8, F_z = 49 N, mu = 0.8) at the demo bag's slips and
// noise (0.005 m/s and 0.02 rad/s at 1.5 m/s).
sce::BrushParameters demoRobot(sce::SlidingLaw law)
{
  sce::BrushParameters p;
  p.sliding_law = law;
  p.a = 0.01;
  p.k = 2e8;
  p.F_z = 5.0 * 9.81;
  p.mu = 0.8;
  return p;
}

void BM_ForceCovariance(benchmark::State& state)
{
  const bool demo = state.range(0) != 0;
  const sce::SlidingLaw law = lawArg(state.range(1));
  const sce::BrushParameters p = demo ? demoRobot(law) : figure4(16, false, law);
  const Eigen::Vector2d sigma = demo ? Eigen::Vector2d(0.003, 0.002) : Eigen::Vector2d(0.05, 0.02);
  const double phi = demo ? 0.3 : 3.33;
  const double s = demo ? 0.005 / 1.5 : 0.005;
  const Eigen::Matrix3d S = Eigen::Vector3d(s * s, s * s, (demo ? 0.02 / 1.5 : 0.1) * (demo ? 0.02 / 1.5 : 0.1)).asDiagonal();
  int evaluations = 0;
  for (auto _ : state)
  {
    const sce::ForceCovariance c = sce::propagateSlipCovariance(sce::BrushModelKind::Steady, p, sigma, phi, 1.0, S);
    evaluations = c.evaluations;
    benchmark::DoNotOptimize(c.covariance);
  }
  state.counters["evaluations"] = evaluations;
}
BENCHMARK(BM_ForceCovariance)->ArgsProduct({ { 0, 1 }, kLawArgs })->ArgNames({ "demo", "law" });

void BM_SteadyAtCovarianceTolerance(benchmark::State& state)
{
  // one evaluation at the tolerance the sigma points above use (a twentieth of the forces' spread)
  const bool demo = state.range(0) != 0;
  const sce::SlidingLaw law = lawArg(state.range(1));
  sce::BrushParameters p = demo ? demoRobot(law) : figure4(16, false, law);
  const Eigen::Vector2d sigma = demo ? Eigen::Vector2d(0.003, 0.002) : Eigen::Vector2d(0.05, 0.02);
  const double phi = demo ? 0.3 : 3.33;
  const double s = demo ? 0.005 / 1.5 : 0.005;
  const Eigen::Matrix3d S = Eigen::Vector3d(s * s, s * s, (demo ? 0.02 / 1.5 : 0.1) * (demo ? 0.02 / 1.5 : 0.1)).asDiagonal();
  p.accuracy_target = std::clamp(
      0.05 * sce::propagateSlipCovariance(sce::BrushModelKind::Steady, p, sigma, phi, 1.0, S).spread(p), 1e-7, 1e-2);
  const sce::BrushSteady model(p);
  for (auto _ : state)
    benchmark::DoNotOptimize(model.evaluate(sigma, phi, phi, 0.0));
}
BENCHMARK(BM_SteadyAtCovarianceTolerance)->ArgsProduct({ { 0, 1 }, kLawArgs })->ArgNames({ "demo", "law" });

// a sweep through the contact-patch regime
template <class Model>
void BM_Cylinder(benchmark::State& state)
{
  const Model model(rubber());
  double v = 0.1;
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(model.solve(v));
    v = v < 20.0 ? v * 1.1 : 0.1;
  }
}
BENCHMARK_TEMPLATE(BM_Cylinder, sce::CylinderExact)->Name("BM_CylinderExact");
BENCHMARK_TEMPLATE(BM_Cylinder, sce::CylinderExpansion)->Name("BM_CylinderExpansion");
BENCHMARK_TEMPLATE(BM_Cylinder, sce::CylinderTable)->Name("BM_CylinderTable");

void BM_CylinderTableMuRoll(benchmark::State& state)
{
  const sce::CylinderTable model(rubber());
  double v = 0.1;
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(model.muRoll(v));
    v = v < 20.0 ? v * 1.1 : 0.1;
  }
}
BENCHMARK(BM_CylinderTableMuRoll);

// The node's core path with its default configuration (config/contact_estimator.yaml), at 5 kHz, under each sliding
// law (the linear model has none: once).
void BM_EstimatorUpdate(benchmark::State& state)
{
  sce::EstimatorSettings s;
  s.brush_model = static_cast<sce::BrushModelKind>(state.range(0));
  s.sliding_law = lawArg(state.range(1));
  s.bristle_stiffness = 2e8;
  s.standstill_speed = 0.05;
  s.surface_stiffness = 1e8;
  s.surface_damping = 1e5;
  s.surface_density = 10.0;
  sce::ContactEstimator e(s);
  sce::EstimatorInput in;
  in.omega = Eigen::Vector3d(0.0, 15.0, 0.5);
  in.v_contact = Eigen::Vector3d(1.52, 0.02, 0.0);
  double t = 0.0;
  for (auto _ : state)
  {
    in.stamp = (t += 2e-4);
    benchmark::DoNotOptimize(e.update(in));
  }
}
BENCHMARK(BM_EstimatorUpdate)
    ->Args({ 1, 0 })
    ->Args({ 2, 0 })
    ->Args({ 2, 1 })
    ->Args({ 3, 0 })
    ->Args({ 3, 1 })
    ->Args({ 4, 0 })
    ->Args({ 4, 1 })
    ->ArgNames({ "brush_model", "law" });
}  // namespace

int main(int argc, char** argv)
{
  for (sce::SlidingLaw law : kLaws)
    for (double target : { 1e-2, 1e-3, 1e-4 })
      for (int tilt = 0; tilt < 2; ++tilt)
        for (double sigma_y : { 0.0, 0.05, 0.1, 0.2 })
          for (int i = 0; i <= 20; ++i)
          {
            const double sigma_x = -1.0 + 0.1 * i;
            char name[160];
            std::snprintf(name, sizeof(name), "BM_BrushSteadyFigure4/law:%s/target:%g/tilt:%d/sigma_y:%g/sigma_x:%.1f",
                          sce::toString(law), target, tilt, sigma_y, sigma_x);
            benchmark::RegisterBenchmark(name, BM_BrushSteadyFigure4, law, target, tilt != 0, sigma_x, sigma_y)
                ->MinTime(0.02);
          }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
