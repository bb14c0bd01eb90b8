#include "sphere_contact_estimator/core/brush/contact_kinematics.h"

// STL
#include <cmath>

namespace sphere_contact_estimator
{
ContactKinematics ContactKinematics::fromWheel(const Eigen::Vector3d& omega, const Eigen::Vector2d& V_C, double R_r,
                                               double psi_dot)
{
  ContactKinematics k;
  k.V_r = Eigen::Vector2d(-omega.y(), omega.x()) * R_r;  // pure-rolling velocity (Sect. 2)
  k.V_s = V_C - k.V_r;                                    // eq. 2
  k.omega_z = omega.z();
  k.psi_dot = psi_dot;
  return k;
}

ContactKinematics ContactKinematics::fromWheelWithTiltRatio(const Eigen::Vector3d& omega, const Eigen::Vector2d& V_C,
                                                            double R_r, double chi_gamma)
{
  return fromWheel(omega, V_C, R_r, (1.0 - chi_gamma) * omega.z());
}

ContactKinematics ContactKinematics::fromSlips(const Eigen::Vector2d& sigma, double phi, double chi_gamma, double V_r)
{
  ContactKinematics k;
  k.V_r = Eigen::Vector2d(V_r, 0.0);
  k.V_s = -sigma * V_r;
  k.omega_z = -phi * V_r;
  k.psi_dot = (1.0 - chi_gamma) * k.omega_z;
  return k;
}

Slips computeSlips(const ContactKinematics& kin, double standstill_speed)
{
  Slips s;
  s.V_r = kin.V_r.norm();
  if (kin.omega_z != 0.0)
  {
    s.chi_gamma = kin.omegaGamma() / kin.omega_z;
    s.chi_psi = kin.psi_dot / kin.omega_z;
  }
  s.defined = s.V_r >= standstill_speed && s.V_r > 0.0;
  if (!s.defined)
    return s;
  const double inv = 1.0 / s.V_r;
  s.sigma = -kin.V_s * inv;                                            // eq. 12a
  s.epsilon = Eigen::Vector2d(-kin.V_r.y(), kin.V_r.x()) * inv;        // eq. 12b: (eps_y, -eps_x) = V_r / V_r
  s.phi = -kin.omega_z * inv;                                          // eq. 12c
  s.phi_gamma = -kin.omegaGamma() * inv;                               // eq. 13a
  s.phi_psi = -kin.psi_dot * inv;                                      // eq. 13b
  if (s.phi_gamma != 0.0)
    s.tilting_centre = s.epsilon / s.phi_gamma;                        // eq. 36
  if (s.phi_psi != 0.0)
    s.turning_centre = -s.epsilon / s.phi_psi;                         // eq. 42
  return s;
}

}  // namespace sphere_contact_estimator
