// Every brush model under both sliding laws on any parameters and kinematics: finite, |F_t| <= mu F_z, an error estimate >= 0, or a clear
// rejection. The cost per input is bounded (resolution <= 8, at most 4 steps, each within 64 transient substeps,
// targets >= 1 % (auto's >= 5 %, so that it rarely grows its lattice), the steady solver's work budget; the truncation
// at kMaxSubsteps, the growth and the tight targets have their unit tests and the accuracy program), so that CI runs
// 10^5 inputs in a few minutes.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "fuzz_input.h"
#include "sphere_contact_estimator/core/brush/brush_model.h"

using namespace sphere_contact_estimator;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  fuzz::Input in(data, size);
  BrushParameters p;
  p.a = std::pow(10.0, in.in(-6.0, 3.0));
  p.k = std::pow(10.0, in.in(-3.0, 20.0));
  p.mu = std::pow(10.0, in.in(-3.0, 3.0));
  // the load through the stiffness ratio k a^3 / (mu F_z) in [1e-12, 1e12] (or no load): every regime from bristles
  // that hardly deflect to full sliding at any spin; the steady solver's work budget bounds each evaluation
  p.F_z = p.k * p.a * p.a * p.a / (p.mu * std::pow(10.0, in.in(-12.0, 12.0))) * (in.in(0.0, 1.0) < 0.1 ? 0.0 : 1.0);
  p.tilt = in.in(0.0, 1.0) < 0.5;
  p.pressure = static_cast<PressureDistribution>(static_cast<int>(in.in(0.0, 2.99)));
  p.resolution = 2 + static_cast<int>(in.in(0.0, 6.99));
  p.sliding_law = in.in(0.0, 1.0) < 0.5 ? SlidingLaw::Coulomb : SlidingLaw::Rigid;
  p.accuracy_target = in.in(1e-2, 1.0);
  const auto kind = static_cast<BrushModelKind>(1 + static_cast<int>(in.in(0.0, 3.99)));  // linear .. auto
  if (kind == BrushModelKind::Auto)
    p.accuracy_target = std::max(p.accuracy_target, 0.05);
  std::unique_ptr<BrushModel> model;
  try
  {
    model = makeBrushModel(kind, p);
  }
  catch (const std::invalid_argument&)
  {
    return 0;
  }
  for (int step = 0; step < 4 && in.more(); ++step)
  {
    ContactKinematics k;
    k.V_r = Eigen::Vector2d(in.in(-1e3, 1e3), in.in(-1e3, 1e3)) * (in.in(0.0, 1.0) < 0.2 ? 0.0 : 1.0);
    k.V_s = Eigen::Vector2d(in.in(-1e6, 1e6), in.in(-1e6, 1e6)) * std::pow(10.0, in.in(-9.0, 0.0));
    k.omega_z = in.in(-1e4, 1e4) * std::pow(10.0, in.in(-9.0, 0.0));
    k.psi_dot = k.omega_z * in.in(-1.0, 1.0);
    // the transient model's substeps: a travel of half a spacing or a turn of 0.1 rad each (BrushTransient)
    const double h = 2.0 * p.a / p.resolution;
    const double rate = (k.V_r.norm() + std::abs(k.omega_z) * (p.a + h)) / (0.5 * h) + std::abs(k.omega_z) / 0.1;
    const double dt = std::min(in.in(0.0, 0.01), rate > 0.0 ? 64.0 / rate : 0.01);
    const BrushForces f = model->update(k, dt);
    if (!(std::isfinite(f.F_x) && std::isfinite(f.F_y) && std::isfinite(f.M_z) && std::isfinite(f.sliding_fraction)))
      std::abort();
    if (std::hypot(f.F_x, f.F_y) > p.mu * p.F_z * (1.0 + 1e-9) + 1e-300)
      std::abort();
    if (!(f.error_estimate >= 0.0))  // NaN or negative
      std::abort();
  }
  return 0;
}
