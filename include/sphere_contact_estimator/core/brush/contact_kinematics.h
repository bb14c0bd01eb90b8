#pragma once

// Eigen
#include <Eigen/Core>

// STL
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sphere_contact_estimator
{
/// Rigid-body kinematics of the contact, dimensional, in the paper frame (SAE: z down) with axes
/// attached to the contact patch (Romano et al., Sect. 2). Nothing here divides by a speed, so it
/// stays defined at standstill; the transient brush model works on it directly.
struct ContactKinematics
{
  Eigen::Vector2d V_r = Eigen::Vector2d::Zero();  ///< rolling velocity [-omega_y, omega_x] R_r (eq. 2 context) [m/s]
  Eigen::Vector2d V_s = Eigen::Vector2d::Zero();  ///< sliding velocity of C, V_C - V_r (eq. 2) [m/s]
  double omega_z = 0.0;  ///< total angular speed about z, omega_z = psi_dot + omega_gamma [rad/s]
  double psi_dot = 0.0;  ///< turning speed of the contact frame psi_dot [rad/s]

  double omegaGamma() const { return omega_z - psi_dot; }  ///< tilting part omega_gamma [rad/s]

  /// From the sphere's angular velocity omega (paper frame) [rad/s], the velocity of the
  /// contact-patch centre V_C [m/s] and the rolling radius R_r [m] (eq. 2), with the turning speed
  /// psi_dot given [rad/s].
  static ContactKinematics fromWheel(const Eigen::Vector3d& omega, const Eigen::Vector2d& V_C, double R_r,
                                     double psi_dot);
  /// The same, with the tilt ratio chi_gamma = omega_gamma / omega_z given instead (psi_dot =
  /// (1 - chi_gamma) omega_z, Sect. 2).
  static ContactKinematics fromWheelWithTiltRatio(const Eigen::Vector3d& omega, const Eigen::Vector2d& V_C,
                                                  double R_r, double chi_gamma);

  /// Constant slips as kinematics at rolling speed V_r along +x (epsilon = (0, 1)): V_s = -sigma V_r,
  /// omega_z = -phi V_r, psi_dot = (1 - chi_gamma) omega_z (eqs. 12, 13).
  static ContactKinematics fromSlips(const Eigen::Vector2d& sigma, double phi, double chi_gamma, double V_r = 1.0);
};

/// Slip quantities of Romano et al. eqs. 12, 13, 36, 42, all in the paper frame. Every quotient by V_r
/// is guarded: below the standstill speed the slip form is undefined (defined = false), the fields
/// that need it stay 0, and only the transient model can describe the contact.
struct Slips
{
  double V_r = 0.0;                                   ///< rolling speed |V_r| [m/s]
  bool defined = false;                               ///< V_r >= standstill speed
  Eigen::Vector2d sigma = Eigen::Vector2d::Zero();    ///< (sigma_x, sigma_y) = -V_s / V_r, eq. 12a [-]
  Eigen::Vector2d epsilon = Eigen::Vector2d::Zero();  ///< -R_r (omega_x, omega_y) / V_r, eq. 12b [-]
  double phi = 0.0;                                   ///< spin -omega_z / V_r, eq. 12c [1/m]
  double phi_gamma = 0.0;                             ///< tilt spin -omega_gamma / V_r, eq. 13a [1/m]
  double phi_psi = 0.0;                               ///< turn spin -psi_dot / V_r, eq. 13b [1/m]
  std::optional<double> chi_gamma;                    ///< tilt ratio omega_gamma / omega_z (none if omega_z = 0)
  std::optional<double> chi_psi;                      ///< turn ratio psi_dot / omega_z (none if omega_z = 0)
  /// Tilting centre epsilon / phi_gamma (eq. 36) and turning centre -epsilon / phi_psi (eq. 42) [m];
  /// none when the spin part is zero (the centre is at infinity).
  std::optional<Eigen::Vector2d> tilting_centre;
  std::optional<Eigen::Vector2d> turning_centre;
};

/// Rolling speed below which the slip form is not used [m/s] (documented default).
constexpr double kDefaultStandstillSpeed = 1.0e-3;

/// Slips of the kinematics, eqs. 12-13 (epsilon from V_r: (epsilon_y, -epsilon_x) = V_r / |V_r|).
Slips computeSlips(const ContactKinematics& kinematics, double standstill_speed = kDefaultStandstillSpeed);

}  // namespace sphere_contact_estimator
