#include "bristle_advance.h"

// STL
#include <algorithm>
#include <cmath>

// Package
#include "sphere_contact_estimator/core/numerics/magnus_sl2.h"
#include "rim_entry.h"
#include "rim_integral.h"

// eq. (4b)'s sliding along a bristle's path over an update: without rolling in closed form (coulombSlideStill);
// rolling, by steps along each sliding piece (coulombSlide, the class CoulombSlide), and the steps' kinds: the return
// mapping, the exponential step (with nearRim's integral of the pull), the Magnus step (in CoulombSlide), and from the
// leading rim under the parabolic pressure RimEntry's (rim_entry.h).

namespace sphere_contact_estimator::lattice
{
namespace
{
// exponentialStep: a step longer than this share of its distance to a rim crossing integrates lambda against the
// bound's shape (nearRim); up to it Simpson's rule stands, the trapezoid's difference above its error (at half the
// distance to a pole 1 / (rho - s), 0.014 against 0.0013 of the integral's 0.69)
constexpr double kRimNear = 0.5;
// A step with pull |w| / b times its length above this is stiff: the Magnus series' reach (it converges below pi)
constexpr double kStiffPull = 3.0;
// The shortest first try a neighbour's step suggests (BristleAdvance::advance's first_step), as a share of the span: the
// shortest retry after a rejected step
constexpr double kFirstStepShare = 0.2;
// coulombSlideFrozen: within this share of the tolerance. Its bound stands about 5 times above its error (test
// BristleAdvance.SlidingStepErrorBoundsTheErrorInPlaceAndSlow) and carries no contraction beyond the frozen flow's,
// where the steps it spares claim theirs: at the whole tolerance the 1 kHz recording's pivot (0.3 m/s, half a spacing
// a message) took it too and its estimates rose by a tenth; spinning in place and parked it stands at a thousandth.
constexpr double kFrozenShare = 0.05;
// and only where the path is shorter than this share of the patch radius: its bound grows as Lambda^2 travel / a, which
// at the tolerance of the coarsest lattice passes this only for a pull Lambda of a few hundredths (1 kHz). Rolling
// pieces, which failed the check, made the 1 kHz recording 2 % dearer in all (callgrind) before this gate.
constexpr double kFrozenTravel = 2e-3;
// e^{-x}, the same number: past 746 it rounds to 0, which is returned without glibc's underflow path (errno and its
// checks: about 1.5 % of perf's samples of Fig. 4's message at resolution 64, from stiff steps by the rim)
inline double decay(double x) { return x > 746.0 ? 0.0 : std::exp(-x); }
// The unit vector h turned by 2 atan(T) (T the tangent of half the angle, as the steps carry a direction)
inline Eigen::Vector2d turned(const Eigen::Vector2d& h, double T)
{
  const double n = 1.0 / (1.0 + T * T), c = (1.0 - T * T) * n, sn = 2.0 * T * n;
  return { c * h.x() - sn * h.y(), sn * h.x() + c * h.y() };
}
}  // namespace

double BristleAdvance::coulombSlideStill(BristleState& s, const Eigen::Vector2d& x, double span) const
{
  // Without rolling the drive and the bound stay put: with delta the angle from w to u, b delta' = -|w| sin delta,
  // so tan(delta / 2) decays as e^{-|w| tau / b} (exact). It re-adheres at once where w pulls it back (w . u < 0).
  const double b = bound(x);
  const Eigen::Vector2d w = drive(x);
  const double wn = w.norm();
  if (b <= 0.0)
  {
    s.u.setZero();
    return INFINITY;
  }
  if (wn == 0.0)
    return INFINITY;  // no drive: it stays where it is
  const double un = s.u.norm();
  if (un == 0.0)
    return 0.0;
  const Eigen::Vector2d e_w = w / wn, e = s.u / un;
  const double cos_d = e.dot(e_w), sin_d = e_w.x() * e.y() - e_w.y() * e.x();
  if (cos_d < 0.0)
    return 0.0;
  const double k = sin_d / (1.0 + cos_d) * decay(wn * span / b), k2 = k * k;
  const double c = (1.0 - k2) / (1.0 + k2), sn = 2.0 * k / (1.0 + k2);
  s.u = b * (c * e_w + sn * Eigen::Vector2d(-e_w.y(), e_w.x()));
  return INFINITY;
}

bool BristleAdvance::coulombSlideFrozen(BristleState& s, const Eigen::Vector2d& x, double span) const
{
  // A piece that rolls far less than the drive and the bound change over (a parked or spinning robot's noise at 1 kHz):
  // the drive and the bound frozen at the path's middle m, coulombSlideStill's exact relaxation, where that is within
  // the tolerance. On the bound the direction obeys theta' = f(tau, theta) = -lambda sin(theta - psi), lambda = |w| / b,
  // psi = arg w; frozen, f_m. The difference D of the true and the frozen direction obeys D' = k D + r with
  // k = -lambda_m cos(xi - psi_m) in [-lambda_m, 0] within a right angle of the drive, and r(tau) = (f - f_m)(tau,
  // theta(tau)), which vanishes at m; so D(span) = int G r with 0 < G <= 1, |G(s) - G(m)| <= lambda_m |s - m|, and
  // since int r = int (r - r'(m) (s - m)):
  //   |D(span)| <= span^3 (R2 / 24 + lambda_m R1 / 12),   |D(tau)| <= R1 span^2 / 4 on the way,
  // R1 >= |r'|, R2 >= |r''| from the path's bounds on lambda, psi and their first two derivatives (w affine in tau,
  // b = c f(t), t quadratic) and |theta'| <= lambda. Third order: along the slow streams' bristles the first-order bound
  // (the integral of |f - f_m|) stood 45 times above the error and raised a parked robot's estimate by 2 %.
  // Both directions stay within a right angle (the frozen one turns towards the drive) and the true one pushed
  // outward, w . e - db/dtau > 0, checked with the angles' margins: else (and off the tolerance) false, u untouched.
  if (!(speed2_ * span * span * inv_a2_ <= kFrozenTravel * kFrozenTravel))
    return false;  // rolling: the check below would fail (and cost a fifth of a step each time)
  const double un = s.u.norm();
  const Eigen::Vector2d x_m = x - 0.5 * span * V_r_, w = drive(x_m);
  const double wn = w.norm(), dw = 0.5 * span * w_dot_norm_;
  if (!(un > 0.0 && dw < 0.5 * wn))
    return false;
  const Quadratic t = tAlong(x);
  const double t_end = t.t0 + span * (t.t1 + span * t.t2);
  const double t_lo = std::min(t.t0, t_end);
  if (!(t_lo > 0.0))
    return false;  // a rim crossing: the bound's pole is the stepping's
  const double b_lo = c_ * pressure_.shape(t_lo), b_m = bound(x_m);
  const double b0 = c_ * pressure_.shape(t.t0), b1 = c_ * pressure_.shape(t_end);
  // along the path: |t'| <= T1, t'' = 2 t2; f' and |f''| are largest at t_lo (f = t^{m/2}); |w| within dw of |w_m|
  const double T1 = std::abs(t.t1) + 2.0 * std::abs(t.t2) * span;
  const double f1 = pressure_.shapeSlope(t_lo), f2 = std::abs(pressure_.shapeCurvature(t_lo));
  const double B1 = c_ * f1 * T1, B2 = c_ * (f2 * T1 * T1 + 2.0 * f1 * std::abs(t.t2));  // |b'|, |b''|
  const double W_lo = wn - dw, W_hi = wn + dw, Wd = w_dot_norm_;
  const double L = W_hi / b_lo;                                            // lambda
  const double L1 = Wd / b_lo + W_hi * B1 / (b_lo * b_lo);                 // |lambda'|
  const double L2 = Wd * Wd / (W_lo * b_lo) + 2.0 * Wd * B1 / (b_lo * b_lo) + W_hi * B2 / (b_lo * b_lo) +
                    2.0 * W_hi * B1 * B1 / (b_lo * b_lo * b_lo);           // |lambda''|
  const double P1 = Wd / W_lo, P2 = 2.0 * P1 * P1;                         // |psi'|, |psi''|
  const double A1 = L1 + L * P1, A2 = L2 + 2.0 * L1 * P1 + L * (P2 + P1 * P1);  // |f_tau|, |f_tautau|
  const double R1 = A1 * (1.0 + 0.5 * L * span);
  const double R2 = A2 + 2.0 * A1 * L + 0.5 * span * A1 * (A1 + 2.0 * L * L);
  const double lambda = wn / b_m;
  const double E = span * span * span * (R2 / 24.0 + lambda * R1 / 12.0);
  if (!(b1 * E <= kFrozenShare * tolerance_))
    return false;
  const Eigen::Vector2d e_w = w / wn, e = s.u / un;
  const double cos_d = e.dot(e_w), sin_d = e_w.x() * e.y() - e_w.y() * e.x();
  // pushed throughout: the true direction (from within the carried angle of this one's) lies within |delta| + carried +
  // R1 span^2 / 4 of the frozen drive and that within asin(dw / |w_m|) of the drive at the time, so w . e >= (|w_m| -
  // dw) cos(|delta| + g) (cos(d + g) >= cos d (1 - g^2 / 2) - |sin d| g), against the bound's largest rate B1
  const double carried = b0 > 0.0 ? s.step_error / b0 : 0.0;
  const double g = 0.25 * R1 * span * span + std::asin(dw / wn) + carried;
  const double cos_reach = cos_d * (1.0 - 0.5 * g * g) - std::abs(sin_d) * g;
  if (!(cos_reach > 0.0 && W_lo * cos_reach > B1))
    return false;
  // the relaxation (coulombSlideStill's closed form) from delta to delta_1: tan(delta_1 / 2) = tan(delta / 2) e^{-Lambda}
  const double relax = decay(lambda * span);
  const double k = sin_d / (1.0 + cos_d) * relax, k2 = k * k;
  const double c = (1.0 - k2) / (1.0 + k2), sn = 2.0 * k / (1.0 + k2);
  // The carried error (an angle step_error / b0) shrinks by the frozen flow's contraction, the largest derivative of
  // delta -> delta_1 within the angle a carried direction may have, alpha = |delta| + that angle (below a right angle):
  // e^{-Lambda} (1 + T^2) / (1 + T^2 e^{-2 Lambda}), T = tan(alpha / 2), growing with T. Beyond a right angle, none.
  const double cos_alpha = cos_d * (1.0 - 0.5 * carried * carried) - std::abs(sin_d) * carried;
  double shrink = 1.0;
  if (cos_alpha > 0.0)
  {
    const double T2 = (1.0 - cos_alpha) / (1.0 + cos_alpha);
    shrink = std::min(1.0, relax * (1.0 + T2) / (1.0 + T2 * relax * relax));
  }
  s.u = b1 * (c * e_w + sn * Eigen::Vector2d(-e_w.y(), e_w.x()));
  s.step_error = b1 * (carried * shrink + E);
  return true;
}

// Along a sliding piece from x_p: the drive, the bound and its rate at time tau after its start.
struct BristleAdvance::Along
{
  Eigen::Vector2d x, w;  // at tau = 0
  double t0, t1, t2;     // t = 1 - r^2 / a^2
};

inline BristleAdvance::Point BristleAdvance::at(const Along& p, double tau) const
{
  Point q;
  q.w = p.w + tau * w_dot_;
  const double t = p.t0 + tau * (p.t1 + tau * p.t2), dt = p.t1 + 2.0 * tau * p.t2;
  q.b = c_ * pressure_.shape(t);
  q.b_dot = c_ * pressure_.shapeSlope(t) * dt;
  return q;
}

double BristleAdvance::returnMapping(BristleState& s, const Along& p, double tau, double d, double& error,
                                     bool& slides) const
{
  // The closed-form adhering deflection over the step, scaled back onto the bound at its end where it lies beyond it
  // (backward Euler of eq. 4b, stable at any pull). One step against two half steps: the first-order method's error is
  // twice their difference, their combination 2 u_half - u_one (put back on the bound) second order.
  const auto project = [](Eigen::Vector2d& v, double b) {
    const double n = v.norm();
    if (n <= b)
      return false;
    v *= b / n;
    return true;
  };
  const Eigen::Vector2d x = p.x - tau * V_r_, x_mid = x - 0.5 * d * V_r_;
  const double b_end = at(p, tau + d).b;
  const Eigen::Vector2d trial = adhere(x, s.u, d);
  Eigen::Vector2d one = trial;
  const bool slides_one = project(one, b_end);
  Eigen::Vector2d half = adhere(x, s.u, 0.5 * d);
  const bool slides_mid = project(half, at(p, tau + 0.5 * d).b);
  half = adhere(x_mid, half, 0.5 * d);
  slides = project(half, b_end);
  const double diff = (one - half).norm();
  Eigen::Vector2d next = half;
  if (slides_one && slides && !slides_mid)
    // inside the bound at the middle, beyond it at the end: the two half steps adhere through the middle as the one
    // step does, and agree whatever the bristle did (it slides from the start): no estimate, the bound's
    error = 2.0 * b_end;
  else if (slides_one && slides)
  {
    const double theta = b_end > 0.0 ? std::min(1.0, (trial - s.u).norm() / b_end) : 1.0;
    error = 2.0 * theta * diff;
    const Eigen::Vector2d combined = 2.0 * half - one;
    const double cn = combined.norm();
    if (cn > 0.0)
      next = b_end / cn * combined;
  }
  else
    error = diff;  // it re-adheres within the step: the first-order difference
  s.u = next;
  const double tn = trial.norm();
  return tn > b_end ? b_end / tn : 1.0;  // how a direction error carried into the step shrinks
}

void BristleAdvance::nearRim(const Quadratic& t, double d, const Eigen::Vector2d& w_start, double w0, double wm,
                             double w1, double& Lambda, double& error) const
{
  double s_a, s_b;
  if (!RimIntegral::crossings(t.t0, t.t1, t.t2, s_a, s_b) || !(d > kRimNear * std::min(-s_a, s_b) && d < s_b))
    return;  // far from both: Simpson's rule stands
  // |w| as the quadratic through its three values, w0 + a1 s + a2 s^2, against 1 / f in closed form
  const double a2 = 2.0 * (w0 - 2.0 * wm + w1) / (d * d), a1 = (w1 - w0) / d - a2 * d;
  const RimIntegral integral(m_, t.t0, t.t1, t.t2, s_a, s_b, d);
  Lambda = integral(w0, a1, a2) / c_;
  // Its error: the quadratic's (driveNormThird)
  const double third = driveNormThird(w_start, w_dot_, w_dot_norm_, d, w0, w1);
  error = third / 12.0 * d * d * std::min(integral(0.0, 1.0, 0.0), integral(d, -1.0, 0.0)) / c_;
}

bool BristleAdvance::exponentialStep(const Along& p, const Point& q0, const Point& q1, double w0, double w1,
                                     const Eigen::Vector2d& e0, double tau, double d, bool first_try,
                                     Exponential& out) const
{
  // In the drive's frame, delta = theta - arg w obeys delta' = -lambda sin delta - omega with lambda = |w| / b and
  // omega = (w x w') / |w|^2 the drive's turn; T = tan(delta / 2) obeys T' = -lambda T - (omega / 2) (1 + T^2), so that
  // T(d) = e^{-Lambda} T0 - (1 - e^{-Lambda}) <g>, g = omega (1 + T^2) / (2 lambda) averaged with the positive kernel
  // lambda e^{-(Lambda(d) - Lambda(s))} / (1 - e^{-Lambda}), Lambda the integral of lambda (Simpson's rule; near a rim
  // crossing nearRim). The step takes g at the end, T1 = e^{-Lambda} T0 - (1 - e^{-Lambda}) g(T1): a quadratic; on the
  // slow manifold that is the lag, delta ~ -omega / lambda. Its error is 2 b |dT| (|d theta| <= 2 |dT|), dT bounded
  // below, plus T0's decay's error from Lambda's.
  const Point qm = at(p, tau + 0.5 * d);
  const double wm = qm.w.norm();
  if (!(w0 > 0.0 && wm > 0.0 && w1 > 0.0 && q1.b > 0.0 && qm.b > 0.0))
    return false;  // a drive through zero, or no bound
  const double l0 = w0 / std::max(q0.b, 1e-300), lm = wm / qm.b, l1 = w1 / q1.b;
  const double om_m = (qm.w.x() * w_dot_.y() - qm.w.y() * w_dot_.x()) / (wm * wm);
  const double om_1 = (q1.w.x() * w_dot_.y() - q1.w.y() * w_dot_.x()) / (w1 * w1);
  // the start's angle from the drive
  const Eigen::Vector2d h0 = q0.w / w0, h1 = q1.w / w1;
  const double c0 = e0.dot(h0), s0 = h0.x() * e0.y() - h0.y() * e0.x();
  const double cross = q0.w.x() * w_dot_.y() - q0.w.y() * w_dot_.x();  // w x w', the same along the piece
  double Lambda = INFINITY, Lambda_error = 0.0;
  if (std::isfinite(l0))
  {
    Lambda = d / 6.0 * (l0 + 4.0 * lm + l1);
    Lambda_error = std::abs(Lambda - d / 4.0 * (l0 + 2.0 * lm + l1));  // the trapezoid's difference
    // Near a rim crossing (t, a concave quadratic, not positive at d / kRimNear before or after the step's start, so a
    // crossing lies within that), nearRim.
    const Quadratic t{ p.t0 + tau * (p.t1 + tau * p.t2), p.t1 + 2.0 * tau * p.t2, p.t2 };  // from the step's start
    const double reach = d / kRimNear;
    if (m_ > 0 && (t.t0 + reach * (t.t1 + reach * t.t2) <= 0.0 || t.t0 - reach * (t.t1 - reach * t.t2) <= 0.0))
      nearRim(t, d, q0.w, w0, wm, w1, Lambda, Lambda_error);
  }
  const double E = decay(Lambda);
  const double T0 = c0 > -1.0 ? s0 / (1.0 + c0) : INFINITY;
  const auto solve = [&](double ratio, double& T1) {
    const double kappa = (1.0 - E) * 0.5 * ratio, c = kappa - (std::isfinite(T0) ? E * T0 : 0.0);
    const double disc = 1.0 - 4.0 * kappa * c;
    if (!(disc >= 0.0) || !std::isfinite(T0))
      return false;
    T1 = -2.0 * c / (1.0 + std::sqrt(disc));
    return true;
  };
  double T1;
  if (!(c0 > 0.0 && solve(om_1 / l1, T1) && std::abs(T1) <= 1.0))
    return false;  // no slow manifold within the step
  // Its error: T1 - T(d) = (1 - E) (<g> - g(d, T1)), where with r = omega / (2 lambda) = omega b / (2 |w|) (0 where the
  // bound vanishes) <g> - g(d, T1) = <(r - r(d)) (1 + T^2)> + r(d) (<T^2> - T1^2). Each term is at most its range over
  // the step (r's between its three values, T^2's between T0^2 and T1^2, or from 0 where T changes sign): the bound for
  // a short step, where the kernel is nearly flat. Over a long one the kernel's weight lies at the end, and
  // - r as the quadratic through its three values, |r(s) - r(d)| <= (|r'(d)| + |r''| d / 2) (d - s), where the kernel's
  //   mean of d - s is at most its mean of Lambda(d) - Lambda(s), (1 - (1 + Lambda) E) / (1 - E), over lambda's least;
  // - |T(s)| <= |T0| e^{-Lambda(s)} + G with G >= |g| over the step, and in the kernel's weights
  //   <e^{-2 Lambda(s)}> = E, <e^{-Lambda(s)}> = Lambda E / (1 - E): <T^2> <= T0^2 E + 2 |T0| G Lambda E / (1 - E) +
  //   G^2, and |<T^2> - T1^2| is at most the larger of that and T1^2.
  // (The stiff step's estimate was the midpoint's ratio alone: it missed the second term, a parked or spinning
  // bristle's error over a 10-ms message, by up to 29x.)
  const double r0 = 0.5 * cross * q0.b / (w0 * w0 * w0);
  const double rm = 0.5 * om_m / lm, r1 = 0.5 * om_1 / l1;
  const double T0s = T0 * T0, T1s = T1 * T1, T2_max = std::max(T0s, T1s);
  const double r_max = std::max({ std::abs(r0), std::abs(rm), std::abs(r1) });
  double r_term = std::max({ r0, rm, r1 }) - std::min({ r0, rm, r1 });
  double T2_term = T2_max - (T0 * T1 > 0.0 ? std::min(T0s, T1s) : 0.0);
  if (Lambda > 1.0)
  {
    const double lag = (1.0 - (1.0 + Lambda) * E) / (1.0 - E) / std::min({ l0, lm, l1 });
    r_term = std::min(r_term, (std::abs(r0 - 4.0 * rm + 3.0 * r1) + 2.0 * std::abs(r0 - 2.0 * rm + r1)) / d * lag);
    const double G = r_max * (1.0 + T2_max);
    T2_term = std::min(T2_term, std::max(T1s, T0s * E + 2.0 * std::abs(T0) * G * Lambda * E / (1.0 - E) + G * G));
  }
  const double turn = (1.0 - E) * ((1.0 + T2_max) * r_term + r_max * T2_term);
  // (Lambda's error: e^{-(Lambda - dLambda)} - e^{-Lambda} = E (e^{dLambda} - 1) <= E dLambda (1 + dLambda) to 1)
  const double decay_error = Lambda_error <= 1.0 ? E * Lambda_error * (1.0 + Lambda_error)
                                                 : decay(std::max(0.0, Lambda - Lambda_error)) - E;
  out.error = 2.0 * q1.b * (turn + std::abs(T0) * decay_error);
  const double cd = (1.0 - T1s) * (1.0 / (1.0 + T1s));  // cos delta at the end (as turned() takes it)
  out.e1 = turned(h1, T1);
  // pushed outward at the end and the middle (with first_try, at the middle along the nearer of the ends' angles)
  out.pushed = w1 * cd - q1.b_dot >= 0.0 && wm * std::min(first_try ? c0 : 1.0, cd) - qm.b_dot >= 0.0;
  out.Lambda = Lambda;
  return true;
}

/// One sliding piece of a bristle under eq. (4b) from x_start over at most span (coulombSlide), step by step.
///
/// The direction u = b e obeys b e' = (I - e e^T) w (eq. 4b with |u| = b). In the frame of the direction e0 at a
/// step's start, t = tan((theta - theta0) / 2) obeys the Riccati equation t' = A + B t - A t^2 with B = -w.e0 / b and
/// A = (e0 x w) / (2 b): t = y1 / y2 with y' = M y linear, M = (-w.e0 H + (e0 x w) S) / (2 b) (numerics::Sl2), whose
/// solution is analytic wherever w / b is (t's own poles, where the direction turns by a half turn, are not y's).
/// Where the pull |w| / b is not stiff over the step, the sixth-order Magnus step on y (numerics::magnus6) with its
/// embedded fourth-order estimate; where it is, the exponential step or the return mapping (stable at any pull), or
/// where the bound is below half the tolerance, no steps at all (|u - u_true| <= 2 b whatever the direction).
/// The sliding speed w.e - db/dtau (eq. 4b's multiplier) is watched at the nodes and the end; where it turns negative
/// the bristle re-adheres, located on the step's cubic Hermite interpolant.
class BristleAdvance::CoulombSlide
{
public:
  CoulombSlide(const BristleAdvance& a, BristleState& s, const Along& p, double span, int& steps, int max_steps,
               double* first_step)
    : a_(a)
    , s_(s)
    , p_(p)
    , span_(span)
    , steps_(steps)
    , max_steps_(max_steps)
    , first_step_(first_step)
    , turn_(p_.w.x() * a.w_dot_.y() - p_.w.y() * a.w_dot_.x())
  {
  }

