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

}  // namespace sphere_contact_estimator::numerics
