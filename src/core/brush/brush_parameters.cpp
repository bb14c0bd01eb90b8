#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "pressure_law.h"
#include "sphere_contact_estimator/core/numerics/parameter_check.h"

// STL
#include <cmath>
#include <stdexcept>

// Boost
#include <boost/math/constants/constants.hpp>

namespace sphere_contact_estimator
{
namespace
{
using boost::math::double_constants::pi;

void require(bool ok, const char* name, double value, const char* rule)
{
  detail::requireParameter(ok, "brush ", name, value, rule);
}
}  // namespace

const char* toString(PressureDistribution pressure)
{
  switch (pressure)
  {
    case PressureDistribution::Parabolic:
      return "parabolic";
    case PressureDistribution::Hertzian:
      return "hertzian";
    case PressureDistribution::Uniform:
      return "uniform";
  }
  return "unknown";
}

std::optional<PressureDistribution> parsePressureDistribution(std::string_view name)
{
  for (auto pressure : { PressureDistribution::Parabolic, PressureDistribution::Hertzian, PressureDistribution::Uniform })
    if (name == toString(pressure))
      return pressure;
  return std::nullopt;
}

const char* toString(SlidingLaw law)
{
  switch (law)
  {
    case SlidingLaw::Coulomb:
      return "coulomb";
    case SlidingLaw::Rigid:
      return "rigid";
  }
  return "unknown";
}

std::optional<SlidingLaw> parseSlidingLaw(std::string_view name)
{
  for (auto law : { SlidingLaw::Coulomb, SlidingLaw::Rigid })
    if (name == toString(law))
      return law;
  return std::nullopt;
}

double peakFactor(PressureDistribution pressure)
{
  return PressureLaw(pressure).peakFactor();
}

void BrushParameters::validate() const
{
  const auto finite = [](double x) { return std::isfinite(x); };
  require(finite(a) && a > 0.0 && a <= 1e3, "patch radius a", a, "finite, > 0 and <= 1e3 [m]");
  require(finite(k) && k > 0.0 && k <= 1e20, "bristle stiffness k", k, "finite, > 0 and <= 1e20 [N/m^3]");
  require(finite(F_z) && F_z >= 0.0 && F_z <= 1e12, "load F_z", F_z, "finite, >= 0 and <= 1e12 [N]");
  require(finite(mu) && mu >= 0.0 && mu <= 1e6, "friction mu", mu, "finite, >= 0 and <= 1e6");
  require(resolution >= 2 && resolution <= 1024, "resolution", resolution, "between 2 and 1024");
  require(finite(standstill_speed) && standstill_speed > 0.0, "standstill speed", standstill_speed,
          "finite and > 0 [m/s]");
  require(finite(accuracy_target) && accuracy_target > 0.0 && accuracy_target <= 1.0, "accuracy target",
          accuracy_target, "in (0, 1] (relative to mu F_z)");
  require(finite(auto_noise_fraction) && auto_noise_fraction >= 0.0 && auto_noise_fraction <= 1.0,
          "auto noise fraction", auto_noise_fraction, "in [0, 1]");
}

double BrushParameters::qz(double r2) const
{
  const PressureLaw law(pressure);
  return law.peakFactor() * F_z / (pi * a * a) * law.shape(1.0 - r2 / (a * a));
}

bool operator==(const BrushParameters& a, const BrushParameters& b)
{
  return a.a == b.a && a.k == b.k && a.F_z == b.F_z && a.mu == b.mu && a.pressure == b.pressure && a.tilt == b.tilt &&
         a.sliding_law == b.sliding_law &&
         a.resolution == b.resolution && a.standstill_speed == b.standstill_speed &&
         a.accuracy_target == b.accuracy_target && a.auto_noise_fraction == b.auto_noise_fraction;
}

double contactRadiusHertz(double F_z, double R, double E_star)
{
  if (!(std::isfinite(F_z) && F_z >= 0.0 && std::isfinite(R) && R > 0.0 && std::isfinite(E_star) && E_star > 0.0))
    throw std::invalid_argument("Hertz contact radius needs F_z >= 0, R > 0 and E* > 0, all finite");
  return std::cbrt(3.0 * F_z * R / (4.0 * E_star));
}

}  // namespace sphere_contact_estimator