  /// Slides the bristle: returns where it re-adhered (< span), or INFINITY where it slides on to the span's end.
  [[gnu::always_inline]] double run();

private:
  // a Magnus step tried: its five points (the start, the Gauss nodes, the end), the generator's coordinates there in
  // the frame of the start's direction e0, y = (y1, y2) at the end and the step's error
  struct Magnus
  {
    Point q[5];
    double P[5], Q[5];
    double y1 = 0.0, y2 = 1.0, error = 0.0;
    bool turned = false;  // by more than a right angle within the step: too long a step
  };

  // Where the steps stand along the piece (run()'s own local, which the kinds of step below advance)
  struct Walk
  {
    double tau = 0.0;  // travel from the piece's start
    double step;       // the next step's length
    // where the steps stop (the span's end or G's edge): a step that reaches it leaves the next one's length unasked
    // (the controller's roots, waited for, held about 3 % of perf's samples of Fig. 4's message at resolution 64, where
    // most sliding bristles take one step)
    double end = INFINITY;
    bool to_event = false;  // a re-adhesion was located in a step: the step to it is being taken
    // An exponential step's estimate was above the tolerance along this piece. Over a stiff step its error is the lag's
    // change across the kernel's width 1 / lambda, which a shorter step barely reduces (cut to a fifth, the retries
    // failed again and again: 514 of 691 stiff tries at resolution 64 on Fig. 4's message): later steps stay within the
    // Magnus step's reach instead.
    bool exponential_failed = false;
    // the point at the end of an accepted step is the next one's start: kept, not evaluated again
    Point known;
    double known_tau = 0.0;
    // the path's rim crossings behind and ahead of its start (where 1 / b has its pole or branch point), found at the
    // first Magnus step
    int crosses;  // -1: not yet looked for
    double cross_a = 0.0, cross_b = 0.0;
  };

