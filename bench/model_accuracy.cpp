// Accuracy of every model and resolution on a fixed set of operating points, against a converged
// reference: the steady scheme at resolution 512 for the brush (itself held to the closed forms eqs. 23/51
// by test_brush), the exact solution of eq. 18 for the cylinder. Prints JSON for scripts/benchmark_report.py.
//
// Brush errors are max(|dF_x|, |dF_y|, |dM_z| / a) / (mu F_z) on the paper's Fig. 4 set; cylinder errors
// are |d mu_roll| / mu_roll on the paper's rubber (g = 10).

// STL
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

// Package
#include "sphere_contact_estimator/core/brush_linear.h"
#include "sphere_contact_estimator/core/brush_steady.h"
#include "sphere_contact_estimator/core/brush_transient.h"
#include "sphere_contact_estimator/core/cylinder_exact.h"
#include "sphere_contact_estimator/core/cylinder_expansion.h"
#include "sphere_contact_estimator/core/cylinder_table.h"

namespace sce = sphere_contact_estimator;

namespace
{
struct Point
{
  const char* name;
  double sigma_x, sigma_y, phi;
  bool tilt;
};

// The documented operating points (docs/benchmarks.md): adhesion, partial and full sliding, spin, tilt.
const std::vector<Point> kPoints{
  { "adhesion", 0.002, 0.001, 0.1, false },        { "partial sliding", 0.05, 0.02, 0.0, false },
  { "full sliding", 0.5, 0.2, 0.0, false },         { "spin", 0.0, 0.0, 3.33, false },
  { "slip and spin", 0.05, 0.02, 3.33, false },     { "slip, spin, tilt", 0.05, 0.02, 3.33, true },
  { "spin against slip", 0.0, -0.05, 10.0, false },
};
constexpr double kChi = 0.9;  // tilt ratio of the tilt point, as in Fig. 4

sce::BrushParameters params(int resolution, bool tilt)
{
  sce::BrushParameters p;
  p.resolution = resolution;
  p.tilt = tilt;
  return p;
}

double distance(const sce::BrushForces& f, const sce::BrushForces& g, const sce::BrushParameters& p)
{
  return std::max({ std::abs(f.F_x - g.F_x), std::abs(f.F_y - g.F_y), std::abs(f.M_z - g.M_z) / p.a }) / (p.mu * p.F_z);
}

sce::BrushForces steady(const Point& q, int resolution)
{
  return sce::BrushSteady(params(resolution, q.tilt)).evaluate({ q.sigma_x, q.sigma_y }, q.phi, kChi * q.phi, (1 - kChi) * q.phi);
}

// transient from undeformed, 4a at constant slips (steady by then), at rolling speed V
sce::BrushForces transient(const Point& q, int resolution, double V)
{
  sce::BrushTransient m(params(resolution, q.tilt));
  return m.update(sce::ContactKinematics::fromSlips({ q.sigma_x, q.sigma_y }, q.phi, kChi, V), 4.0 * m.parameters().a / V);
}

void brushRow(const char* model, int resolution, bool tilt_capable, const std::vector<double>& errors, bool& first)
{
  std::printf("%s    {\"model\": \"%s\", \"resolution\": %d, \"tilt\": %s, \"errors\": {", first ? "" : ",\n", model,
              resolution, tilt_capable ? "true" : "false");
  double worst = 0.0;
  for (std::size_t i = 0; i < kPoints.size(); ++i)
  {
    std::printf("%s\"%s\": %.6g", i ? ", " : "", kPoints[i].name, errors[i]);
    worst = std::max(worst, errors[i]);
  }
  std::printf("}, \"max\": %.6g}", worst);
  first = false;
}
}  // namespace

int main()
{
  std::vector<sce::BrushForces> reference;
  for (const Point& q : kPoints)
    reference.push_back(steady(q, 512));
  const sce::BrushParameters p = params(16, false);

  std::printf("{\n  \"brush\": [\n");
  bool first = true;
  {
    std::vector<double> e;
    const sce::BrushLinear linear(p);
    for (std::size_t i = 0; i < kPoints.size(); ++i)
      e.push_back(distance(linear.evaluate({ kPoints[i].sigma_x, kPoints[i].sigma_y }, kPoints[i].phi), reference[i], p));
    brushRow("linear", 0, false, e, first);
  }
  for (int n : { 4, 8, 12, 16, 24, 32, 48, 64 })
  {
    std::vector<double> e;
    for (std::size_t i = 0; i < kPoints.size(); ++i)
      e.push_back(distance(steady(kPoints[i], n), reference[i], p));
    brushRow("steady", n, true, e, first);
  }
  for (int n : { 8, 12, 16, 24, 32, 48 })
  {
    std::vector<double> e;
    for (std::size_t i = 0; i < kPoints.size(); ++i)
      e.push_back(distance(transient(kPoints[i], n, 1.0), reference[i], p));
    brushRow("transient", n, true, e, first);
  }
  // low speed: the transient at 1 cm/s reaches the same state (nothing divides by V_r)
  {
    std::vector<double> e;
    for (std::size_t i = 0; i < kPoints.size(); ++i)
      e.push_back(distance(transient(kPoints[i], 16, 0.01), reference[i], p));
    brushRow("transient at 0.01 m/s", 16, true, e, first);
  }
  std::printf("\n  ],\n");

  // cylinder: the paper's rubber, below, at and past v*, and past the critical speed
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
  std::printf("\n  ]\n}\n");
  return 0;
}
