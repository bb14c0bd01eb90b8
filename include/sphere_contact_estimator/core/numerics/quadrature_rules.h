#pragma once

// STL
#include <array>

namespace sphere_contact_estimator::numerics
{
/// An m-point Gauss-Legendre rule on [-1, 1]: exact for polynomials of degree 2m - 1.
struct GaussLegendre
{
  static constexpr int kMaxPoints = 32;
  int m = 0;
  std::array<double, kMaxPoints> x{}, w{};
};

/// The m-point rule, 1 <= m <= GaussLegendre::kMaxPoints (nodes by Newton's method on P_m, built once).
const GaussLegendre& gaussLegendre(int m);

/// The 15-point Gauss-Kronrod rule on [-1, 1] with its embedded 7-point Gauss rule (Boost.Math's nodes):
/// x[i] ascending, wk the Kronrod weights, wg the Gauss weights (0 at the 8 Kronrod-only nodes). The
/// difference of the two sums is the classic error estimate of the Kronrod sum.
struct GaussKronrod15
{
  std::array<double, 15> x{}, wk{}, wg{};
};

const GaussKronrod15& gaussKronrod15();

/// Weights (on [-1, 1]) of the interpolatory rule on the 8 nodes of gaussKronrod15() that its Gauss rule lacks (exact
/// to degree 7), in the order of gaussKronrod15().x (0 at the Gauss nodes): a third, lower-degree view of the same
/// samples, to tell whether the rules converge (a null rule of the error estimate).
const std::array<double, 15>& kronrodComplement();

/// The 7-point Gauss-Kronrod rule on [-1, 1] with its embedded 3-point Gauss rule (degrees 11 and 5), laid out as
/// GaussKronrod15: for intervals narrow enough that fewer nodes meet a tolerance.
struct GaussKronrod7
{
  std::array<double, 7> x{}, wk{}, wg{};
};

const GaussKronrod7& gaussKronrod7();

/// The interpolatory rule on the 4 nodes of gaussKronrod7() that its Gauss rule lacks (exact to degree 3), as
/// kronrodComplement.
const std::array<double, 7>& kronrod7Complement();

/// Gauss-Kronrod pairs for the weight (1 - y^2)^(3/2) on [-1, 1] (Jacobi's, alpha = beta = 3/2): the n-point Gauss rule of
/// that weight (exact to degree 2n - 1) embedded in Kronrod's extension of it to 2n + 1 nodes (exact to degree 3n + 1),
/// and the interpolatory rule of the same weight on the n + 1 Kronrod-only nodes (exact to degree n): nodes y ascending,
/// wk, wg (0 at the Kronrod-only nodes), wr (0 at the Gauss ones), as GaussKronrod15 and kronrodComplement. Kronrod's
/// extension exists for this weight (Gegenbauer's with lambda = 2) with real nodes inside (-1, 1) and positive weights.
struct JacobiKronrod
{
  static constexpr int kMinPoints = 3, kMaxPoints = 6;  // n
  int n = 0;
  int size = 0;  // 2n + 1
  std::array<double, 2 * kMaxPoints + 1> y{}, wk{}, wg{}, wr{};
};

/// The pair with n Gauss points, kMinPoints <= n <= kMaxPoints (nodes and weights to 21 digits, computed from the
/// weight's moments in 60-digit arithmetic; test QuadratureRules.JacobiKronrodIsExactForItsWeight).
const JacobiKronrod& jacobiKronrod(int n);

/// Builds every rule above that is built on first use (the Gauss-Legendre rules by Newton's iterations, about 0.4 ms,
/// and the complements): once per process, so that no message pays for it (ContactEstimator does at construction).
void prepareQuadratureRules();

}  // namespace sphere_contact_estimator::numerics
