#include "bristle_advance.h"

// STL
#include <algorithm>
#include <cmath>

// Package
#include "sphere_contact_estimator/core/numerics/polynomial_roots.h"

namespace sphere_contact_estimator::lattice
{
namespace
{
constexpr int kMaxEvents = 16;  // onsets and re-adhesions per bristle and update (more only at a tangency's rounding)

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

double BristleAdvance::onset(const Piece& s, double span, bool at_rim, bool may_isolate, bool& isolated) const
{
  isolated = false;
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
  if (!may_isolate)
    return NAN;
  double root;
  isolated = true;
  return numerics::signChanges(g, 4, 0.0, span, &root, 1) == 1 ? root : INFINITY;
}

double BristleAdvance::rigidReAdhesion(const Piece& s, double span, bool may_isolate, bool& isolated) const
{
  isolated = false;
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
  if (!may_isolate)
    return NAN;
  double root;
  isolated = true;
  return numerics::signChanges(P, n, 0.0, end, &root, 1) == 1 ? root : INFINITY;
}

bool BristleAdvance::remainder(BristleState& s, const Eigen::Vector2d& x, double span, double b_start,
                               double b_end) const
{
  Eigen::Vector2d trial = adhere(x, s.u, span);
  const double n = trial.norm();
  const bool slides = n > b_end;
  if (slides)
    trial *= b_end / n;
  s.u = trial;
  s.step_error = 2.0 * std::max(b_end, b_start);
  s.cut = true;
  return slides;
}

int BristleAdvance::advance(BristleState& s, const Eigen::Vector2d& x_start, double duration, bool at_rim,
                            int max_steps, double* first_step) const
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
    {
      s.step_error += 2.0 * c_;  // events it did not follow: no claim beyond |u|, |u_true| <= the bound
      s.cut = true;
    }
    if (!s.sliding)
    {
      const Piece p = piece(x, s.u);
      bool isolated = false;
      const double on = final_event ? NAN : onset(p, left, rim, steps < max_steps, isolated);
      steps += isolated;
      rim = false;
      if (std::isnan(on))
      {
        if (remainder(s, x, left, bound(x), bound(x - left * V_r_)))
        {
          s.sliding = true;  // its onset somewhere along the way, not located
          s.slip_travel = 0.0;
          s.jump.setZero();
        }
        return steps;
      }
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
      bool isolated = false;
      const double re = final_event ? NAN : rigidReAdhesion(piece(x, s.u), left, steps < max_steps, isolated);
      steps += isolated;
      // (not located: the work budget spent, or past kMaxEvents; on the sliding field at the end, no claim beyond the
      // bound)
      const bool located = !std::isnan(re);
      const double b_start = located ? 0.0 : bound(x);
      const double run = located ? std::min(re, left) : left;
      x -= run * V_r_;
      left -= run;
      const Eigen::Vector2d w = drive(x);
      const double b = bound(x), wn = w.norm();
      if (wn > 0.0)
        s.u = b / wn * w;
      else if (s.u.squaredNorm() > 0.0)
        s.u *= b / s.u.norm();
      if (!located)
      {
        s.slip_travel += speed * run;
        s.step_error = 2.0 * std::max(b_start, b);
        s.cut = true;
        return steps;
      }
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
    const double re = speed2_ == 0.0             ? coulombSlideStill(s, x, left)
                      : coulombSlideFrozen(s, x, left) ? INFINITY
                                                       : coulombSlide(s, x, left, steps, final_event ? steps + 1 : max_steps,
                                                                      first_step);
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
