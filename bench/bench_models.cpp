// Time per evaluation of every model and resolution (Google Benchmark). Accuracy is measured separately
// (bench/model_accuracy.cpp); scripts/benchmark.sh joins the two into docs/benchmarks.md.

// Google Benchmark
#include <benchmark/benchmark.h>

// Package
#include "sphere_contact_estimator/core/brush_linear.h"
#include "sphere_contact_estimator/core/brush_steady.h"
#include "sphere_contact_estimator/core/brush_transient.h"
#include "sphere_contact_estimator/core/contact_estimator.h"
#include "sphere_contact_estimator/core/cylinder_exact.h"
#include "sphere_contact_estimator/core/cylinder_expansion.h"
#include "sphere_contact_estimator/core/cylinder_table.h"

namespace sce = sphere_contact_estimator;

namespace
{
sce::BrushParameters figure4(int resolution, bool tilt)
{
  sce::BrushParameters p;  // a = 0.05 m, k = 1.023e8, F_z = 3000 N, mu = 1: the paper's Fig. 4
  p.resolution = resolution;
  p.tilt = tilt;
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

void BM_BrushSteady(benchmark::State& state)
{
  sce::BrushSteady model(figure4(static_cast<int>(state.range(0)), state.range(1) != 0));
  for (auto _ : state)
    benchmark::DoNotOptimize(model.update(kKinematics, 0.0));
}
BENCHMARK(BM_BrushSteady)->ArgsProduct({ { 4, 8, 12, 16, 24, 32, 48, 64 }, { 0, 1 } })->ArgNames({ "resolution", "tilt" });

// One odometry step of 1 ms at 1 m/s (a 1 kHz driver), in steady rolling.
void BM_BrushTransientStep(benchmark::State& state)
{
  sce::BrushTransient model(figure4(static_cast<int>(state.range(0)), state.range(1) != 0));
  model.update(kKinematics, 0.2);  // settle
  for (auto _ : state)
    benchmark::DoNotOptimize(model.update(kKinematics, 1e-3));
}
BENCHMARK(BM_BrushTransientStep)->ArgsProduct({ { 8, 12, 16, 24, 32, 48 }, { 0, 1 } })->ArgNames({ "resolution", "tilt" });

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

// The node's core path with its default configuration (config/contact_estimator.yaml), at 5 kHz.
void BM_EstimatorUpdate(benchmark::State& state)
{
  sce::EstimatorSettings s;
  s.brush_model = static_cast<sce::BrushChoice>(state.range(0));
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
BENCHMARK(BM_EstimatorUpdate)->Arg(1)->Arg(2)->Arg(3)->ArgName("brush_model");
}  // namespace

BENCHMARK_MAIN();
