#include "bristle_advance.h"

// STL
#include <algorithm>
#include <cmath>

// Package
#include "sphere_contact_estimator/core/numerics/magnus_sl2.h"
#include "sphere_contact_estimator/core/numerics/polynomial_roots.h"
#include "rim_integral.h"

namespace sphere_contact_estimator::lattice
{
namespace
{
constexpr int kMaxEvents = 16;  // onsets and re-adhesions per bristle and update (more only at a tangency's rounding)
// exponentialStep: a step longer than this share of its distance to a rim crossing integrates lambda against the
// bound's shape (nearRim); up to it Simpson's rule stands, the trapezoid's difference above its error (at half the
// distance to a pole 1 / (rho - s), 0.014 against 0.0013 of the integral's 0.69)
constexpr double kRimNear = 0.5;

// Whether p(s) = sum c[i] s^i (degree n <= 4) can be positive on (0, span]: its Bernstein coefficients on [0, span]
// bound it (convex hull), so all of them <= 0 means it is not. A cheap test before the exact isolation.
bool mayBePositive(const double* c, int n, double span)
{
  double a[5];
  double scale = 1.0;
  for (int i = 0; i <= n; ++i, scale *= span)
    a[i] = c[i] * scale;
  for (int i = n + 1; i <= 4; ++i)
    a[i] = 0.0;
  // degree-4 Bernstein coefficients of a polynomial of degree <= 4 (C(j, i) / C(4, i))
  const double b[5] = { a[0], a[0] + 0.25 * a[1], a[0] + 0.5 * a[1] + a[2] / 6.0,
                        a[0] + 0.75 * a[1] + 0.5 * a[2] + 0.25 * a[3], a[0] + a[1] + a[2] + a[3] + a[4] };
  return *std::max_element(b + 1, b + 5) > 0.0;
}
}  // namespace

// A stretch of a path from its start x_s (tau = 0): t(tau) = 1 - |x_s - V_r tau|^2 / a^2 = t0 + t1 tau + t2 tau^2.
struct BristleAdvance::Piece
{
  Eigen::Vector2d x, u;
  double t0, t1, t2;
};

BristleAdvance::BristleAdvance(const BrushParameters& p, const ContactKinematics& kin, double tolerance)
  : pressure_(p.pressure)
  , law_(p.sliding_law)
  , m_(pressure_.squaredExponent())
  , c_(p.mu * pressure_.peakFactor() * p.F_z / (M_PI * p.a * p.a) / p.k)
  , inv_a2_(1.0 / (p.a * p.a))
  , V_r_(kin.V_r)
  , V_s_(kin.V_s)
  , w_dot_(-kin.omega_z * kin.V_r.y(), kin.omega_z * kin.V_r.x())  // d/dtau of -A_omega_z x at dx/dtau = -V_r
  , w_dot_norm_(w_dot_.norm())
  , omega_z_(kin.omega_z)
  , speed2_(kin.V_r.squaredNorm())
  , tolerance_(tolerance)
{
}

double BristleAdvance::onset(const Piece& s, double span, bool at_rim) const
{
  // g = |u|^2 - (c f)^2, f^2 = t^m: a polynomial of degree <= 4 in tau
  const Eigen::Vector2d w = drive(s.x), alpha = 0.5 * w_dot_;
  const double c2 = c_ * c_, t0 = at_rim ? 0.0 : s.t0, eps = kRounding * c2;
  if (staysInside(s.u, w, { t0, s.t1, s.t2 }, span))
    return INFINITY;
  double g[5] = { s.u.squaredNorm(), 2.0 * s.u.dot(w), w.squaredNorm() + 2.0 * s.u.dot(alpha), 2.0 * w.dot(alpha),
                  alpha.squaredNorm() };
  double b[5] = {};
  switch (m_)
  {
    case 0:
      b[0] = c2;
      break;
    case 1:
      b[0] = c2 * t0, b[1] = c2 * s.t1, b[2] = c2 * s.t2;
      break;
    default:
      b[0] = c2 * t0 * t0, b[1] = 2.0 * c2 * t0 * s.t1, b[2] = c2 * (s.t1 * s.t1 + 2.0 * t0 * s.t2);
      b[3] = 2.0 * c2 * s.t1 * s.t2, b[4] = c2 * s.t2 * s.t2;
  }
  for (int i = 0; i < 5; ++i)
    g[i] -= b[i];
  // At the start: on the bound (entering at a rim where it vanishes, re-adhered, or rounding) and moving out of it, it
  // slides at once. Moving in, the leading terms that are only rounding are set to zero: a re-adhesion is a tangency
  // (|u| and the bound grow alike there), which rounding would otherwise turn into a spurious onset just after it.
  if (g[0] > eps)
    return 0.0;
  if (g[0] >= -eps)
  {
    g[0] = 0.0;
    for (int i = 1; i < 5; ++i)
    {
      const double scale = 1e-12 * (std::abs(g[i]) + std::abs(b[i]) + 1e-300);
      if (g[i] > scale)
        return 0.0;
      if (g[i] < -scale)
        break;
      g[i] = 0.0;
    }
  }
  if (!mayBePositive(g, 4, span))
    return INFINITY;
  double root;
  return numerics::signChanges(g, 4, 0.0, span, &root, 1) == 1 ? root : INFINITY;
}

double BristleAdvance::rigidReAdhesion(const Piece& s, double span) const
{
  // G: d(c f)/dtau >= |w|, with f = t^{m/2}; t' = t1 + 2 t2 tau >= 0 (the bound grows) up to tau* = -t1 / (2 t2)
  if (m_ == 0 || speed2_ == 0.0)
    return INFINITY;  // the bound does not change along the path: G is only where w = 0
  const double end = std::min(span, -s.t1 / (2.0 * s.t2));
  if (!(end >= 0.0))
    return INFINITY;
  const Eigen::Vector2d w = drive(s.x);
  // Ruled out cheaply first (spinning in place the bound barely changes along the path): over [0, end] t grows and t'
  // falls, so the bound's rate c f'(t) t' is at most c f'(t0) t1 (f' never grows with t), and the drive is at least
  // |w| - |w'| end; where twice the one stays below the other, G is not reached.
  if (s.t0 > 0.0 && 2.0 * c_ * pressure_.shapeSlope(s.t0) * s.t1 < w.norm() - w_dot_norm_ * end)
    return INFINITY;
  const double w2[3] = { w.squaredNorm(), 2.0 * w.dot(w_dot_), w_dot_.squaredNorm() };
  const double c2 = c_ * c_;
  const double td2[3] = { s.t1 * s.t1, 4.0 * s.t1 * s.t2, 4.0 * s.t2 * s.t2 };  // t'^2
  double P[5] = {};
  int n;
  if (m_ == 2)
  {
    // c^2 t'^2 - |w|^2
    for (int i = 0; i < 3; ++i)
      P[i] = c2 * td2[i] - w2[i];
    n = 2;
  }
  else
  {
    // (c t' / (2 sqrt t))^2 >= |w|^2  <=>  c^2 t'^2 - 4 t |w|^2 >= 0
    const double t[3] = { s.t0, s.t1, s.t2 };
    for (int i = 0; i < 3; ++i)
      P[i] = c2 * td2[i];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        P[i + j] -= 4.0 * t[i] * w2[j];
    n = 4;
  }
  if (P[0] >= 0.0)
    return 0.0;
  if (end == 0.0 || !mayBePositive(P, n, end))
    return INFINITY;
  double root;
  return numerics::signChanges(P, n, 0.0, end, &root, 1) == 1 ? root : INFINITY;
}

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
  const double k = sin_d / (1.0 + cos_d) * std::exp(-wn * span / b), k2 = k * k;
  const double c = (1.0 - k2) / (1.0 + k2), sn = 2.0 * k / (1.0 + k2);
  s.u = b * (c * e_w + sn * Eigen::Vector2d(-e_w.y(), e_w.x()));
  return INFINITY;
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
  project(half, at(p, tau + 0.5 * d).b);
  half = adhere(x_mid, half, 0.5 * d);
  slides = project(half, b_end);
  const double diff = (one - half).norm();
  Eigen::Vector2d next = half;
  if (slides_one && slides)
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

void BristleAdvance::nearRim(const Quadratic& t, double d, const Eigen::Vector2d& w_start, double cross, double w0,
                             double wm, double w1, double& Lambda, double& error) const
{
  double s_a, s_b;
  if (!RimIntegral::crossings(t.t0, t.t1, t.t2, s_a, s_b) || !(d > kRimNear * std::min(-s_a, s_b) && d < s_b))
    return;  // far from both: Simpson's rule stands
  // |w| as the quadratic through its three values, w0 + a1 s + a2 s^2, against 1 / f in closed form
  const double a2 = 2.0 * (w0 - 2.0 * wm + w1) / (d * d), a1 = (w1 - w0) / d - a2 * d;
  const RimIntegral integral(m_, t.t0, t.t1, t.t2, s_a, s_b, d);
  Lambda = integral(w0, a1, a2) / c_;
  // Its error: the quadratic's, |w| - W = |w|'''(xi) / 6 s (s - d / 2) (s - d), where |s (s - d / 2) (s - d)| <=
  // d^2 / 2 min(s, d - s) and, with |w|^2 = |w_s + w' s|^2, |w|''' = -3 D (w . w') / |w|^5, D = (w_s x w')^2, so that
  // ||w|'''| <= 3 D |w'| / |w|^4 at the least |w| over the step.
  const double D = cross * cross;
  const double vertex = -w_start.dot(w_dot_) / std::max(w_dot_norm_ * w_dot_norm_, 1e-300);
  const double w_least = vertex > 0.0 && vertex < d ? std::abs(cross) / w_dot_norm_ : std::min(w0, w1);
  const double third = 3.0 * D * w_dot_norm_ / (w_least * w_least * w_least * w_least);
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
      nearRim(t, d, q0.w, cross, w0, wm, w1, Lambda, Lambda_error);
  }
  const double E = std::exp(-Lambda);
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
                                                 : std::exp(-std::max(0.0, Lambda - Lambda_error)) - E;
  out.error = 2.0 * q1.b * (turn + std::abs(T0) * decay_error);
  const double n = 1.0 / (1.0 + T1s), cd = (1.0 - T1s) * n, sd = 2.0 * T1 * n;
  out.e1 = Eigen::Vector2d(cd * h1.x() - sd * h1.y(), sd * h1.x() + cd * h1.y());
  // pushed outward at the end and the middle (with first_try, at the middle along the nearer of the ends' angles)
  out.pushed = w1 * cd - q1.b_dot >= 0.0 && wm * std::min(first_try ? c0 : 1.0, cd) - qm.b_dot >= 0.0;
  out.Lambda = Lambda;
  return true;
}

