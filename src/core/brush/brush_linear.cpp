#include "sphere_contact_estimator/core/brush/brush_linear.h"

// STL
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

namespace sphere_contact_estimator
{
double BrushLinear::slipStiffness(const BrushParameters& p)
{
  return 8.0 / 3.0 * p.k * p.a * p.a * p.a;  // eq. 62
}

double BrushLinear::spinStiffness(const BrushParameters& p)
{
  return 3.0 * boost::math::double_constants::pi * p.a / 32.0 * slipStiffness(p);  // eq. 62
}

BrushLinear::BrushLinear(const BrushParameters& parameters)
  : BrushSlipModel(parameters), C_sigma_(slipStiffness(p_)), C_phi_(spinStiffness(p_))
{
  const double a = p_.a;
  C_Mphi_ = 8.0 / 15.0 * p_.k * a * a * a * a * a;  // derived above, not in the paper
}

BrushForces BrushLinear::evaluate(const Eigen::Vector2d& sigma, double phi) const
{
  BrushForces f;
  Eigen::Vector2d F = C_sigma_ * sigma + Eigen::Vector2d(0.0, C_phi_ * phi);  // eq. 61a
  f.M_z = -C_phi_ * sigma.y() + C_Mphi_ * phi;                                // eq. 61b + spin term
  const double limit = p_.mu * p_.F_z, norm = F.norm();
  if (norm > limit)
  {
    const double scale = norm > 0.0 ? limit / norm : 0.0;
    F *= scale;
    f.M_z *= scale;
    f.flags |= brush_flags::kLinearSaturated;
    f.sliding_fraction = 1.0;
    f.max_utilisation = 1.0;
  }
  else
  {
    f.max_utilisation = limit > 0.0 ? norm / limit : 0.0;  // global |F_t| / (mu F_z): no local bound in this theory
  }
  f.F_x = F.x();
  f.F_y = F.y();
  f.work = kWork;
  return f;
}

BrushForces BrushLinear::evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const
{
  BrushForces f = evaluate(sigma, phi);
  f.error_estimate = errorBound(p_, sigma, phi, phi_gamma, phi_psi);
  return f;
}

double BrushLinear::errorBound(const BrushParameters& p, const Eigen::Vector2d& sigma, double phi, double phi_gamma,
                               double phi_psi)
{
  const double limit = p.mu * p.F_z;
  if (!(limit > 0.0))
    return 0.0;  // no friction or no load: every model gives zero force
  const double s = (slipStiffness(p) * sigma.norm() + 2.0 * spinStiffness(p) * std::abs(phi)) / limit;
  double bound = 0.5 * s * s;
  if (p.tilt)
    bound += 0.6 * (std::abs(phi_gamma) + std::abs(phi_psi)) * p.a * s;
  return bound;
}

}  // namespace sphere_contact_estimator
