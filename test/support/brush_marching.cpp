#include "brush_marching.h"

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "friction_cap.h"

namespace sphere_contact_estimator::test
{
namespace
{
using boost::math::double_constants::pi;

Eigen::Vector2d rotate(double c, double s, const Eigen::Vector2d& v)
{
  return { c * v.x() - s * v.y(), s * v.x() + c * v.y() };
}

}  // namespace

BrushMarching::BrushMarching(const BrushParameters& parameters) : BrushSlipModel(parameters)
{
}

BrushForces BrushMarching::evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const
{
  return integrate(sigma, phi, phi_gamma, phi_psi, nullptr);
}

BrushForces BrushMarching::evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                                  const Visitor& visit) const
{
  return integrate(sigma, phi, phi_gamma, phi_psi, &visit);
}

BrushForces BrushMarching::integrate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                                   const Visitor* visit) const
{
  BrushForces out;
  const double a = p_.a, k = p_.k;
  const int n = p_.resolution;            // paths across the patch
  const int m = kStepsPerPath * n;        // cells along each path
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
  const bool coulomb = p_.sliding_law == SlidingLaw::Coulomb;
  // the drive of eqs. 11/32 is sigma + A_phi x, with A_phi x = (-phi y, phi x)

  // sums per path (Fx, Fy, M_z, load), then times the path's cell area; k applied at the end
  Eigen::Vector2d F = Eigen::Vector2d::Zero();
  double Fx = 0.0, Fy = 0.0, M_z = 0.0, load = 0.0, M_total = 0.0, load_total = 0.0;
  double area = 0.0, sliding_area = 0.0, utilisation2 = 0.0;
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
    const double h = length / m;
    const Eigen::Vector2d centre(0.0, c), entry(x_entry, y_entry);
    // position after travelling t from the leading edge: a shift by -t, or a rotation about (0, c) by
    // -phi_gamma t (eq. 39b)
    const auto along = [&](double t) -> Eigen::Vector2d {
      if (straight)
        return entry - Eigen::Vector2d(t, 0.0);
      return centre + rotate(std::cos(phi_gamma * t), -std::sin(phi_gamma * t), entry - centre);
    };
    // Nodes at the middle of n equal cells (midpoint rule: none on the patch edge, where q_z = 0). The
    // bristle steps node to node: u <- R(L) u + R(L/2) drive(x_mid) L, with R the turn coupling of eq. 40b
    // (second order; exact on straight paths without coupling, where the drive is linear along the path).
    // Scalar code: this loop is the model's whole cost.
    const bool coupled = phi_psi != 0.0;
    double cg = 1.0, sg = 0.0, cp = 1.0, sp = 0.0, cph = 1.0, sph = 0.0;
    if (!straight)
    {
      cg = std::cos(phi_gamma * h);  // one step along the circle: R(-phi_gamma h) about (0, c)
      sg = -std::sin(phi_gamma * h);
    }
    if (coupled)
    {
      cp = std::cos(phi_psi * h);
      sp = std::sin(phi_psi * h);
      cph = std::cos(0.5 * phi_psi * h);
      sph = std::sin(0.5 * phi_psi * h);
    }
    // area of a cell: width times its length along the path, |v| h, with |v| = |phi_gamma| rho on a circle
    const double dA = width * h * (straight ? 1.0 : std::abs(phi_gamma) * (entry - centre).norm());
    const Eigen::Vector2d first_node = along(0.5 * h), first_mid = along(0.25 * h), second_mid = along(h);
    double nx = first_node.x(), ny = first_node.y(), mx = second_mid.x(), my = second_mid.y();
    // first half step from the leading edge, undeformed (eq. 8)
    double ux, uy;
    {
      const double L = 0.5 * h, gx = (sigma.x() - phi * first_mid.y()) * L, gy = (sigma.y() + phi * first_mid.x()) * L;
      const double c = coupled ? std::cos(0.5 * phi_psi * L) : 1.0, s = coupled ? std::sin(0.5 * phi_psi * L) : 0.0;
      ux = c * gx - s * gy;
      uy = s * gx + c * gy;
    }
    for (int i = 0; i < m; ++i)
    {
      if (i > 0)
      {
        const double gx = (sigma.x() - phi * my) * h, gy = (sigma.y() + phi * mx) * h;  // drive at the step's middle
        if (coupled)
        {
          const double rx = cp * ux - sp * uy, ry = sp * ux + cp * uy;
          ux = rx + cph * gx - sph * gy;
          uy = ry + sph * gx + cph * gy;
        }
        else
        {
          ux += gx;
          uy += gy;
        }
        if (straight)
        {
          nx -= h;
          mx -= h;
        }
        else
        {
          const double px = nx, py = ny - c, qx = mx, qy = my - c;
          nx = cg * px - sg * py;
          ny = c + sg * px + cg * py;
          mx = cg * qx - sg * qy;
          my = c + sg * qx + cg * qy;
        }
      }
      // Rigid: slides along drive(node). Coulomb: the return mapping, back onto the bound along the trial itself
      // (backward Euler of eq. 4b); re-adhesion is then automatic.
      const FrictionCap::Result r = coulomb ? cap.apply(ux, uy, nx, ny, ux, uy) :
                                              cap.apply(ux, uy, nx, ny, sigma.x() - phi * ny, sigma.y() + phi * nx);
      utilisation2 = std::max(utilisation2, r.utilisation2);
      Fx += ux;
      Fy += uy;
      M_z += nx * uy - ny * ux;
      load += r.q_z;
      if (r.sliding)
        sliding_area += dA;
      area += dA;
      if (visit)
        (*visit)(Eigen::Vector2d(nx, ny), Eigen::Vector2d(ux, uy), r.sliding);
    }
    // every cell of a path has the same area
    F += Eigen::Vector2d(Fx, Fy) * dA;
    M_total += M_z * dA;
    load_total += load * dA;
    Fx = Fy = M_z = load = 0.0;
  }
  // Quadrature weights normalised so that the discrete integral of q_z is F_z (an O(h^2) correction):
  // every bristle obeys |q| <= mu q_z, so then |F_t| <= mu F_z holds exactly, not just to O(h^2).
  const double eta = load_total > 0.0 ? p_.F_z / load_total : 1.0;
  out.F_x = k * eta * F.x();
  out.F_y = k * eta * F.y();
  out.M_z = k * eta * M_total;
  out.sliding_fraction = area > 0.0 ? sliding_area / area : 0.0;
  out.max_utilisation = std::sqrt(utilisation2);
  return out;
}

}  // namespace sphere_contact_estimator::test
