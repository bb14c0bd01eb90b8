#pragma once

namespace sphere_contact_estimator::numerics
{
/// Largest polynomial degree the root isolation takes.
constexpr int kMaxPolynomialDegree = 40;

/// p(s) = sum_{i <= n} c[i] s^i by Horner's rule.
double evaluatePolynomial(const double* c, int n, double s);

/// Where a real polynomial p(s) = sum_{i <= n} c[i] s^i (n <= kMaxPolynomialDegree) changes sign on the open
/// interval (lo, hi), lo < hi: the roots of odd multiplicity, in increasing order, each to machine precision.
///
/// Isolation is exact (no sampling): the polynomial is written in the Bernstein basis of [lo, hi], whose
/// coefficients' sign changes bound the number of roots (Descartes' rule); an interval with one sign change
/// holds exactly one root, which Newton's method kept inside the bracket finds to machine precision; one with more is halved by de
/// Casteljau's algorithm. A root of even multiplicity (a touch) is no sign change and is not reported.
///
/// Writes at most max_roots roots to `roots` and returns how many it wrote; with max_roots = 1 it stops at the
/// first, which is what an event search needs.
int signChanges(const double* c, int n, double lo, double hi, double* roots, int max_roots);

}  // namespace sphere_contact_estimator::numerics
