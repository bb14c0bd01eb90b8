#include "sphere_contact_estimator/core/rolling_resistance/cylinder_spread.h"

// STL
#include <algorithm>
#include <cmath>
#include <stdexcept>

// Package
#include "sphere_contact_estimator/core/numerics/unscented_transform.h"

namespace sphere_contact_estimator
{
CylinderSpread cylinderSpread(const CylinderModel& model, double v, double sd)
{
  if (!(std::isfinite(sd) && sd >= 0.0))
    throw std::invalid_argument("speed standard deviation must be finite and >= 0 [m/s]");
  CylinderSpread out;
  if (sd == 0.0)
  {
    model.solve(v);  // the same refusals as with a spread
    out.method = CovarianceMethod::Zero;
    return out;
  }
  const auto u = unscentedTransform<1, 2>(
      Eigen::Matrix<double, 1, 1>(v), Eigen::Matrix<double, 1, 1>(sd * sd),
      [&](const Eigen::Matrix<double, 1, 1>& x) {
        const CylinderState s = model.solve(std::min(std::abs(x(0)), CylinderModel::kMaxSpeed));
        return Eigen::Vector2d(s.F_R, s.mu_roll);
      },
      2.0);
  out.F_R_variance = u.covariance(0, 0);
  out.mu_roll_variance = u.covariance(1, 1);
  out.method = CovarianceMethod::Unscented;
  return out;
}

}  // namespace sphere_contact_estimator