  static double pushing(const Point& q, const Eigen::Vector2d& e) { return q.w.dot(e) - q.b_dot; }
  // An error carried through a step from bound b0 to b1: on the bound a deflection's error is the bound times its
  // direction's, so it scales with the bound's ratio (it grows where the bound grows: a bristle entering at the rim,
  // whose first step's error stood below its error by up to 3 % after its bound grew tenfold, when the ratio was
  // capped at 1) and with the step's contraction of the direction; never beyond two bounds (both on the bound).
  static double carried(double error, double b0, double b1, double contraction)
  {
    if (!(error > 0.0))
      return 0.0;
    return std::min(2.0 * b1, (b0 > 0.0 ? error * (b1 / b0) : error) * contraction);
  }
  // The kinds of step, each a room of run()'s loop. (Every function is inlined into coulombSlide, where the object is a
  // local the compiler takes apart: members of one that lived on beyond inlining were stored and reloaded around each
  // call out, and the message took 3-5 % longer.)
  // A bristle sliding in from the leading rim under the parabolic pressure: RimEntry's step, tried first (taken: the
  // walk advanced).
  [[gnu::always_inline]] void fromRim(Walk& walk);
  // Out of work: the remainder in one return mapping.
  [[gnu::always_inline]] double remainder(double tau);
  // Too little bound for the direction to matter: no step (true).
  [[gnu::always_inline]] bool faint(Walk& walk, const Point& q0, const Point& q1, double d);
  // Not stiff: the exponential step tried first, where the drive's turn against its pull barely changes (true: taken).
  [[gnu::always_inline]] bool relaxedFirst(Walk& walk, const Point& q0, const Point& q1, double w0, double w1,
                                           const Eigen::Vector2d& e0, double d);
  // Not stiff: the Magnus step tried (m), accepted or not by run().
  [[gnu::always_inline]] void magnus(Walk& walk, const Point& q0, const Point& q1, const Eigen::Vector2d& e0, double d,
                                     Magnus& m);
  // Stiff: the exponential step, else the return mapping (true: re-adhered at `ended`); pull: |w| / b's largest.
  [[gnu::always_inline]] bool stiff(Walk& walk, const Point& q0, const Point& q1, double w0, double w1,
                                    const Eigen::Vector2d& e0, double d, double pull, double& ended);
  // An accepted Magnus step: the re-adhesion watched along it (true: re-adhered at `ended`), else its end taken.
  [[gnu::always_inline]] bool takeMagnus(Walk& walk, const Magnus& m, const Eigen::Vector2d& e0, double d,
                                         double& ended);
  [[gnu::always_inline]] void takeExponential(Walk& walk, const Exponential& x, double b0, const Point& q1,
                                              double d);

