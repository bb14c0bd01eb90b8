#pragma once

// Eigen
#include <Eigen/Core>

// Closed-form bristle deflections of Romano et al. under vanishing sliding, for constant slips, in the
// frame where epsilon = (0, 1) and starting undeformed (u_t0 = 0). They are the oracles the tests hold the
// numerical models to; the models themselves do not use them.
namespace sphere_contact_estimator::brush_closed_form
{
/// Distance Sigma(x) a bristle at x has travelled since the leading edge: x_L(y) - x for straight paths
/// (eq. 19a, 23), eq. 52a on circles about the tilting centre (0, 1/phi_gamma), |1/phi_gamma| >= a.
double travelRolling(const Eigen::Vector2d& x, double a);
double travelTilting(const Eigen::Vector2d& x, double a, double phi_gamma);

/// Steady state of a rolling sphere, eq. 23.
Eigen::Vector2d steadyRolling(const Eigen::Vector2d& x, double a, const Eigen::Vector2d& sigma, double phi);
/// Steady state of a rolling and tilting sphere, eq. 51 (Assumption 4.1; phi_psi != 0).
Eigen::Vector2d steadyTilting(const Eigen::Vector2d& x, double a, const Eigen::Vector2d& sigma, double phi_gamma,
                              double phi_psi);

/// After a travelled distance s: eq. 28 in the transient region (Sigma(x) >= s, eq. 29), eq. 23 behind
/// the travelling edge (eq. 30).
Eigen::Vector2d transientRolling(const Eigen::Vector2d& x, double s, double a, const Eigen::Vector2d& sigma,
                                 double phi);
/// The same with tilt: eq. 55 with eq. 56, and eq. 51 behind the travelling edge.
Eigen::Vector2d transientTilting(const Eigen::Vector2d& x, double s, double a, const Eigen::Vector2d& sigma,
                                 double phi_gamma, double phi_psi);

/// Pure spin (Sect. 5) after the turn angle psi = integral |psi_dot| dt, with sigma = -V_s / |psi_dot| and
/// phi_psi = -psi_dot / |psi_dot| (eq. 57; the paper's "= sgn(psi_dot)" drops this minus sign):
/// eq. 59 with the turn coupling A_phi_psi u, and eq. 60 without it (which grows without bound).
Eigen::Vector2d spinCoupled(const Eigen::Vector2d& x, double psi, const Eigen::Vector2d& sigma, double phi_psi);
Eigen::Vector2d spinUncoupled(const Eigen::Vector2d& x, double psi, const Eigen::Vector2d& sigma, double phi_psi);

}  // namespace sphere_contact_estimator::brush_closed_form
