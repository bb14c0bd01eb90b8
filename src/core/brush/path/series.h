#pragma once

// STL
#include <cmath>
#include <complex>

// Package
#include "bristle_path.h"

/// The Taylor series along a bristle path that both sliding laws build their events and adhesion pieces from
/// (private to the path solver).
namespace sphere_contact_estimator::path
{
using cd = std::complex<double>;

constexpr int kMaxDegree = 30;         // of the Taylor series along a path
constexpr int kSize = kMaxDegree + 2;  // the position series carries one more term (for d(r^2)/dtau)
constexpr double kSeriesTolerance = 1e-17;

inline cd timesI(double a, cd z) { return { -a * z.imag(), a * z.real() }; }  // i a z
inline double dot(cd a, cd b) { return a.real() * b.real() + a.imag() * b.imag(); }    // Re(a conj(b))
inline double cross(cd a, cd b) { return a.real() * b.imag() - a.imag() * b.real(); }  // Im(conj(a) b)

/// phi_1(i x) = (e^{ix} - 1) / (ix) and phi_2(i x) = (e^{ix} - 1 - ix) / (ix)^2, without cancellation.
cd phi1(double x);
cd phi2(double x);

/// Degree of the series along a path stretch on which the fastest turn is rate * length = x radians.
int seriesDegree(double x);

/// Truncated Cauchy products of series of degree n: a b, and Re(a conj(b)) termwise.
void multiply(const double* a, const double* b, int n, double* out);
void dotSeries(const cd* a, const cd* b, int n, double* out);
/// Integral over [lo, hi] of a series; value of a complex series at s.
double integrate(const double* c, int n, double lo, double hi);
cd evaluate(const cd* c, int n, double s);

/// One stretch [t0, t1] of a path with the Taylor series, about tm, of everything the events need: the root's
/// position z, the drive w = sigma + i phi z, t = 1 - r^2 (the pressure law's variable), d(r^2)/dtau, and the
/// squared bound f^2 = t^m (PressureLaw::squaredExponent).
struct Segment
{
  double t0 = 0.0, t1 = 0.0, tm = 0.0;
  int n = 4;
  cd Z[kSize], W[kSize];
  double T[kSize];   // t = 1 - r^2
  double D[kSize];   // d(r^2)/dtau = -2 x on a straight path
  double B2[kSize];  // f^2
  long work = 0;     // what building it took

  /// Series about `centre` (the midpoint by default; an adhesion piece expands about its own start, where its
  /// event polynomial is small and its low-order coefficients exact).
  void build(const BristleField& f, const BristlePath& p, double a, double b, int degree, double centre = NAN);
};

/// The adhering bristle's series on a segment from its deflection u_s at travel tau_s:
/// u' = w + i kappa u (eqs. 15c, 35c)  ->  U_{k+1} = (i kappa U_k + W_k) / (k + 1), with U_0 from u(tau_s) = u_s.
void adhesionSeries(const BristleField& f, const Segment& g, double tau_s, cd u_s, cd* U);

}  // namespace sphere_contact_estimator::path
