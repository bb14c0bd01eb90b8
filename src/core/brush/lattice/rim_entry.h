#pragma once

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator::lattice
{
/// One step of eq. (4b) for a bristle that slides in from the leading rim under the parabolic pressure (f = t, so the
/// bound b = c t vanishes there and grows as b'(0) s): the step from the rim (s = 0) to s = d along its straight path.
///
/// In the drive's frame T = tan(delta / 2) (delta the direction's angle from w) obeys T' = -lambda T - (omega / 2)
/// (1 + T^2), lambda = |w| / b, omega = (w x w') / |w|^2 (the exponential step's form, coulomb_slide.cpp). At the rim
/// lambda ~ kappa / s, kappa = |w(0)| / b'(0) (> 1 where the bristle slides from its entry), and the one solution
/// regular there is
///     T(d) = -int_0^d e^{-(Lambda(d) - Lambda(s))} (omega / 2) (1 + T^2) ds,
/// where e^{-(Lambda(d) - Lambda(s))} = (s / d)^kappa Psi(s) / Psi(d) with Psi smooth on [0, d]: Lambda with |w| as the
/// quadratic through its values at 0, d / 2 and d, in closed form against 1 / t = 1 / (t2 s (s - s_b)) (partial
/// fractions; nearRim's, with the rim crossing behind at 0). So the integral is d int_0^1 x^kappa phi(d x) dx with phi
/// = Psi (omega / 2) (1 + T^2) smooth: phi's interpolant at five Chebyshev-Lobatto points in x against x^kappa, in
/// closed form (int x^(kappa + k) = 1 / (kappa + k + 1)); its partial integrals give T at the nodes for the T^2 term,
/// two Picard passes. The exponential step from the rim takes -r(d) = -omega / (2 lambda) instead, whose lag
/// 1 / (kappa + 1) of the answer no shorter step removes (docs/speed_and_accuracy.md): there it took 4-5 steps each.
///
/// Its error bound on T(d): the interpolant's against the one through the three of them at 0, 1/2 and 1 (its integral's
/// difference, the cruder one's error), the fit of |w| (nearRim's bound on Lambda, through the kernel), and the Picard
/// passes' (a contraction's a posteriori bound), and t0's: 1 / t against 1 / (t - t0) changes Lambda(d) - Lambda(s) by
/// at most kappa |t0| / (t1 s) to first order, which the kernel's (s / d)^kappa weighs to |t0| / t1 max|phi|.
class RimEntry
{
public:
  struct Result
  {
    double T = 0.0;        // tan(delta / 2) at d, delta the direction's angle from the drive there
    double error = 0.0;    // bound on |T - T_true|
    bool pushed = false;   // pushed outward (w . e - db/ds >= 0) at every node: no re-adhesion seen within the step
    double reach = 1.0;    // where it does not apply for the step's length alone (Psi too steep), about the share of
                           // the step that would: < 1
  };

  /// c: the bound at the centre [m]; w0: the drive at the rim; w_dot: its rate along the path; t = t0 + t1 s + t2 s^2
  /// from the rim (t1 > 0 entering, t2 < 0; t0, the rim point's rounding, taken as 0 with its effect in the bound); d:
  /// the step (0 < d <= -t1 / (2 t2), half the way to the crossing ahead). False where the step does not apply
  /// (kappa <= 1: it adheres as it enters; a drive through zero or turning fast; the Picard passes not contracting).
  static bool step(double c, const Eigen::Vector2d& w0, const Eigen::Vector2d& w_dot, double t0, double t1, double t2,
                   double d, Result& out);
};

}  // namespace sphere_contact_estimator::lattice
