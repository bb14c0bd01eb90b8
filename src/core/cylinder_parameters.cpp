#include "sphere_contact_estimator/core/cylinder_parameters.h"

// STL
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sphere_contact_estimator
{
namespace
{
void require(bool ok, const char* name, const char* symbol, double value, const char* rule)
{
  if (ok)
    return;
  std::ostringstream msg;
  msg.precision(17);
  msg << "invalid cylinder parameter " << name << " (" << symbol << ") = " << value << ": must be " << rule;
  throw std::invalid_argument(msg.str());
}
}  // namespace

void CylinderParameters::validate() const
{
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  const auto non_negative = [](double x) { return std::isfinite(x) && x >= 0.0; };
  require(positive(R), "radius", "R", R, "finite and > 0 [m]");
  require(positive(M), "mass per length", "M", M, "finite and > 0 [kg/m]");
  require(positive(k), "surface stiffness", "k", k, "finite and > 0 [N/m^3]");
  require(non_negative(gamma), "surface damping", "gamma", gamma, "finite and >= 0 [kg/(m^2 s)]");
  require(non_negative(m), "surface density", "m", m, "finite and >= 0 [kg/m^2]");
  require(positive(g), "gravity", "g", g, "finite and > 0 [m/s^2]");
  require(positive(L), "effective length", "L", L, "finite and > 0 [m]");
  require(std::isfinite(weight()), "weight per length", "M g", weight(), "finite [N/m]");
}

}  // namespace sphere_contact_estimator
