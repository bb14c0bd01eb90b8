#pragma once

// STL
#include <cmath>

namespace sphere_contact_estimator::numerics
{
/// A traceless real 2x2 matrix x H + y S + z J, H = diag(1, -1), S = [[0, 1], [1, 0]], J = [[0, 1], [-1, 0]]: the
/// generators of y' = M(s) y whose solution ratio y1 / y2 obeys a Riccati equation (a Moebius map over a step).
struct Sl2
{
  double x = 0.0, y = 0.0, z = 0.0;
};

inline Sl2 operator+(const Sl2& a, const Sl2& b) { return { a.x + b.x, a.y + b.y, a.z + b.z }; }
inline Sl2 operator-(const Sl2& a, const Sl2& b) { return { a.x - b.x, a.y - b.y, a.z - b.z }; }
inline Sl2 operator*(double s, const Sl2& a) { return { s * a.x, s * a.y, s * a.z }; }

/// [a, b] = ab - ba, from [H, S] = 2 J, [H, J] = 2 S, [S, J] = -2 H.
inline Sl2 bracket(const Sl2& a, const Sl2& b)
{
  return { -2.0 * (a.y * b.z - a.z * b.y), 2.0 * (a.x * b.z - a.z * b.x), 2.0 * (a.x * b.y - a.y * b.x) };
}

namespace detail
{
/// 1 / (2k)! and 1 / (2k + 1)!, k <= 12
struct CoshSinhSeries
{
  double C[13] = {}, S[13] = {};
  constexpr CoshSinhSeries()
  {
    double factorial = 1.0;  // n!
    for (int n = 0; n <= 25; ++n)
    {
      if (n > 0)
        factorial *= n;
      if (n % 2 == 0)
        C[n / 2] = 1.0 / factorial;
      else
        S[n / 2] = 1.0 / factorial;
    }
  }
};
constexpr CoshSinhSeries kCoshSinh;
}  // namespace detail

/// The second column of exp(X), the image y of (0, 1), and the gradient of its angle atan2(y1, y2) with respect to
/// X's coordinates (a perturbation dX turns y by grad . dX to first order). With X^2 = delta I,
/// delta = x^2 + y^2 - z^2, exp(X) = C(delta) I + S(delta) X, C = sum delta^k / (2k)!, S = sum delta^k / (2k + 1)!
/// (cosh sqrt(delta) and sinh sqrt(delta) / sqrt(delta), or cos and sin where delta < 0), S' = (C - S) / (2 delta):
/// their series by Horner's rule where |delta| <= 4, the closed forms beyond.
inline void expColumn2(const Sl2& X, double& y1, double& y2, double grad[3])
{
  const double delta = X.x * X.x + X.y * X.y - X.z * X.z;
  double C, S, S_dot;
  const double size = std::abs(delta);
  if (size <= 4.0)
  {
    // the degree that keeps the first term left out of each series below 2e-19
    const int n = size <= 0.01 ? 5 : (size <= 0.25 ? 8 : 12);
    C = detail::kCoshSinh.C[n], S = detail::kCoshSinh.S[n], S_dot = n * detail::kCoshSinh.S[n];
    for (int k = n - 1; k >= 0; --k)
    {
      C = C * delta + detail::kCoshSinh.C[k];
      S = S * delta + detail::kCoshSinh.S[k];
      if (k > 0)
        S_dot = S_dot * delta + k * detail::kCoshSinh.S[k];
    }
  }
  else
  {
    const double r = std::sqrt(std::abs(delta));
    C = delta > 0.0 ? std::cosh(r) : std::cos(r);
    S = (delta > 0.0 ? std::sinh(r) : std::sin(r)) / r;
    S_dot = (C - S) / (2.0 * delta);
  }
  const double v = X.y + X.z;
  y1 = S * v;
  y2 = C - S * X.x;
  // d y1 = S' v d delta + S (dy + dz), d y2 = (S / 2 - S' x) d delta - S dx, d delta = 2 (x dx + y dy - z dz);
  // d angle = (y2 d y1 - y1 d y2) / |y|^2
  const double n = 1.0 / (y1 * y1 + y2 * y2);
  const double a = (y2 * S_dot * v - y1 * (0.5 * S - S_dot * X.x)) * 2.0 * n;  // d angle / d delta, doubled
  grad[0] = a * X.x + y1 * S * n;
  grad[1] = a * X.y + y2 * S * n;
  grad[2] = -a * X.z + y2 * S * n;
}

/// Gauss's rule for the integral of M over a step, from the generator times the step at magnus6's nodes.
inline Sl2 gaussIntegral(const Sl2 A[3]) { return (5.0 / 18.0) * (A[0] + A[2]) + (8.0 / 18.0) * A[1]; }

/// Sixth-order Magnus exponent over a step, omega1 + the commutator terms, from the generator times the step,
/// A_i = d M(s + c_i d), at the three Gauss-Legendre nodes c = 1/2 -+ sqrt(15) / 10, 1/2 (Blanes, Casas and Ros 2000:
/// local error O(d^7) with omega1 = gaussIntegral(A), or the integral of M in closed form). Also a fourth-order
/// exponent for an embedded estimate, omega1_low with the first commutator term alone: the two differ by the
/// commutator terms of fifth order and up and by omega1 - omega1_low (a lower-order rule's difference from omega1's).
inline Sl2 magnus6(const Sl2 A[3], const Sl2& omega1, const Sl2& omega1_low, Sl2& fourth)
{
  static constexpr double kRoot15Over3 = 1.2909944487358056;  // sqrt(15) / 3
  const Sl2 a1 = A[1], a2 = kRoot15Over3 * (A[2] - A[0]), a3 = (10.0 / 3.0) * (A[0] - 2.0 * A[1] + A[2]);
  const Sl2 C1 = bracket(a1, a2);
  const Sl2 C2 = (-1.0 / 60.0) * bracket(a1, 2.0 * a3 + C1);
  fourth = omega1_low - (1.0 / 12.0) * C1;
  return omega1 + (1.0 / 240.0) * bracket(C1 - 20.0 * a1 - a3, a2 + C2);
}

/// Gauss-Legendre nodes of magnus6.
constexpr double kMagnusNodes[3] = { 0.11270166537925831, 0.5, 0.88729833462074169 };

}  // namespace sphere_contact_estimator::numerics
