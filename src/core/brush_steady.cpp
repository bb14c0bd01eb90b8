#include "sphere_contact_estimator/core/brush_steady.h"

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/friction_cap.h"

namespace sphere_contact_estimator
{
namespace
{
using boost::math::double_constants::pi;

Eigen::Vector2d rotate(double c, double s, const Eigen::Vector2d& v)
{
  return { c * v.x() - s * v.y(), s * v.x() + c * v.y() };
}

double cross(const Eigen::Vector2d& x, const Eigen::Vector2d& u)
{
  return x.x() * u.y() - x.y() * u.x();
}
}  // namespace

BrushSteady::BrushSteady(const BrushParameters& parameters) : BrushSlipModel(parameters)
{
}

BrushForces BrushSteady::evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const
{
  return integrate(sigma, phi, phi_gamma, phi_psi, nullptr);
}

BrushForces BrushSteady::evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                                  const Visitor& visit) const
{
  return integrate(sigma, phi, phi_gamma, phi_psi, &visit);
}

BrushForces BrushSteady::integrate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                                   const Visitor* visit) const
{
  BrushForces out;
  const double a = p_.a, k = p_.k;
  const int n = p_.resolution;
  if (!p_.tilt)
    phi_gamma = phi_psi = 0.0;  // Sect. 3: straight paths, chi_psi u neglected
  const bool straight = std::abs(phi_gamma) * a < kStraightPathTolerance;
  const double c = straight ? 0.0 : 1.0 / phi_gamma;  // tilting centre (0, c), eq. 36 with epsilon = (0, 1)
  if (!straight && std::abs(c) < a)
  {
    out.flags |= brush_flags::kNoSteadyStateTilt;
    return out;
  }
  const FrictionCap cap(p_);
  // drive of eqs. 11/32: sigma + A_phi x, with A_phi x = (-phi y, phi x)
  const auto drive = [&](const Eigen::Vector2d& x) { return Eigen::Vector2d(sigma.x() - phi * x.y(), sigma.y() + phi * x.x()); };

  Eigen::Vector2d F = Eigen::Vector2d::Zero();
  double M_z = 0.0, area = 0.0, sliding_area = 0.0, utilisation = 0.0, load = 0.0;
  const double dtheta = pi / n;
  for (int j = 0; j < n; ++j)
  {
    const double theta = -0.5 * pi + (j + 0.5) * dtheta;
    const double width = a * std::cos(theta) * dtheta;  // dy or d rho
    // Leading-edge entry point (x*, y*) and the path's length in travelled distance.
    double x_entry, y_entry, length;
    if (straight)
    {
      y_entry = a * std::sin(theta);
      x_entry = std::sqrt(std::max(0.0, a * a - y_entry * y_entry));  // eq. 19a
      length = 2.0 * x_entry;
    }
    else
    {
      const double rho = std::abs(c) + a * std::sin(theta);  // circle about the tilting centre (eq. 44a)
      y_entry = (a * a - rho * rho + c * c) / (2.0 * c);
      x_entry = std::sqrt(std::max(0.0, a * a - y_entry * y_entry));
      const double half_angle = std::atan2(x_entry, std::copysign(1.0, c) * (c - y_entry));
      length = 2.0 * half_angle * std::abs(c);  // angle / |phi_gamma|
    }
    const double h = length / n;
    const Eigen::Vector2d centre(0.0, c), entry(x_entry, y_entry);
    // position after travelling t from the leading edge: a shift by -t, or a rotation about (0, c) by
    // -phi_gamma t (eq. 39b)
    const auto along = [&](double t) -> Eigen::Vector2d {
      if (straight)
        return entry - Eigen::Vector2d(t, 0.0);
      return centre + rotate(std::cos(phi_gamma * t), -std::sin(phi_gamma * t), entry - centre);
    };
    const double cg = std::cos(phi_gamma * h), sg = -std::sin(phi_gamma * h);  // one step along a circle
    const auto advance = [&](const Eigen::Vector2d& x) -> Eigen::Vector2d {
      if (straight)
        return x - Eigen::Vector2d(h, 0.0);
      return centre + rotate(cg, sg, x - centre);
    };
    // Nodes at the middle of n equal cells (midpoint rule: none on the patch edge, where q_z = 0). The
    // bristle steps node to node: u <- R(L) u + R(L/2) drive(x_mid) L, with R the turn coupling of eq. 40b
    // (second order; exact on straight paths without coupling, where the drive is linear along the path).
    const auto step = [&](const Eigen::Vector2d& u, double L, const Eigen::Vector2d& x_mid) -> Eigen::Vector2d {
      const Eigen::Vector2d g = drive(x_mid) * L;
      if (phi_psi == 0.0)
        return u + g;
      return rotate(std::cos(phi_psi * L), std::sin(phi_psi * L), u) +
             rotate(std::cos(0.5 * phi_psi * L), std::sin(0.5 * phi_psi * L), g);
    };
    const double cp = std::cos(phi_psi * h), sp = std::sin(phi_psi * h);
    const double cph = std::cos(0.5 * phi_psi * h), sph = std::sin(0.5 * phi_psi * h);

    Eigen::Vector2d node = along(0.5 * h), mid = along(h);
    Eigen::Vector2d u = step(Eigen::Vector2d::Zero(), 0.5 * h, along(0.25 * h));
    for (int i = 0; i < n; ++i)
    {
      if (i > 0)
      {
        node = advance(node);
        const Eigen::Vector2d g = drive(mid) * h;
        u = phi_psi == 0.0 ? Eigen::Vector2d(u + g) : Eigen::Vector2d(rotate(cp, sp, u) + rotate(cph, sph, g));
        mid = advance(mid);
      }
      const FrictionCap::Result r = cap.apply(u, node, drive(node));
      utilisation = std::max(utilisation, r.utilisation);
      const double dA = width * h * (straight ? 1.0 : std::abs(phi_gamma) * (node - centre).norm());
      F += k * u * dA;
      M_z += k * cross(node, u) * dA;
      load += r.q_z * dA;
      if (r.sliding)
        sliding_area += dA;
      area += dA;
      if (visit)
        (*visit)(node, u, r.sliding);
    }
  }
  // Quadrature weights normalised so that the discrete integral of q_z is F_z (an O(h^2) correction):
  // every bristle obeys |q| <= mu q_z, so then |F_t| <= mu F_z holds exactly, not just to O(h^2).
  const double eta = load > 0.0 ? p_.F_z / load : 1.0;
  out.F_x = eta * F.x();
  out.F_y = eta * F.y();
  out.M_z = eta * M_z;
  out.sliding_fraction = area > 0.0 ? sliding_area / area : 0.0;
  out.max_utilisation = utilisation;
  return out;
}

}  // namespace sphere_contact_estimator