double BristleAdvance::coulombSlide(BristleState& s, const Eigen::Vector2d& x_start, double span, int& steps,
                                    int max_steps) const
{
  // The direction u = b e obeys b e' = (I - e e^T) w (eq. 4b with |u| = b). In the frame of the direction e0 at a
  // step's start, t = tan((theta - theta0) / 2) obeys the Riccati equation t' = A + B t - A t^2 with B = -w.e0 / b and
  // A = (e0 x w) / (2 b): t = y1 / y2 with y' = M y linear, M = (-w.e0 H + (e0 x w) S) / (2 b) (numerics::Sl2), whose
  // solution is analytic wherever w / b is (t's own poles, where the direction turns by a half turn, are not y's).
  // Where the pull |w| / b is not stiff over the step, the sixth-order Magnus step on y (numerics::magnus6) with its
  // embedded fourth-order estimate; where it is, the exponential step or the return mapping (stable at any pull), or
  // where the bound is below half the tolerance, no steps at all (|u - u_true| <= 2 b whatever the direction).
  // The sliding speed w.e - db/dtau (eq. 4b's multiplier) is watched at the nodes and the end; where it turns negative
  // the bristle re-adheres, located on the step's cubic Hermite interpolant.
  const Quadratic t_start = tAlong(x_start);
  const Along p{ x_start, drive(x_start), t_start.t0, t_start.t1, t_start.t2 };
  const auto pushing = [](const Point& q, const Eigen::Vector2d& e) { return q.w.dot(e) - q.b_dot; };
  // the path's rim crossings behind and ahead of its start (where 1 / b has its pole or branch point), found at the
  // first Magnus step
  double cross_a = 0.0, cross_b = 0.0;
  int crosses = m_ > 0 ? -1 : 0;  // -1: not yet looked for
  double tau = 0.0;
  double step = span;
  bool to_event = false;  // a re-adhesion was located in a step: the step to it is being taken
  const double turn = p.w.x() * w_dot_.y() - p.w.y() * w_dot_.x();  // w x w', the drive's turn times |w|^2
  // the point at the end of an accepted step is the next one's start: kept, not evaluated again
  Point known = at(p, 0.0);
  double known_tau = 0.0;
  // an exponential step taken (either branch): the carried error shrinks with the bound and by the pull's contraction,
  // its own is added, and the next step follows from its estimate
  const auto takeExponential = [&](const Exponential& x, double b0, const Point& q1, double d) {
    s.step_error = s.step_error * std::min(1.0, q1.b / std::max(b0, 1e-300)) / (1.0 + x.Lambda) + x.error;
    s.u = q1.b * x.e1;
    tau += d;
    known = q1;
    known_tau = tau;
    step = x.error > 0.0 ? d * std::min(4.0, 0.9 * std::sqrt(tolerance_ / x.error)) : 4.0 * d;
  };
  if (known.b > 0.0 && s.u.squaredNorm() > 0.0 && pushing(known, s.u / s.u.norm()) < 0.0)
    return 0.0;  // the drive pulls it back at once: it re-adheres here
  // It slides only while pushed outward, w.e - db/dtau <= |w| - db/dtau, which turns negative where the path enters G
  // (|w| <= db/dtau, the rigid law's re-adhesion: exact): it has re-adhered there at the latest, and no step passes that
  // point (a long stiff step, checked at its middle and end, passed over the re-adhesion and slid on)
  const double end = std::min(span, rigidReAdhesion(Piece{ x_start, s.u, p.t0, p.t1, p.t2 }, span));
  while (tau < end)
  {
    if (steps >= max_steps)
    {
      // no work left for steps: the remainder's return mapping alone, no claim beyond |u|, |u_true| <= the bound
      const double d = span - tau;
      const Point q1 = at(p, span);
      Eigen::Vector2d trial = adhere(p.x - tau * V_r_, s.u, d);
      const double n = trial.norm();
      const bool slides = n > q1.b;
      if (slides)
        trial *= q1.b / n;
      s.u = trial;
      s.step_error = 2.0 * std::max(q1.b, at(p, tau).b);
      return slides ? INFINITY : span;
    }
    double d = std::min(step, end - tau);
    const Point q0 = tau == known_tau ? known : at(p, tau), q1 = at(p, tau + d);
    const double b_min = std::min(q0.b, q1.b);
    // the bound along a straight path is largest at an end or at its vertex (t is a concave quadratic)
    double b_max = std::max(q0.b, q1.b);
    if (p.t2 < 0.0)
    {
      const double vertex = -p.t1 / (2.0 * p.t2);
      if (vertex > tau && vertex < tau + d)
        b_max = std::max(b_max, at(p, vertex).b);
    }
    if (b_max <= 0.5 * tolerance_)
    {
      // too little bound for any direction to matter: along the drive, the error bound 2 b
      const double wn = q1.w.norm();
      s.u = wn > 0.0 ? Eigen::Vector2d(q1.b / wn * q1.w) : Eigen::Vector2d(s.u.normalized() * q1.b);
      s.step_error = 2.0 * q1.b;
      tau += d;
      continue;
    }
    const double w0 = q0.w.norm(), w1 = q1.w.norm();
    const double pull = std::max(w0, w1) / std::max(b_min, 1e-300);
    ++steps;
    bool stiff = pull * d > 3.0;
    const double un = s.u.norm();
    // (on the rim the bound, and u, vanish: the drive's direction)
    const Eigen::Vector2d e0 = un > 0.0 ? Eigen::Vector2d(s.u / un)
                                        : (w0 > 0.0 ? Eigen::Vector2d(q0.w / w0) : Eigen::Vector2d(1.0, 0.0));
    // Not stiff, but where the drive's turn against its pull, omega / lambda, changes little over the step (spin in
    // place, a slow pivot: the slow manifold's lag barely moves), the exponential step with its bounded error first:
    // a few dozen operations against the Magnus step's. (Its turn term is at most (1 - e^{-Lambda}) times the
    // range of g <= 2 |ratio| over the step: where the ends' ratios alone rule it out, it is not tried.)
    if (!stiff && q0.b > 0.0 && q1.b > 0.0 && w0 > 0.0 && w1 > 0.0)
    {
      // omega / (2 lambda) = (w x w') b / (2 |w|^3), w x w' the same along the piece (w is affine in tau)
      const double decay = 0.5 * d * (w0 / q0.b + w1 / q1.b);  // >= 1 - e^{-Lambda} to first order
      const double ratio_change = q1.b / (w1 * w1 * w1) - q0.b / (w0 * w0 * w0);
      Exponential x;
      if (q1.b * decay * std::abs(turn * ratio_change) <= 0.5 * tolerance_ &&
          exponentialStep(p, q0, q1, w0, w1, e0, tau, d, true, x) && x.error <= tolerance_ && x.pushed)
      {
        takeExponential(x, q0.b, q1, d);
        continue;
      }
    }
    // the generator of the direction's linear form at a point (its Riccati equation's coefficients, below), times d
    const auto generator = [&](const Point& q, double& P, double& Q) {
      const double scale = q.b > 0.0 ? 0.5 * d / q.b : 0.0;
      P = q.w.dot(e0);
      Q = e0.x() * q.w.y() - e0.y() * q.w.x();
      return numerics::Sl2{ -P * scale, Q * scale, 0.0 };
    };
    double P[5], Q[5], y1 = 0.0, y2 = 1.0, error = 0.0;
    Point q[5];  // the start, the Gauss nodes, the end
    bool turned = false;
    if (!stiff)
    {
      q[0] = q0;
      q[4] = q1;
      for (int i = 0; i < 3; ++i)
        q[i + 1] = at(p, tau + numerics::kMagnusNodes[i] * d);
      numerics::Sl2 A[5];
      for (int i = 0; i < 5; ++i)
        A[i] = generator(q[i], P[i], Q[i]);
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
      if (crosses < 0)
        crosses = RimIntegral::crossings(p.t0, p.t1, p.t2, cross_a, cross_b) ? 1 : 0;
      if (crosses > 0)
      {
        const double s_a = cross_a - tau, s_b = cross_b - tau;  // the crossings from the step's start
        const double rho = std::min(-s_a, s_b - d);
        if (rho > d || !(d < s_b))
        {
          const numerics::Sl2 simpson = (1.0 / 6.0) * (A[0] + 4.0 * A[2] + A[4]);
          omega1_low = omega1 + (rho > d ? 0.5 * (d / rho) * (d / rho) : 1.0) * (simpson - omega1);
        }
        else
        {
          const Quadratic tq{ p.t0 + tau * (p.t1 + tau * p.t2), p.t1 + 2.0 * tau * p.t2, p.t2 };  // from the step's start
          const RimIntegral integral(m_, tq.t0, tq.t1, tq.t2, s_a, s_b, d);
          const double P_dot = w_dot_.dot(e0), Q_dot = e0.x() * w_dot_.y() - e0.y() * w_dot_.x();
          const double scale = 0.5 * integral.stretchedLength() / c_;
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
      numerics::expColumn2(omega, y1, y2, grad);
      error = 2.0 * q1.b *
              (std::abs(grad[0] * (fourth.x - omega.x)) + std::abs(grad[1] * (fourth.y - omega.y)) +
               std::abs(grad[2] * (fourth.z - omega.z)));
      turned = !(std::abs(y1) <= y2);  // by more than a right angle within the step: too long a step
      stiff = turned && !(d > 1e-9 * span);  // a step the Magnus step cannot take any shorter: the return mapping's
    }
    if (stiff)
    {
      // stiff over this step: the exponential step (exponentialStep), its error bounded as where it is tried first
      Exponential x;
      if (exponentialStep(p, q0, q1, w0, w1, e0, tau, d, false, x))
      {
        if (x.error <= tolerance_ && x.pushed)
        {
          takeExponential(x, q0.b, q1, d);
          continue;
        }
        if (x.pushed && d > 1e-9 * span)
        {
          step = d * std::max(0.2, 0.9 * std::sqrt(tolerance_ / x.error));
          continue;
        }
      }
      // else (no slow manifold, a re-adhesion in the step, or a drive through zero): the return mapping's step
      // doubling, its own step control
      bool slides;
      const Eigen::Vector2d u0 = s.u;
      const double shrink = returnMapping(s, p, tau, d, error, slides);
      if (error > tolerance_ && d > 1e-9 * span)
      {
        s.u = u0;
        step = d * std::max(0.2, 0.9 * std::cbrt(tolerance_ / error));
        continue;
      }
      s.step_error = s.step_error * shrink + error;
      tau += d;
      if (!slides)
        return tau;
      step = error > 0.0 ? d * std::min(4.0, 0.9 * std::cbrt(tolerance_ / error)) : 4.0 * d;
      continue;
    }
    if ((turned || error > tolerance_) && d > 1e-9 * span)
    {
      step = d * (turned ? 0.25 : std::max(0.2, 0.9 * std::sqrt(std::sqrt(tolerance_ / error))));
      continue;
    }
    // the direction at t = tan((theta - theta0) / 2): e0 turned by 2 atan(t)
    const auto direction = [&](double ti) {
      const double n = 1.0 / (1.0 + ti * ti);
      const double c = (1.0 - ti * ti) * n, sn = 2.0 * ti * n;
      return Eigen::Vector2d(c * e0.x() - sn * e0.y(), sn * e0.x() + c * e0.y());
    };
    // t over the step on its cubic Hermite interpolant (t and t' = A + B t - A t^2 at the ends; t = 0 at the start)
    const double t1 = y1 / y2;
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
      const auto speed = [&](double x) { return pushing(at(p, tau + x * d), direction(cubic(x))); };
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
      if (!to_event && x < 0.999)
      {
        // the interpolant only locates the event: the Magnus step itself steps to it, so that the bristle's last
        // sliding state carries its error estimate (the cubic's value, third order, carries none)
        to_event = true;
        step = x * d;
        continue;
      }
      s.u = at(p, tau + x * d).b * direction(cubic(x));
      s.step_error += error;
      return tau + x * d;
    }
    // the carried error: the bound's ratio, and the pull's contraction of a direction error (d/dt of the right side is
    // B - 2 A t; the larger of its values at the ends)
    const auto slope = [&](int i, double ti) {
      double A, B;
      coefficients(i, A, B);
      return B - 2.0 * A * ti;
    };
    // (1 / (1 + x) >= e^-x: never less than the decay)
    const double growth = 1.0 / (1.0 + std::max(0.0, -d * std::max(slope(0, 0.0), slope(4, t1))));
    s.step_error = s.step_error * (q0.b > 0.0 ? std::min(1.0, q1.b / q0.b) : 1.0) * growth + error;
    s.u = q1.b * direction(t1);
    tau += d;
    known = q1;
    known_tau = tau;
    // (the controller's exponent 1/4 rather than the estimate's 1/5: no pow in the loop)
    step = error > 0.0 ? d * std::min(5.0, 0.9 * std::sqrt(std::sqrt(tolerance_ / error))) : 5.0 * d;
  }
  return end < span ? end : INFINITY;  // at G's edge it is pushed no more
}

int BristleAdvance::advance(BristleState& s, const Eigen::Vector2d& x_start, double duration, bool at_rim,
                            int max_steps) const
{
  int steps = 0;
  if (!(c_ > 0.0))
  {
    s.u.setZero();  // no load or no friction: no bristle holds a deflection
    s.sliding = false;
    s.slip_travel = INFINITY;
    return 0;
  }
  Eigen::Vector2d x = x_start;
  double left = duration;
  const double speed = std::sqrt(speed2_);
  const auto piece = [&](const Eigen::Vector2d& at, const Eigen::Vector2d& u) {
    const Quadratic t = tAlong(at);
    return Piece{ at, u, t.t0, t.t1, t.t2 };
  };
  bool rim = at_rim;
  for (int event = 0; left > 0.0; ++event)
  {
    const bool final_event = event >= kMaxEvents;
    if (final_event && event == kMaxEvents)
      s.step_error += 2.0 * c_;  // events it did not follow: no claim beyond |u|, |u_true| <= the bound
    if (!s.sliding)
    {
      const Piece p = piece(x, s.u);
      const double on = final_event ? INFINITY : onset(p, left, rim);
      rim = false;
      if (!(on < left))
      {
        s.u = adhere(x, s.u, left);
        return steps;
      }
      const Eigen::Vector2d u_on = adhere(x, s.u, on);
      x -= on * V_r_;
      left -= on;
      s.sliding = true;
      s.slip_travel = 0.0;
      s.jump.setZero();
      if (law_ == SlidingLaw::Rigid)
      {
        // the deflection jumps from the adhering direction onto the sliding field
        const Eigen::Vector2d w = drive(x);
        const double b = bound(x), wn = w.norm();
        s.u = wn > 0.0 ? Eigen::Vector2d(b / wn * w) : u_on;
        s.jump = u_on - s.u;
      }
      else
        s.u = u_on;
      continue;
    }
    if (law_ == SlidingLaw::Rigid)
    {
      const double re = final_event ? INFINITY : rigidReAdhesion(piece(x, s.u), left);
      const double run = std::min(re, left);
      x -= run * V_r_;
      left -= run;
      const Eigen::Vector2d w = drive(x);
      const double b = bound(x), wn = w.norm();
      if (wn > 0.0)
        s.u = b / wn * w;
      else if (s.u.squaredNorm() > 0.0)
        s.u *= b / s.u.norm();
      if (re < INFINITY && re <= run)
      {
        s.sliding = false;
        s.slip_travel = INFINITY;
      }
      else
        s.slip_travel += speed * run;
      continue;
    }
    // eq. (4b)
    const double re = speed2_ == 0.0 ? coulombSlideStill(s, x, left)
                                     : coulombSlide(s, x, left, steps, final_event ? steps + 1 : max_steps);
    const double run = std::min(re, left);
    x -= run * V_r_;
    left -= run;
    s.slip_travel += speed * run;
    if (re < INFINITY)
    {
      s.sliding = false;  // it adheres from here (without rolling: pulled back at once)
      s.slip_travel = INFINITY;
    }
  }
  return steps;
}

}  // namespace sphere_contact_estimator::lattice
