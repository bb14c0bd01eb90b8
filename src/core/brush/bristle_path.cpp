#include "bristle_path.h"

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "path/coulomb_sliding.h"
#include "path/rigid_sliding.h"
#include "path/series.h"

namespace sphere_contact_estimator
{
using path::cd;
using path::timesI;

double deflectionUnit(const BrushParameters& p)
{
  return p.mu * peakFactor(p.pressure) * p.F_z / (boost::math::double_constants::pi * p.a * p.a) / p.k;
}

bool makeBristleField(const BrushParameters& p, const std::complex<double>& sigma, double phi, double phi_gamma,
                      double phi_psi, BristleField& f)
{
  const double beta = deflectionUnit(p) / p.a;  // the largest bound, in units of a
  if (!(beta > 0.0 && std::isfinite(beta)))
    return false;
  f.sigma = sigma / beta;
  f.phi = phi * p.a / beta;
  f.pressure = PressureLaw(p.pressure);
  f.law = p.sliding_law;
  f.kappa = p.tilt ? phi_psi * p.a : 0.0;
  f.omega = p.tilt ? -phi_gamma * p.a : 0.0;
  if (std::abs(f.omega) < 1e-12)  // |R_gamma| > 1e12 a: straight
    f.omega = 0.0;
  return true;
}

double BristleField::deflectionBound() const
{
  return std::min(1.0, boost::math::double_constants::pi * (std::abs(sigma) + std::abs(phi)));
}

double BristleField::bound(double r2) const
{
  return pressure.shape(1.0 - r2);
}

BristlePath BristlePath::across(const BristleField& field, double theta)
{
  BristlePath p;
  p.theta = theta;
  p.omega = field.omega;
  const double y0 = std::sin(theta), c = std::cos(theta);
  if (field.omega == 0.0)
  {
    p.entry = cd(c, y0);
    p.length = 2.0 * c;
    p.weight = c;
  }
  else
  {
    // the circle about (0, -1/omega) through (0, y0): entry y_e = (1 - rho^2 + c^2) / (2c), written without 1/omega
    const double w = field.omega;
    const double y_e = std::clamp(y0 - 0.5 * w * (1.0 - y0 * y0), -1.0, 1.0);
    const double x_e = std::sqrt(std::max(0.0, 1.0 - y_e * y_e));
    p.entry = cd(x_e, y_e);
    // half the angle the arc subtends at the centre, from (0, y0) to the entry, both scaled by omega
    const double half = std::atan2(x_e * std::abs(w) * std::abs(1.0 + w * y0), (1.0 + w * y_e) * (1.0 + w * y0));
    p.length = 2.0 * half / std::abs(w);
    p.weight = c * std::abs(1.0 + w * y0);  // rho |omega| d(rho) / d(theta)
  }
  p.velocity = cd(-1.0, 0.0) + timesI(field.omega, p.entry);
  return p;
}

std::complex<double> BristlePath::position(double tau) const
{
  return entry + tau * path::phi1(omega * tau) * velocity;
}

double BristlePath::edgeDistance(double tau) const
{
  // r^2 = |c + e^{i omega tau} (z_e - c)|^2 with r(0) = 1 gives 1 - r^2 = 2 tau (x_e + tau Re(phi_2(i omega tau) v_0)),
  // v_0 the velocity at the entry (the 1/omega parts cancel exactly); the path is symmetric about x = 0, so the
  // nearer edge's form is used
  return edgeDistanceNear(std::min(tau, length - tau));
}

double BristlePath::edgeDistanceNear(double t) const
{
  if (!(t > 0.0))
    return 0.0;
  return 2.0 * t * (entry.real() + t * (path::phi2(omega * t) * velocity).real());
}

double pathThrough(const BristleField& field, std::complex<double> z)
{
  if (field.omega == 0.0)
    return z.imag();
  // the circle about (0, c), c = -1/omega, through z crosses the y axis at c - sgn(c) |z - i c|:
  // with t = x / (c - y), y0 = y - x t / (1 + sqrt(1 + t^2))
  const double t = -z.real() * field.omega / (1.0 + field.omega * z.imag());
  return z.imag() - z.real() * t / (1.0 + std::sqrt(1.0 + t * t));
}

std::complex<double> deflectionAt(const BristleField& field, const BristlePath& path, const PathIntegrals& solved,
                                  double tau, bool* sliding)
{
  for (int i = 0; i < solved.pieces; ++i)
  {
    const PathPiece& piece = solved.piece[i];
    if (tau < piece.begin || tau > piece.end)
      continue;
    if (sliding)
      *sliding = !piece.adhering;
    const cd z = path.position(tau);
    if (!piece.adhering && field.law == SlidingLaw::Rigid)
      return path::rigidSlidingDeflection(field, path, tau);
    if (!piece.adhering)
    {
      path::SlideStart start;
      start.tau = piece.begin;
      start.from_rim = piece.begin == 0.0 && field.pressure.vanishesAtRim();
      start.direction = std::abs(piece.u_begin) > 0.0 ? piece.u_begin / std::abs(piece.u_begin) : cd(1.0, 0.0);
      return field.bound(std::norm(z)) * path::coulombDirectionAt(field, path, start, tau);
    }
    // adhesion from the piece's start: a fresh single segment over [begin, tau] (closed form, as solvePath)
    BristlePath sub = path;
    sub.entry = path.position(piece.begin);
    sub.velocity = cd(-1.0, 0.0) + timesI(field.omega, sub.entry);
    sub.length = tau - piece.begin;
    if (!(sub.length > 0.0))
      return piece.u_begin;
    path::Segment g;
    const double rate = std::max(std::abs(field.omega), std::abs(field.kappa));
    g.build(field, sub, 0.0, sub.length, path::seriesDegree(rate * sub.length), 0.0);
    cd U[path::kSize];
    path::adhesionSeries(field, g, 0.0, piece.u_begin, U);
    return path::evaluate(U, g.n, sub.length - g.tm);
  }
  if (sliding)
    *sliding = false;
  return 0.0;
}

}  // namespace sphere_contact_estimator
