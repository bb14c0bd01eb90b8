#pragma once

// STL
#include <array>
#include <complex>
#include <cstdint>
#include <limits>

// Package
#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "sphere_contact_estimator/core/brush/coulomb_stepper.h"
#include "pressure_law.h"

namespace sphere_contact_estimator
{
/// The steady bristle problem of Romano et al. (Sects. 3, 4 and 6) in the frame with epsilon = (0, 1),
/// made dimensionless: positions and travel in units of the patch radius a, deflections in units of the
/// largest friction bound mu q_z(0) / k (so that the bound is f(r^2) <= 1), complex numbers for plane vectors
/// (z = x + i y; the skew tensor A_phi of eq. 12c is multiplication by i phi).
///
/// Along a characteristic the root moves as dz/dtau = -1 + i omega z (eqs. 15b, 35b: a straight line, or a
/// circle about the tilting centre (0, -1/omega)), and an adhering bristle as du/dtau = w(z) + i kappa u
/// (eqs. 11, 32) with the drive w(z) = sigma + i phi z, starting undeformed at the leading edge (eq. 8).
/// Limited friction (eq. 4): |u| <= f(r^2); a sliding bristle has |u| = f, its direction set by the sliding law:
/// eq. (4b) with the full micro-sliding velocity (SlidingLaw::Coulomb), or along the rigid sliding field,
/// u = f w / |w| (Sect. 6, SlidingLaw::Rigid).
struct BristleField
{
  std::complex<double> sigma;  ///< slip sigma / beta, beta = mu q_z(0) / (k a) [-]
  double phi = 0.0;            ///< spin phi a / beta [-]
  double kappa = 0.0;          ///< turn coupling phi_psi a of eq. 32 (0 in the Sect. 3 formulation) [-]
  double omega = 0.0;          ///< turn of the roots per unit travel, -phi_gamma a (eq. 39b); 0: straight paths
  PressureLaw pressure{ PressureDistribution::Parabolic };
  SlidingLaw law = SlidingLaw::Coulomb;

  /// The drive w(z) = sigma + i phi z, which is also the rigid sliding field.
  std::complex<double> drive(std::complex<double> z) const { return sigma + std::complex<double>(-phi * z.imag(), phi * z.real()); }
  /// The bound f(r^2) = mu q_z / (mu q_z(0)): 1 - r^2, sqrt(1 - r^2) or 1 on the patch, 0 off it.
  double bound(double r2) const;
  /// Where the drive vanishes, the spin pole i sigma / phi (the sliding direction turns about it); phi != 0.
  std::complex<double> pole() const { return std::complex<double>(-sigma.imag(), sigma.real()) / phi; }
  /// Tilting centre's y (eq. 36 with epsilon = (0, 1)), -1 / omega; only with omega != 0.
  double tiltingCentre() const { return -1.0 / omega; }
  /// The largest |u| any bristle reaches: adhering, |du/dtau| <= |w| (the turn coupling only rotates u); sliding
  /// outside G, |u| = f grows slower than |w| (G is where it would grow faster); so |u| <= min(1, travel max|w|),
  /// with travel <= pi and |w| <= |sigma| + |phi| on the patch. Tiny slips give a tiny bound.
  double deflectionBound() const;
};

/// The dimensionless problem of a brush at these slips (frame with epsilon = (0, 1); phi_gamma and phi_psi used
/// with p.tilt only; tilt radii beyond 1e12 a count as straight). False when there is nothing to integrate: no
/// friction or no load.
bool makeBristleField(const BrushParameters& p, const std::complex<double>& sigma, double phi, double phi_gamma,
                      double phi_psi, BristleField& out);

/// The bound at the patch centre, mu q_z(0) / k [m]: the unit of the field's deflections.
double deflectionUnit(const BrushParameters& p);

/// No limit on a path's work (solvePath).
constexpr long kUnlimitedWork = 1L << 62;

/// One characteristic, identified by where it crosses the y axis: y0 = sin(theta). Straight paths are the
/// lines y = y0 (eq. 18a); with tilt the circles about the tilting centre through (0, y0) (eq. 44a).
struct BristlePath
{
  double theta = 0.0;                ///< the path's coordinate across the patch, y0 = sin(theta)
  std::complex<double> entry;        ///< leading-edge point z_e (eqs. 19a, 45)
  std::complex<double> velocity;     ///< dz/dtau at the leading edge, -1 + i omega z_e
  double omega = 0.0;                ///< as BristleField::omega
  double length = 0.0;               ///< travel from the leading to the trailing edge
  double weight = 0.0;               ///< area element: dA = weight dtheta dtau