  const BristleAdvance& a_;
  BristleState& s_;
  const Along& p_;
  const double span_;
  int& steps_;
  const int max_steps_;
  double* const first_step_;  // a neighbour's suggested first try, and where this piece leaves its own (advance())
  const double turn_;  // w x w', the drive's turn times |w|^2 (the same along the piece: w is affine in tau)
};

inline double BristleAdvance::CoulombSlide::run()
{
  Walk walk;
  // (never shorter than a rejected whole span's retry could be: a neighbour's short steps, at the rim, were else handed
  // on from bristle to bristle, down to 1e-16 of a span, and a test of random histories ran for minutes)
  walk.step = first_step_ ? std::min(span_, std::max(*first_step_, kFirstStepShare * span_)) : span_;
  walk.known = a_.at(p_, 0.0);
  walk.crosses = a_.m_ > 0 ? -1 : 0;
  if (walk.known.b > 0.0 && s_.u.squaredNorm() > 0.0 && pushing(walk.known, s_.u / s_.u.norm()) < 0.0)
    return 0.0;  // the drive pulls it back at once: it re-adheres here
  // It slides only while pushed outward, w.e - db/dtau <= |w| - db/dtau, which turns negative where the path enters G
  // (|w| <= db/dtau, the rigid law's re-adhesion: exact): it has re-adhered there at the latest, and no step passes
  // that point (a long stiff step, checked at its middle and end, passed over the re-adhesion and slid on)
  bool isolated = false;
  const double entry =
      a_.rigidReAdhesion(Piece{ p_.x, s_.u, p_.t0, p_.t1, p_.t2 }, span_, steps_ < max_steps_, isolated);
  steps_ += isolated;  // (work: counted as a step)
  if (std::isnan(entry))
    return remainder(0.0);  // the work budget spent
  walk.end = std::min(span_, entry);
  if (a_.m_ == 2 && s_.u.squaredNorm() == 0.0)
    fromRim(walk);
  while (walk.tau < walk.end)
  {
    if (steps_ >= max_steps_)
      return remainder(walk.tau);
    const double d = std::min(walk.step, walk.end - walk.tau);
    const Point q0 = walk.tau == walk.known_tau ? walk.known : a_.at(p_, walk.tau), q1 = a_.at(p_, walk.tau + d);
    if (faint(walk, q0, q1, d))
      continue;
    const double b_min = std::min(q0.b, q1.b);
    const double w0 = q0.w.norm(), w1 = q1.w.norm();
    const double pull = std::max(w0, w1) / std::max(b_min, 1e-300);
    // (a shorter step's pull is no larger: |w| is convex and the bound unimodal along a straight path; where the bound
    // vanishes at the start, as at the rim, the stiff step's own kinds)
    if (walk.exponential_failed && pull * d > kStiffPull && 0.97 * kStiffPull / pull > 0.01 * d)
    {
      walk.step = 0.97 * kStiffPull / pull;
      continue;
    }
    ++steps_;
    bool stiff_step = pull * d > kStiffPull;
    const double un = s_.u.norm();
    // (on the rim the bound, and u, vanish: the drive's direction)
    const Eigen::Vector2d e0 = un > 0.0 ? Eigen::Vector2d(s_.u / un)
                                        : (w0 > 0.0 ? Eigen::Vector2d(q0.w / w0) : Eigen::Vector2d(1.0, 0.0));
    if (!stiff_step && relaxedFirst(walk, q0, q1, w0, w1, e0, d))
      continue;
    Magnus m;
    if (!stiff_step)
    {
      magnus(walk, q0, q1, e0, d, m);
      stiff_step = m.turned && !(d > 1e-9 * span_);  // a step the Magnus step cannot take any shorter
    }
    double ended = 0.0;
    if (stiff_step)
    {
      if (stiff(walk, q0, q1, w0, w1, e0, d, pull, ended))
        return ended;
      continue;
    }
    if ((m.turned || m.error > a_.tolerance_) && d > 1e-9 * span_)
    {
      walk.step = d * (m.turned ? 0.25 : std::max(0.2, 0.9 * std::sqrt(std::sqrt(a_.tolerance_ / m.error))));
      continue;
    }
    const bool from_start = walk.tau == 0.0;
    if (takeMagnus(walk, m, e0, d, ended))
      return ended;
    if (from_start && first_step_)
      *first_step_ = walk.tau < walk.end ? walk.step : INFINITY;  // (to its end at once: the whole span next)
  }
  return walk.end < span_ ? walk.end : INFINITY;  // at G's edge it is pushed no more
}

inline void BristleAdvance::CoulombSlide::fromRim(Walk& walk)
{
  // From the rim (t = t1 s + t2 s^2, entering) up to half the way to the crossing ahead, shorter where its bound is
  // above the tolerance; where it does not apply (it re-adheres within the step, the drive turns too fast, ...), the
  // steps below from the rim as before
  if (!(std::abs(p_.t0) <= 1e-12 && p_.t1 > 0.0 && p_.t2 < 0.0))
    return;
  double d = std::min(walk.end, -0.5 * p_.t1 / p_.t2);
  for (int tries = 0; tries < 3 && steps_ < max_steps_; ++tries)
  {
    ++steps_;
    RimEntry::Result r;
    if (!RimEntry::step(a_.c_, p_.w, a_.w_dot_, p_.t0, p_.t1, p_.t2, d, r) && r.reach < 1.0 && r.reach > 0.01)
    {
      d *= 0.9 * r.reach;
      continue;
    }
    if (!r.pushed || !(std::abs(r.T) <= 1.0))
      return;
    const Point q1 = a_.at(p_, d);
    const double error = 2.0 * q1.b * r.error, w1 = q1.w.norm();
    if (error > a_.tolerance_ || !(w1 > 0.0))
    {
      d *= std::max(0.2, 0.9 * std::cbrt(a_.tolerance_ / error));
      continue;
    }
    s_.u = q1.b * turned(q1.w / w1, r.T);  // the drive's direction at d turned by delta = 2 atan(T)
    s_.step_error = carried(s_.step_error, 0.0, q1.b, 1.0) + error;
    walk.tau = d;
    walk.known = q1;
    walk.known_tau = d;
    if (walk.tau < walk.end)
      walk.step = error > 0.0 ? d * std::min(4.0, 0.9 * std::sqrt(a_.tolerance_ / error)) : 4.0 * d;
    return;
  }
}

inline double BristleAdvance::CoulombSlide::remainder(double tau)
{
  // no work left for steps: the remainder's return mapping alone, no claim beyond |u|, |u_true| <= the bound
  return a_.remainder(s_, p_.x - tau * a_.V_r_, span_ - tau, a_.at(p_, tau).b, a_.at(p_, span_).b) ? INFINITY : span_;
}

inline bool BristleAdvance::CoulombSlide::faint(Walk& walk, const Point& q0, const Point& q1, double d)
{
  // the bound along a straight path is largest at an end or at its vertex (t is a concave quadratic)
  double b_max = std::max(q0.b, q1.b);
  if (p_.t2 < 0.0)
  {
    const double vertex = -p_.t1 / (2.0 * p_.t2);
    if (vertex > walk.tau && vertex < walk.tau + d)
      b_max = std::max(b_max, a_.at(p_, vertex).b);
  }
  if (!(b_max <= 0.5 * a_.tolerance_))
    return false;
  // too little bound for any direction to matter: along the drive, the error bound 2 b
  const double wn = q1.w.norm();
  s_.u = wn > 0.0 ? Eigen::Vector2d(q1.b / wn * q1.w) : Eigen::Vector2d(s_.u.normalized() * q1.b);
  s_.step_error = 2.0 * q1.b;
  walk.tau += d;
  return true;
}

inline bool BristleAdvance::CoulombSlide::relaxedFirst(Walk& walk, const Point& q0, const Point& q1, double w0,
                                                       double w1, const Eigen::Vector2d& e0, double d)
{
  // Not stiff, but where the drive's turn against its pull, omega / lambda, changes little over the step (spin in
  // place, a slow pivot: the slow manifold's lag barely moves), the exponential step with its bounded error first:
  // a few dozen operations against the Magnus step's. (Its turn term is at most (1 - e^{-Lambda}) times the
  // range of g <= 2 |ratio| over the step: where the ends' ratios alone rule it out, it is not tried.)
  if (!(q0.b > 0.0 && q1.b > 0.0 && w0 > 0.0 && w1 > 0.0))
    return false;
  // omega / (2 lambda) = (w x w') b / (2 |w|^3), w x w' the same along the piece (w is affine in tau)
  const double decayed = 0.5 * d * (w0 / q0.b + w1 / q1.b);  // >= 1 - e^{-Lambda} to first order
  const double ratio_change = q1.b / (w1 * w1 * w1) - q0.b / (w0 * w0 * w0);
  Exponential x;
  if (!(q1.b * decayed * std::abs(turn_ * ratio_change) <= 0.5 * a_.tolerance_ &&
        a_.exponentialStep(p_, q0, q1, w0, w1, e0, walk.tau, d, true, x) && x.error <= a_.tolerance_ && x.pushed))
    return false;
  takeExponential(walk, x, q0.b, q1, d);
  return true;
}

inline void BristleAdvance::CoulombSlide::takeExponential(Walk& walk, const Exponential& x, double b0, const Point& q1,
                                                          double d)
{
  // an exponential step taken (either branch): the carried error scales with the bound and shrinks by the pull's
  // contraction (carried), its own is added, and the next step follows from its estimate
  s_.step_error = carried(s_.step_error, b0, q1.b, 1.0 / (1.0 + x.Lambda)) + x.error;
  s_.u = q1.b * x.e1;
  walk.tau += d;
  walk.known = q1;
  walk.known_tau = walk.tau;
  if (walk.tau < walk.end)
    walk.step = x.error > 0.0 ? d * std::min(4.0, 0.9 * std::sqrt(a_.tolerance_ / x.error)) : 4.0 * d;
}

inline void BristleAdvance::CoulombSlide::magnus(Walk& walk, const Point& q0, const Point& q1,
                                                 const Eigen::Vector2d& e0, double d, Magnus& m)
{
  // the generator of the direction's linear form at a point (its Riccati equation's coefficients, takeMagnus), times d
  const auto generator = [&](const Point& q, double& P, double& Q) {
    const double scale = q.b > 0.0 ? 0.5 * d / q.b : 0.0;
    P = q.w.dot(e0);
    Q = e0.x() * q.w.y() - e0.y() * q.w.x();
    return numerics::Sl2{ -P * scale, Q * scale, 0.0 };
  };
  double* const P = m.P;
  double* const Q = m.Q;
  m.q[0] = q0;
  m.q[4] = q1;
  for (int i = 0; i < 3; ++i)
    m.q[i + 1] = a_.at(p_, walk.tau + numerics::kMagnusNodes[i] * d);
  numerics::Sl2 A[5];
  for (int i = 0; i < 5; ++i)
    A[i] = generator(m.q[i], P[i], Q[i]);
  // Near a rim crossing (within a step's length of either end) 1 / b has its pole or branch point, which the nodes
  // do not see (neither in M's integral nor in the commutators): there the step is taken in the stretched time u
  // (du = ds / f, RimIntegral), in which M f = (-P H + Q S) / (2 c) is affine in s(u) and smooth. Further away, in
  // s, the estimate compares with Gauss's rule moved towards Simpson's by kappa = (d / rho)^2 / 2 of their
  // difference, rho the distance to the nearer crossing beyond the step's ends: Gauss's error over Simpson's there
  // is f^(6) d^7 / 2016000 against f^(4) d^5 / 2880, with |f^(6) / f^(4)| <= 30 / rho^2 for a simple pole about
  // (d / rho)^2 / 23 (twelvefold room). (Without a pole, the uniform law, Simpson's rule is exact: w is affine.)
  const numerics::Sl2* nodes = A + 1;
  numerics::Sl2 stretched[3];
  numerics::Sl2 omega1 = numerics::gaussIntegral(A + 1), omega1_low = omega1;
  if (walk.crosses < 0)
  {
    double behind = 0.0, ahead = 0.0;  // (not walk's own: its address would leave the registers)
    walk.crosses = RimIntegral::crossings(p_.t0, p_.t1, p_.t2, behind, ahead) ? 1 : 0;
    walk.cross_a = behind;
    walk.cross_b = ahead;
  }
  if (walk.crosses > 0)
  {
    const double s_a = walk.cross_a - walk.tau, s_b = walk.cross_b - walk.tau;  // the crossings from the step's start
    const double rho = std::min(-s_a, s_b - d);
    if (rho > d || !(d < s_b))
    {
      const numerics::Sl2 simpson = (1.0 / 6.0) * (A[0] + 4.0 * A[2] + A[4]);
      omega1_low = omega1 + (rho > d ? 0.5 * (d / rho) * (d / rho) : 1.0) * (simpson - omega1);
    }
    else
    {
      const double tau = walk.tau;  // t from the step's start:
      const Quadratic tq{ p_.t0 + tau * (p_.t1 + tau * p_.t2), p_.t1 + 2.0 * tau * p_.t2, p_.t2 };
      const RimIntegral integral(a_.m_, tq.t0, tq.t1, tq.t2, s_a, s_b, d);
      const double P_dot = a_.w_dot_.dot(e0), Q_dot = e0.x() * a_.w_dot_.y() - e0.y() * a_.w_dot_.x();
      const double scale = 0.5 * integral.stretchedLength() / a_.c_;
      double at_u[3];
      integral.stretchedNodes(numerics::kMagnusNodes[0], at_u);
      for (int i = 0; i < 3; ++i)
        stretched[i] = { -scale * (P[0] + P_dot * at_u[i]), scale * (Q[0] + Q_dot * at_u[i]), 0.0 };
      nodes = stretched;
      omega1 = numerics::gaussIntegral(stretched);
      omega1_low = (scale / 6.0) * numerics::Sl2{ -(P[0] + 4.0 * (P[0] + P_dot * at_u[1]) + P[4]),
                                                  Q[0] + 4.0 * (Q[0] + Q_dot * at_u[1]) + Q[4], 0.0 };
    }
  }
  numerics::Sl2 fourth;
  const numerics::Sl2 omega = numerics::magnus6(nodes, omega1, omega1_low, fourth);
  // the step's angle error: the exponents' difference through the angle's gradient, each coordinate's part on its
  // own (their sum can cancel where the true error's does not), the direction's angle twice y's
  double grad[3];
  numerics::expColumn2(omega, m.y1, m.y2, grad);
  m.error = 2.0 * q1.b *
            (std::abs(grad[0] * (fourth.x - omega.x)) + std::abs(grad[1] * (fourth.y - omega.y)) +
             std::abs(grad[2] * (fourth.z - omega.z)));
  m.turned = !(std::abs(m.y1) <= m.y2);
}

inline bool BristleAdvance::CoulombSlide::stiff(Walk& walk, const Point& q0, const Point& q1, double w0, double w1,
                                                const Eigen::Vector2d& e0, double d, double pull, double& ended)
{
  // stiff over this step: the exponential step (exponentialStep), its error bounded as where it is tried first
  Exponential x;
  if (a_.exponentialStep(p_, q0, q1, w0, w1, e0, walk.tau, d, false, x))
  {
    if (x.error <= a_.tolerance_ && x.pushed)
    {
      takeExponential(walk, x, q0.b, q1, d);
      return false;
    }
    if (x.pushed && d > 1e-9 * span_)
    {
      walk.exponential_failed = true;
      walk.step = d * std::max(0.2, 0.9 * std::sqrt(a_.tolerance_ / x.error));
      return false;
    }
  }
  // else (no slow manifold, a re-adhesion in the step, or a drive through zero): within the Magnus step's reach where
  // that is not far short of this step (a step stiff only for its length: a whole 10-mm update from more than a right
  // angle off the drive, past a spin pole, had taken the return mapping through a re-adhesion and come out 17 degrees
  // off, no error seen: test BristleAdvance.AWholeMessagePastASpinPoleFromBeyondARightAngle), else the return
  // mapping's step doubling, its own step control
  const double reach = 0.97 * kStiffPull / pull;
  if (reach > 0.01 * d && reach < d)
  {
    walk.step = reach;
    return false;
  }
  bool slides;
  double error = 0.0;
  const Eigen::Vector2d u0 = s_.u;
  const double shrink = a_.returnMapping(s_, p_, walk.tau, d, error, slides);
  if (error > a_.tolerance_ && d > 1e-9 * span_)
  {
    s_.u = u0;
    walk.step = d * std::max(0.2, 0.9 * std::cbrt(a_.tolerance_ / error));
    return false;
  }
  s_.step_error = s_.step_error * shrink + error;
  walk.tau += d;
  if (!slides)
  {
    ended = walk.tau;
    return true;
  }
  if (walk.tau < walk.end)
    walk.step = error > 0.0 ? d * std::min(4.0, 0.9 * std::cbrt(a_.tolerance_ / error)) : 4.0 * d;
  return false;
}

inline bool BristleAdvance::CoulombSlide::takeMagnus(Walk& walk, const Magnus& m, const Eigen::Vector2d& e0,
                                                     double d, double& ended)
{
  const Point* const q = m.q;
  const double* const P = m.P;
  const double* const Q = m.Q;
  // the direction at t = tan((theta - theta0) / 2): e0 turned by 2 atan(t)
  const auto direction = [&](double ti) { return turned(e0, ti); };
  // t over the step on its cubic Hermite interpolant (t and t' = A + B t - A t^2 at the ends; t = 0 at the start)
  const double t1 = m.y1 / m.y2;
  // the Riccati coefficients at point i: B = -P / b, A = Q / (2 b)
  const auto coefficients = [&](int i, double& A, double& B) {
    const double inv_b = q[i].b > 0.0 ? 1.0 / q[i].b : 0.0;
    B = -P[i] * inv_b;
    A = 0.5 * Q[i] * inv_b;
  };
  const auto rate = [&](int i, double ti) {
    double A, B;
    coefficients(i, A, B);
    return A + ti * (B - A * ti);
  };
  const double f0 = rate(0, 0.0) * d, f1 = rate(4, t1) * d;
  const auto cubic = [&](double x) {
    const double x2 = x * x, x3 = x2 * x;
    return (3.0 * x2 - 2.0 * x3) * t1 + (x - 2.0 * x2 + x3) * f0 + (x3 - x2) * f1;
  };
  // re-adhesion: the first of the nodes and the end (in time) where the bristle is no longer pushed outward; with e at
  // 2 atan(t) from e0, (1 + t^2) (w . e - db/dtau) = P (1 - t^2) + 2 Q t - (1 + t^2) db/dtau
  static constexpr double kAt[5] = { 0.0, numerics::kMagnusNodes[0], numerics::kMagnusNodes[1],
                                     numerics::kMagnusNodes[2], 1.0 };
  int first = -1;
  for (int i = 1; i < 5 && first < 0; ++i)
  {
    const double ti = i == 4 ? t1 : cubic(kAt[i]), t2 = ti * ti;
    if (P[i] * (1.0 - t2) + 2.0 * Q[i] * ti - (1.0 + t2) * q[i].b_dot < 0.0)
      first = i;
  }
  if (first > 0)
  {
    // between the previous point and that one, on the interpolant, by regula falsi
    const auto speed = [&](double x) { return pushing(a_.at(p_, walk.tau + x * d), direction(cubic(x))); };
    double lo = kAt[first - 1], hi = kAt[first];
    double s_lo = speed(lo), s_hi = speed(hi);
    if (s_lo < 0.0)
      lo = 0.0, s_lo = speed(0.0);
    for (int it = 0; it < 30 && hi - lo > 1e-12; ++it)
    {
      const double mid = s_lo > 0.0 && s_hi < 0.0 ? lo + (hi - lo) * s_lo / (s_lo - s_hi) : 0.5 * (lo + hi);
      const double x = std::min(std::max(mid, lo + 0.01 * (hi - lo)), hi - 0.01 * (hi - lo));
      const double sx = speed(x);
      if (sx < 0.0)
        hi = x, s_hi = sx;
      else
        lo = x, s_lo = sx;
    }
    const double x = hi;
    if (!walk.to_event && x < 0.999)
    {
      // the interpolant only locates the event: the Magnus step itself steps to it, so that the bristle's last
      // sliding state carries its error estimate (the cubic's value, third order, carries none)
      walk.to_event = true;
      walk.step = x * d;
      return false;
    }
    const double b_event = a_.at(p_, walk.tau + x * d).b;
    s_.u = b_event * direction(cubic(x));
    s_.step_error = carried(s_.step_error, q[0].b, b_event, 1.0) + m.error;
    ended = walk.tau + x * d;
    return true;
  }
  // the carried error (carried): the bound's ratio, and the pull's contraction of a direction error (d/dt of the right
  // side is B - 2 A t; the larger of its values at the ends)
  const auto slope = [&](int i, double ti) {
    double A, B;
    coefficients(i, A, B);
    return B - 2.0 * A * ti;
  };
  // (1 / (1 + x) >= e^-x: never less than the decay)
  const double growth = 1.0 / (1.0 + std::max(0.0, -d * std::max(slope(0, 0.0), slope(4, t1))));
  const Point& q0 = q[0];
  const Point& q1 = q[4];
  s_.step_error = carried(s_.step_error, q0.b, q1.b, growth) + m.error;
  s_.u = q1.b * direction(t1);
  walk.tau += d;
  walk.known = q1;
  walk.known_tau = walk.tau;
  // (the controller's exponent 1/4 rather than the estimate's 1/5: no pow in the loop)
  if (walk.tau < walk.end)
    walk.step = m.error > 0.0 ? d * std::min(5.0, 0.9 * std::sqrt(std::sqrt(a_.tolerance_ / m.error))) : 5.0 * d;
  return false;
}

double BristleAdvance::coulombSlide(BristleState& s, const Eigen::Vector2d& x_start, double span, int& steps,
                                    int max_steps, double* first_step) const
{
  const Quadratic t = tAlong(x_start);
  const Along p{ x_start, drive(x_start), t.t0, t.t1, t.t2 };
  return CoulombSlide(*this, s, p, span, steps, max_steps, first_step).run();
}

}  // namespace sphere_contact_estimator::lattice
