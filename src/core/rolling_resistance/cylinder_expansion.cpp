#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"

// STL
#include <algorithm>
#include <cmath>

namespace sphere_contact_estimator
{
CylinderExpansion::CylinderExpansion(const CylinderParameters& parameters) : CylinderModel(parameters)
{
  const double g = p_.gamma, k = p_.k, m = p_.m, a = scales_.xi0;
  c4_ = 3.0 * (g * g * g * g - 4.0 * g * g * k * m + 2.0 * k * k * m * m) / (8.0 * a * a * a * k * k * k * k);
}

CylinderState CylinderExpansion::solve(double v) const
{
  checkSpeed(v);
  if (v == 0.0)
    return staticState();
  const double a = scales_.xi0, lambda = scales_.lambda, R = p_.R, v2 = v * v;
  CylinderState st;
  st.v = v;
  st.regime = CylinderRegime::ContactPatch;
  const double h = scales_.h0 - lambda * v2 / (4.0 * R);                      // eq. 24
  const double xi_plus = a - lambda * v2 / (4.0 * a);                         // eq. 21
  const double xi_minus = -a + p_.gamma / p_.k * v - lambda * v2 / (4.0 * a);  // eq. 23
  const double mu = p_.gamma / p_.k * v - 3.0 * lambda / (4.0 * a) * v2;       // eq. 27
  st.mu_roll_error = std::abs(c4_) * v2 * v2;

  const bool unphysical = h <= 0.0 || xi_plus <= 0.0 || xi_minus >= xi_plus || mu < 0.0 ||
                          p_.m * v > p_.gamma * xi_plus || v >= scales_.v_critical;
  if (unphysical || st.mu_roll_error > kTolerance * std::abs(mu))
    st.flags |= cylinder_flags::kExpansionOutOfRange;
  st.h = std::max(h, 0.0);
  st.xi_plus = std::max(xi_plus, 0.0);
  st.xi_minus = std::min(xi_minus, st.xi_plus);
  st.F_R = std::max(mu, 0.0) * p_.weight() / R;  // eq. 26: M = R F_R = mu M g
  finish(st);
  st.F_N = p_.weight() - st.F_N_impact;  // eq. 9
  return st;
}

}  // namespace sphere_contact_estimator