  /// The path at theta in (-pi/2, pi/2) for the field's kinematics. The circle's entry point and length are
  /// written so that they stay accurate for any tilting radius (no 1/omega cancels).
  static BristlePath across(const BristleField& field, double theta);
  /// The root's position after travelling tau from the leading edge (eq. 17b / 39b).
  std::complex<double> position(double tau) const;
  /// 1 - r^2 there, written so that it does not cancel near the edges (tau(L - tau) on a straight path).
  double edgeDistance(double tau) const;
  /// The same at travel `near` from the nearer end of the path (the path is symmetric about x = 0), for callers
  /// that know that distance better than length - tau.
  double edgeDistanceNear(double near) const;
};

/// A piece of one path: the bristle adheres (from its deflection at the start) or slides over [begin, end].
struct PathPiece
{
  double begin = 0.0, end = 0.0;
  bool adhering = false;
  std::complex<double> u_begin;  ///< deflection at begin
};

/// What one path contributes, as integrals over its travel (dimensionless as above).
struct PathIntegrals
{
  std::complex<double> force;    ///< integral of u dtau
  double moment = 0.0;           ///< integral of Im(conj(z) u) dtau (x u_y - y u_x)
  double sliding = 0.0;          ///< travel spent sliding
  double utilisation2 = 0.0;     ///< largest (|u| / f)^2 seen: 1 if any bristle slides, else sampled
  double error = 0.0;            ///< bound on the error of the along-path quadrature of the sliding pieces
  std::uint64_t signature = 0;   ///< the event structure: equal signatures, no jump between two paths
  /// With the uniform pressure, the largest |u|^2 - f^2 the bristle reaches adhering from the leading edge (in
  /// the stretch where its onset is searched): > 0 where it starts sliding before the trailing edge. Smooth
  /// across paths, so a sign change between two paths of equal signature shows a band of other structure.
  double onset_margin = 1.0;
  /// The value of |u|^2 - f^2 at its first interior local maximum along the first adhesion piece (the bristle
  /// adhering, continued through the piece's stretches); NaN if it has none. Smooth across paths while that maximum
  /// exists, and 0 where it touches the bound: there the onset of sliding jumps from a later crossing to this one, a
  /// jump in the path's integrals that the signature shows only on a band of paths as narrow as the dip after the
  /// maximum. A sign change between two paths of equal signature shows it.
  double fold = std::numeric_limits<double>::quiet_NaN();
  bool truncated = false;        ///< rates too large for the series budget: the path's tail is not resolved
  /// Work done: series coefficients and rule nodes computed (a measure of cost that does not depend on the
  /// machine, for budgets).
  long work = 0;

  static constexpr int kMaxPieces = 16;
  int pieces = 0;
  std::array<PathPiece, kMaxPieces> piece{};  ///< filled only on request (solve's keep_pieces)
};

/// Solves one path from the leading edge (eq. 8) to the trailing edge, piece by piece with exact events.
/// Adhering pieces follow eqs. 15c / 35c exactly (Taylor series of the exact path, to machine precision), and
/// the onset of sliding (|u| reaches f) is located as a root of a polynomial. Sliding pieces follow the field's
/// law: under SlidingLaw::Rigid the bristle lies along the drive, re-adheres where the bound grows along the path
/// faster than the drive pushes it (df/dtau >= |w|, the region G, fixed in the plane; located as roots), and is
/// integrated by Gauss-Legendre rules graded towards the spin pole; under SlidingLaw::Coulomb its direction follows
/// eq. (4b) (path/coulomb_collocation.h, path/coulomb_sliding.h) and it re-adheres where its own sliding speed vanishes. `tolerance` bounds
/// the sliding pieces' error. A path whose work would pass `work_limit` stops there, flagged truncated. `stepper` chooses
/// how eq. (4b)'s sliding pieces are stepped (both to the tolerance).
PathIntegrals solvePath(const BristleField& field, const BristlePath& path, double tolerance, bool keep_pieces = false,
                        long work_limit = kUnlimitedWork, CoulombStepper stepper = CoulombStepper::Collocation);

/// Re-adhesion margin at z in the front half of the patch: (df/dtau)^2 - |w|^2, scaled by a positive factor
/// (4 (1 - r^2) for the Hertzian pressure); >= 0 exactly where a sliding bristle re-adheres (the region G, fixed
/// in the plane: d(r^2)/dtau = -2x on every path, straight or circular). Always < 0 for the uniform pressure.
double reAdhesionMargin(const BristleField& field, std::complex<double> z);

/// The largest re-adhesion margin along the front half of a path: >= 0 iff the path meets G. `work`, if given, is
/// raised by the polynomials' root isolations (kRootWork).
double reAdhesionPeak(const BristleField& field, const BristlePath& path, long* work = nullptr);

/// How many separate stretches of G the front half of a path crosses (`work` as reAdhesionPeak's).
int reAdhesionCount(const BristleField& field, const BristlePath& path, long* work = nullptr);

/// The work reAdhesionPeak or reAdhesionCount will count on this path (before doing it: a search within a budget).
long reAdhesionWork(const BristleField& field, const BristlePath& path);

/// A polynomial of degree n along a path whose roots are isolated, in PathIntegrals::work units: its series built
/// and multiplied and its sign changes isolated, about 50 (50 + n^2) instructions (callgrind: 24 000 for degree 22 on
/// a tilted path, 3 400 for a straight path's quartic).
inline long kRootWork(int n) { return 50 + static_cast<long>(n) * n; }

/// Where the path through z crosses the y axis (its y0; straight: z's y), written without 1/omega.
double pathThrough(const BristleField& field, std::complex<double> z);

/// The deflection at travel tau on a path solved with keep_pieces (for drawing the field).
std::complex<double> deflectionAt(const BristleField& field, const BristlePath& path, const PathIntegrals& solved,
                                  double tau, bool* sliding = nullptr);

}  // namespace sphere_contact_estimator
