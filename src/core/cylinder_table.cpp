#include "sphere_contact_estimator/core/cylinder_table.h"

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
  std::vector<double> h(size), dh(size), r(size), dr(size), mu(size), dmu(size);
  for (std::size_t i = 0; i < size; ++i)
  {
    const double u = std::min(static_cast<double>(i) * du, 1.0);
    const double dv_du = 2.0 * range * u;  // v = range u^2
    CylinderExact::Slopes d;
    const CylinderState st = exact_.solve(range * u * u, &d);
    h[i] = st.h;
    r[i] = st.xi_minus;
    mu[i] = st.mu_roll;
    dh[i] = d.dh_dv * dv_du;
    dr[i] = d.dxi_minus_dv * dv_du;
    dmu[i] = d.dmu_roll_dv * dv_du;
  }
  h_.emplace(std::move(h), std::move(dh), 0.0, du);
  xi_minus_.emplace(std::move(r), std::move(dr), 0.0, du);
  mu_roll_.emplace(std::move(mu), std::move(dmu), 0.0, du);
  size_ = size;
  v_max_ = range;
  inv_v_max_ = 1.0 / range;

  // A cubic Hermite interpolant's error peaks inside each cell: measure it at the midpoints.
  for (std::size_t i = 0; i + 1 < size; ++i)
  {
    const double u = (static_cast<double>(i) + 0.5) * du;
    const CylinderState st = exact_.solve(range * u * u);
    error_.mu_roll = std::max(error_.mu_roll, std::abs((*mu_roll_)(u)-st.mu_roll));
    error_.h = std::max(error_.h, std::abs((*h_)(u)-st.h));
    error_.xi_minus = std::max(error_.xi_minus, std::abs((*xi_minus_)(u)-st.xi_minus));
  }
}

double CylinderTable::u(double v) const
{
  // the library throws past its end point; v <= v_max_ can round u a hair above 1
  return std::min(std::sqrt(v * inv_v_max_), mu_roll_->domain().second);
}

double CylinderTable::muRoll(double v) const
{
  if (mu_roll_ && v >= 0.0 && v <= v_max_)
    return (*mu_roll_)(u(v));
  return solve(v).mu_roll;
}

CylinderState CylinderTable::solve(double v) const
{
  checkSpeed(v);
  if (v == 0.0)
    return staticState();
  if (!mu_roll_ || v > v_max_)
  {
    CylinderState st = exact_.solve(v);
    if (st.regime != CylinderRegime::PointContact)  // point contact is closed-form: nothing to tabulate
      st.flags |= cylinder_flags::kTableFallback;
    return st;
  }
  const double x = u(v);
  CylinderState st;
  st.v = v;
  st.regime = CylinderRegime::ContactPatch;
  st.h = (*h_)(x);
  st.xi_plus = std::sqrt(2.0 * p_.R * st.h);  // eq. 13
  st.xi_minus = std::min((*xi_minus_)(x), st.xi_plus);
  st.F_R = (*mu_roll_)(x)*p_.weight() / p_.R;  // eq. 26
  st.mu_roll_error = error_.mu_roll;
  finish(st);
  st.F_N = p_.weight() - st.F_N_impact;  // eq. 9
  return st;
}

}  // namespace sphere_contact_estimator
