#include "sphere_contact_estimator/core/rolling_resistance/cylinder_parameters.h"

// STL
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sphere_contact_estimator
{
namespace
{
// Throws unless x is finite and, when zero_allowed is false or x != 0, inside r.
void require(double x, CylinderParameters::Range r, bool zero_allowed, const char* name, const char* symbol,
             const char* unit)
{
  const bool ok = std::isfinite(x) && ((zero_allowed && x == 0.0) || (x >= r.lo && x <= r.hi));
  if (ok)
    return;
  std::ostringstream msg;
  msg.precision(17);
  msg << "invalid cylinder parameter " << name << " (" << symbol << ") = " << x << " " << unit << ": ";
  if (!std::isfinite(x))
    msg << "must be finite";
  else if (x < 0.0 || (x == 0.0 && !zero_allowed))
    msg << "must be " << (zero_allowed ? ">= 0" : "> 0");
  else
    msg.precision(3), msg << "outside the supported range [" << r.lo << ", " << r.hi << "]" << (zero_allowed ? " or 0" : "");
  throw std::invalid_argument(msg.str());
}
}  // namespace

void CylinderParameters::validate() const
{
  require(R, kRangeR, false, "radius", "R", "m");
  require(M, kRangeM, false, "mass per length", "M", "kg/m");
  require(k, kRangeK, false, "surface stiffness", "k", "N/m^3");
  require(gamma, kRangeGamma, true, "surface damping", "gamma", "kg/(m^2 s)");
  require(m, kRangeSurfaceDensity, true, "surface density", "m", "kg/m^2");
  require(g, kRangeG, false, "gravity", "g", "m/s^2");
  require(L, kRangeL, false, "effective length", "L", "m");
}

bool operator==(const CylinderParameters& a, const CylinderParameters& b)
{
  return a.R == b.R && a.M == b.M && a.k == b.k && a.gamma == b.gamma && a.m == b.m && a.g == b.g && a.L == b.L;
}

}  // namespace sphere_contact_estimator
