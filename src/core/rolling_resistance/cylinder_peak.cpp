#include "sphere_contact_estimator/core/rolling_resistance/cylinder_peak.h"

// STL
#include <cmath>

// Boost
#include <boost/math/tools/minima.hpp>

namespace sphere_contact_estimator
{
std::optional<CylinderPeak> findPeak(const CylinderModel& model)
{
  const CylinderParameters& p = model.parameters();
  const CylinderScales& sc = model.scales();
  if (p.gamma <= 0.0)
    return std::nullopt;
  const double v_scale = p.k * sc.xi0 / p.gamma;  // speed at which gamma v / k (eq. 23) reaches xi0
  const double v_hi = std::isfinite(sc.v_critical) ? sc.v_critical : 1.0e4 * v_scale;
  const double v_lo = 1.0e-6 * std::min(v_scale, v_hi);
  const auto mu = [&model](double v) { return model.solve(v).mu_roll; };

  // Geometric scan: mu_roll rises linearly from 0 (eq. 27), so the maximum is interior or at v_c.
  constexpr int kScan = 400;
  const double ratio = std::pow(v_hi / v_lo, 1.0 / kScan);
  int best = 0;
  double best_mu = -1.0, v = v_lo;
  for (int i = 0; i <= kScan; ++i, v *= ratio)
  {
    const double value = mu(std::min(v, v_hi));
    if (value > best_mu)
    {
      best_mu = value;
      best = i;
    }
  }
  const double a = v_lo * std::pow(ratio, std::max(best - 1, 0));
  const double b = std::min(v_lo * std::pow(ratio, best + 1), v_hi);
  const auto found = boost::math::tools::brent_find_minima([&mu](double x) { return -mu(x); }, a, b,
                                                           std::numeric_limits<double>::digits / 2);
  return CylinderPeak{ found.first, -found.second };
}

}  // namespace sphere_contact_estimator
