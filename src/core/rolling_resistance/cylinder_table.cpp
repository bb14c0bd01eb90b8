#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

// STL
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sphere_contact_estimator
{
namespace
{
// The patch solution is smooth up to v_c but the point-contact branch meets it with a kink there;
// ending the table just below v_c keeps every tabulated slope on the patch branch.
constexpr double kCriticalMargin = 1.0e-9;
}  // namespace

CylinderTable::CylinderTable(const CylinderParameters& parameters, std::size_t size, double v_max)
  : CylinderModel(parameters), exact_(parameters)
{
  if (size < 2)
    throw std::invalid_argument("cylinder table size must be >= 2");
  if (!(std::isfinite(v_max) && v_max >= 0.0))
    throw std::invalid_argument("cylinder table v_max must be finite and >= 0 [m/s] (0 picks the range)");
  // Without damping there is nothing to tabulate (mu_roll = 0, or point contact at every v > 0);
  // with m k > gamma^2 the patch regime has a gap. The exact solver serves those.
  if (p_.gamma <= 0.0 || p_.m * p_.k > p_.gamma * p_.gamma)
    return;
  const double v_c = scales_.v_critical * (1.0 - kCriticalMargin);
  const double v_auto = std::isfinite(v_c) ? v_c : kAutoRangeFactor * p_.k * scales_.xi0 / p_.gamma;
  const double range = v_max > 0.0 ? std::min(v_max, v_auto) : v_auto;
  if (!(range > 0.0))
    return;

  const double du = 1.0 / static_cast<double>(size - 1);
  table_ = UniformHermite<3>(size);
  for (std::size_t i = 0; i < size; ++i)
  {
    const double u = std::min(static_cast<double>(i) * du, 1.0);
    const double dv_du = 2.0 * range * u;  // v = range u^2
    CylinderExact::Slopes d;
    const CylinderState st = exact_.solve(range * u * u, &d);
    table_.set(i, 0, st.h, d.dh_dv * dv_du);
    table_.set(i, 1, st.xi_minus, d.dxi_minus_dv * dv_du);
    table_.set(i, 2, st.mu_roll, d.dmu_roll_dv * dv_du);
  }
  size_ = size;
  v_max_ = range;
  inv_v_max_ = 1.0 / range;

  // A cubic Hermite interpolant's error peaks inside each cell: measure it at the midpoints.
  for (std::size_t i = 0; i + 1 < size; ++i)
  {
    const double u = (static_cast<double>(i) + 0.5) * du;
    const CylinderState st = exact_.solve(range * u * u);
    const auto [h, r, mu] = table_(u);
    error_.mu_roll = std::max(error_.mu_roll, std::abs(mu - st.mu_roll));
    error_.h = std::max(error_.h, std::abs(h - st.h));
    error_.xi_minus = std::max(error_.xi_minus, std::abs(r - st.xi_minus));
  }
}

double CylinderTable::u(double v) const
{
  return std::sqrt(v * inv_v_max_);  // the table clamps u to [0, 1]
}

double CylinderTable::muRoll(double v) const
{
  if (!table_.empty() && v >= 0.0 && v <= v_max_)
    return table_(u(v))[2];
  return solve(v).mu_roll;
}

CylinderState CylinderTable::solve(double v) const
{
  checkSpeed(v);
  if (v == 0.0)
    return staticState();
  if (table_.empty() || v > v_max_)
  {
    CylinderState st = exact_.solve(v);
    if (st.regime != CylinderRegime::PointContact)  // point contact is closed-form: nothing to tabulate
      st.flags |= cylinder_flags::kTableFallback;
    return st;
  }
  const auto [h, xi_minus, mu] = table_(u(v));
  CylinderState st;
  st.v = v;
  st.regime = CylinderRegime::ContactPatch;
  st.h = h;
  st.xi_plus = std::sqrt(2.0 * p_.R * st.h);  // eq. 13
  st.xi_minus = std::min(xi_minus, st.xi_plus);
  st.F_R = mu * p_.weight() / p_.R;  // eq. 26
  st.mu_roll_error = error_.mu_roll;
  finish(st);
  st.F_N = p_.weight() - st.F_N_impact;  // eq. 9
  return st;
}

}  // namespace sphere_contact_estimator
