#include "brush_closed_form.h"

// STL
#include <algorithm>
#include <cmath>

namespace sphere_contact_estimator::brush_closed_form
{
namespace
{
// A_phi v for the skew tensor of eq. 12c: (-phi v_y, phi v_x)
Eigen::Vector2d skew(double phi, const Eigen::Vector2d& v)
{
  return { -phi * v.y(), phi * v.x() };
}

// R(angle) v, counter-clockwise (eq. 40b with angle = phi_psi s; eq. 40a is R(-phi_gamma s))
Eigen::Vector2d rotate(double angle, const Eigen::Vector2d& v)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return { c * v.x() - s * v.y(), s * v.x() + c * v.y() };
}

// u~(x) of eq. 43: -A_phi_psi^-1 sigma - x + x_C_psi, with x_C_psi = (0, -1/phi_psi) (eq. 42)
Eigen::Vector2d particular(const Eigen::Vector2d& x, const Eigen::Vector2d& sigma, double phi_psi)
{
  return Eigen::Vector2d(-sigma.y() / phi_psi, sigma.x() / phi_psi) - x + Eigen::Vector2d(0.0, -1.0 / phi_psi);
}

// Leading-edge point on the circle through x about (0, 1/phi_gamma): eqs. 45, 48
Eigen::Vector2d leadingEdgeTilting(const Eigen::Vector2d& x, double a, double phi_gamma)
{
  const double c = 1.0 / phi_gamma;
  const double Gamma = x.x() * x.x() + (x.y() - c) * (x.y() - c);  // eq. 48b
  const double Lambda = a * a + c * c - Gamma;                      // eq. 48a
  const double y0 = phi_gamma * Lambda / 2.0;                       // eq. 45
  return { std::sqrt(std::max(0.0, a * a - y0 * y0)), y0 };
}
}  // namespace

double travelRolling(const Eigen::Vector2d& x, double a)
{
  return std::sqrt(std::max(0.0, a * a - x.y() * x.y())) - x.x();  // x_L(y) - x, eq. 19a
}

double travelTilting(const Eigen::Vector2d& x, double a, double phi_gamma)
{
  const double c = 1.0 / phi_gamma;
  const Eigen::Vector2d x0 = leadingEdgeTilting(x, a, phi_gamma);
  return c * (std::atan(x.x() / (x.y() - c)) - std::atan(x0.x() / (x0.y() - c)));  // eq. 52a
}

Eigen::Vector2d steadyRolling(const Eigen::Vector2d& x, double a, const Eigen::Vector2d& sigma, double phi)
{
  const double S = travelRolling(x, a);
  const Eigen::Vector2d x0(x.x() + S, x.y());                       // eq. 20a
  return sigma * S + skew(phi, x0 - Eigen::Vector2d(S / 2.0, 0.0)) * S;  // eq. 23
}

Eigen::Vector2d steadyTilting(const Eigen::Vector2d& x, double a, const Eigen::Vector2d& sigma, double phi_gamma,
                              double phi_psi)
{
  const double S = travelTilting(x, a, phi_gamma);
  const Eigen::Vector2d Psi = -particular(leadingEdgeTilting(x, a, phi_gamma), sigma, phi_psi);  // eq. 52b
  return rotate(phi_psi * S, Psi) + particular(x, sigma, phi_psi);                           // eq. 51
}

Eigen::Vector2d transientRolling(const Eigen::Vector2d& x, double s, double a, const Eigen::Vector2d& sigma,
                                 double phi)
{
  if (travelRolling(x, a) < s)
    return steadyRolling(x, a, sigma, phi);
  const Eigen::Vector2d x0 = x + Eigen::Vector2d(s, 0.0);              // after eq. 28
  return sigma * s + skew(phi, x0 - Eigen::Vector2d(s / 2.0, 0.0)) * s;  // eq. 28, u_t0 = 0
}

Eigen::Vector2d transientTilting(const Eigen::Vector2d& x, double s, double a, const Eigen::Vector2d& sigma,
                                 double phi_gamma, double phi_psi)
{
  if (travelTilting(x, a, phi_gamma) < s)
    return steadyTilting(x, a, sigma, phi_gamma, phi_psi);
  const Eigen::Vector2d C(0.0, 1.0 / phi_gamma);
  const Eigen::Vector2d x0 = rotate(phi_gamma * s, x - C) + C;  // eq. 56: R_phi_gamma^-1(s) = R(+phi_gamma s)
  return rotate(phi_psi * s, -particular(x0, sigma, phi_psi)) + particular(x, sigma, phi_psi);  // eq. 55
}

Eigen::Vector2d spinCoupled(const Eigen::Vector2d& x, double psi, const Eigen::Vector2d& sigma, double phi_psi)
{
  const Eigen::Vector2d u_tilde = Eigen::Vector2d(-sigma.y() / phi_psi, sigma.x() / phi_psi) - x;  // after eq. 59
  return rotate(phi_psi * psi, -u_tilde) + u_tilde;                                                // eq. 59
}

Eigen::Vector2d spinUncoupled(const Eigen::Vector2d& x, double psi, const Eigen::Vector2d& sigma, double phi_psi)
{
  return sigma * psi + skew(phi_psi, x) * psi;  // eq. 60
}

}  // namespace sphere_contact_estimator::brush_closed_form
