// The cylinder models on any parameters and speed: finite, F_R >= 0, or a clear rejection.
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "fuzz_input.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"

using namespace sphere_contact_estimator;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  fuzz::Input in(data, size);
  CylinderParameters p;
  p.R = in.next();
  p.M = in.next();
  p.k = in.next();
  p.gamma = in.next();
  p.m = in.next();
  p.g = in.next();
  try
  {
    const CylinderExact exact(p);
    const CylinderExpansion expansion(p);
    while (in.more())
    {
      const double v = in.next();
      try
      {
        for (const CylinderModel* m : { static_cast<const CylinderModel*>(&exact), static_cast<const CylinderModel*>(&expansion) })
        {
          const CylinderState s = m->solve(v);
          if (!(std::isfinite(s.h) && std::isfinite(s.F_R) && std::isfinite(s.mu_roll) && std::isfinite(s.xi_minus)) ||
              s.F_R < 0.0 || s.xi_minus > s.xi_plus)
            std::abort();
        }
      }
      catch (const std::invalid_argument&)  // a speed that is negative, non-finite or faster than light
      {
      }
    }
  }
  catch (const std::invalid_argument&)  // non-physical parameters, named in the message
  {
  }
  return 0;
}
