#include "sphere_contact_estimator/core/brush/brush_transient.h"

// The transient model's lattice stepped substep by substep (TransientStepping::Substeps), and with tilt bristle by
// bristle along their arcs (advanceArcs): each bristle's path within half a spacing per substep, the drive held over
// each, eq. (1)'s turn coupling (A_psi_dot u) in closed form.

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/numerics/quadrature_rules.h"

// The brush library's private rooms
#include "friction_cap.h"
#include "plane_rotation.h"

namespace sphere_contact_estimator
{
namespace
{
constexpr double kMaxAngle = 0.1;  // rad per substep, for every rotation

// -V_s - A_omega_z x: the drive of the bristle ODE and the rigid sliding direction (time domain).
Eigen::Vector2d drive(const ContactKinematics& k, const Eigen::Vector2d& x)
{
  return { -k.V_s.x() + k.omega_z * x.y(), -k.V_s.y() - k.omega_z * x.x() };
}

// Where a sliding bristle moving from x0 to x1 in a substep first enters G, the region where it re-adheres, as a
// share s of the substep in [0, 1]; -1 if it does not. In G the bound mu q_z / k grows along the motion faster than
// the drive w would grow an adhering |u| from the bound (the sliding direction being w / |w|, docs/conventions.md):
// L >= |w| with L = d(mu q_z / k)/dt = -2 x . V_r d(mu q_z / k)/d(r^2) (the roots move at -V_r + omega_gamma e_z x x,
// so the turn adds nothing to d(r^2)/dt, and the turn coupling only rotates u). Over the substep w is affine in s
// and L is taken linear (exact for the parabolic pressure), so L >= 0 and L^2 - |w|^2 >= 0, a quadratic, give the
// entry in closed form. Testing the ends alone, or the adhering step against the bound, missed G where a path
// passes it within a substep, beside a spin pole where the sliding direction turns: whole streaks of re-adhered
// bristles then slid instead, an error that did not fall with the resolution (the example point of issue 11).
double reAdhesionEntry(const ContactKinematics& k, const FrictionCap& cap, const Eigen::Vector2d& x0,
                       const Eigen::Vector2d& x1)
{
  const auto growth = [&](const Eigen::Vector2d& x) { return -2.0 * x.dot(k.V_r) * cap.boundSlope(x.squaredNorm()); };
  const double L0 = growth(x0), L1 = growth(x1), dL = L1 - L0;
  if (L0 < 0.0 && L1 < 0.0)
    return -1.0;  // the bound shrinks all along (the rear half): no G
  const Eigen::Vector2d w0 = drive(k, x0), dw = drive(k, x1) - w0;
  const auto inside = [&](double s) {
    const double L = L0 + s * dL;
    return L >= 0.0 && L * L >= (w0 + s * dw).squaredNorm() * (1.0 - 1e-12);
  };
  if (inside(0.0))
    return 0.0;
  // the first s where either condition starts to hold: a root of L or of the quadratic
  const double q2 = dL * dL - dw.squaredNorm(), q1 = 2.0 * (L0 * dL - w0.dot(dw)), q0 = L0 * L0 - w0.squaredNorm();
  double candidates[3];
  int n = 0;
  if (dL != 0.0)
    candidates[n++] = -L0 / dL;
  if (q2 != 0.0)
  {
    const double disc = q1 * q1 - 4.0 * q2 * q0;
    if (disc >= 0.0)
    {
      // the roots without cancellation
      const double r = -0.5 * (q1 + std::copysign(std::sqrt(disc), q1));
      if (r != 0.0)
        candidates[n++] = q0 / r;
      candidates[n++] = r / q2;
    }
  }
  else if (q1 != 0.0)
    candidates[n++] = -q0 / q1;
  std::sort(candidates, candidates + n);
  for (int i = 0; i < n; ++i)
    if (candidates[i] > 0.0 && candidates[i] <= 1.0 && inside(candidates[i]))
      return candidates[i];
  return -1.0;
}
}  // namespace

int BrushTransient::substeps(const ContactKinematics& kin, double dt) const { return substepsAt(kin, dt, h_); }

int BrushTransient::substepsAt(const ContactKinematics& kin, double dt, double h) const
{
  // each bristle's path within half a lattice spacing, every rotation below kMaxAngle; -1 beyond kMaxSubsteps
  const double omega_gamma = p_.tilt ? kin.omegaGamma() : 0.0;
  double travel = (kin.V_r.norm() + std::abs(omega_gamma) * (p_.a + h)) * dt;
  // Under eq. (4b) the step is also one of time: the tips' motion (the drive, V_s + A_omega x) is resolved as the
  // roots' (at standstill with spin it is the only motion, and one step per message left a first-order error at the
  // bound's scale)
  if (p_.sliding_law == SlidingLaw::Coulomb)
    travel = std::max(travel, (kin.V_s.norm() + std::abs(kin.omega_z) * (p_.a + h)) * dt);
  double angle = std::abs(omega_gamma) * dt;
  if (p_.tilt)
    angle = std::max(angle, std::abs(kin.psi_dot) * dt);
  const double wanted = std::ceil(std::max({ 1.0, travel / (0.5 * h), angle / kMaxAngle }));
  return wanted <= kMaxSubsteps ? static_cast<int>(wanted) : -1;
}

struct BrushTransient::Coupling
{
  // du/dt = w - [A_psi_dot u] over a time t with the drive w held: R(spin t) u + Int_0^t R(spin tau) dtau w. Every
  // bristle inside throughout a substep takes it over the substep, a sliding one over its halves too: their cosines and
  // sines once per substep (they were a sixth of a tilted message's instructions), the same numbers as before.
  Coupling(double spin, double dt)
    : spin(spin), full(dt), R_full(rotation(spin * dt)), S_full(rotationIntegral(spin, dt))
    , R_half(rotation(spin * (0.5 * dt))), S_half(rotationIntegral(spin, 0.5 * dt))
  {
  }
  Eigen::Vector2d operator()(const Eigen::Vector2d& u, const Eigen::Vector2d& w, double t) const
  {
    if (spin == 0.0)
      return u + t * w;
    if (t == full)
      return R_full * u + S_full * w;
    if (t == 0.5 * full)
      return R_half * u + S_half * w;
    return rotation(spin * t) * u + rotationIntegral(spin, t) * w;
  }
  double spin, full;
  Eigen::Matrix2d R_full, S_full, R_half, S_half;
};

void BrushTransient::substep(const ContactKinematics& kin, double dt)
{
  // Rigid motion of the bristle roots over dt (eq. 31): dx/dt = -V_r - A_omega_gamma x with
  // A_omega_gamma = -chi_gamma A_omega_z (after eq. 31), i.e. the roots turn with the sphere at rate
  // +omega_gamma. Exactly: x' = R(omega_gamma dt) x - Int_0^dt R(omega_gamma tau) dtau V_r.
  const double rate = p_.tilt ? kin.omegaGamma() : 0.0;
  V_r_ = kin.V_r;
  omega_gamma_ = rate;
  const Eigen::Matrix2d Q = rotation(rate * dt);
  const Eigen::Matrix2d R_old = R_;
  const Eigen::Vector2d o_old = o_;
  R_ = Q * R_;
  o_ = Q * o_ - rotationIntegral(rate, dt) * kin.V_r;
  suspect_centre_ = Q * suspect_centre_ - rotationIntegral(rate, dt) * kin.V_r;
  const Coupling coupling(p_.tilt ? -kin.psi_dot : 0.0, dt);
  const FrictionCap cap(p_);
  for (int j = 0; j < w_; ++j)
    for (int i = 0; i < w_; ++i)
    {
      const Eigen::Vector2d l((i - c0_) * h_, (j - c0_) * h_);
      substepBristle(kin, cap, coupling, index(i, j), o_old + R_old * l, o_ + R_ * l, dt);
    }
  recentre();
}

void BrushTransient::substepBristle(const ContactKinematics& kin, const FrictionCap& cap, const Coupling& coupling,
                                    std::size_t p, const Eigen::Vector2d& x0, const Eigen::Vector2d& x1, double dt)
{
  // Bristle ODE du/dt = w(x) - [A_psi_dot u]: exact rotation at rate -psi_dot of the coupling, drive at the midpoint
  // of the time spent inside the patch.
  const double a2 = p_.a * p_.a;
  const double g1 = x1.squaredNorm() - a2;
  if (g1 >= 0.0)
  {
    leavePatch(p);
    return;
  }
  double share = 1.0;  // part of the substep spent inside
  const bool was_sliding = inside_[p] && sliding_[p];
  if (!inside_[p])
  {
    const double g0 = x0.squaredNorm() - a2;
    share = g0 > 0.0 ? -g1 / (g0 - g1) : 1.0;
    u_[p].setZero();
    step_error_[p] = 0.0;
  }
  double t = share * dt;
  Eigen::Vector2d x_start = x1 + share * (x0 - x1);
  Eigen::Vector2d& u = u_[p];
  const double travel = (x1 - x_start).norm();
  if (p_.sliding_law == SlidingLaw::Coulomb)
  {
    coulombStep(kin, cap, coupling, p, x_start, x1, t, was_sliding);
    return;
  }
  if (was_sliding)
  {
    // A sliding bristle re-adheres only where it enters G (reAdhesionEntry). Testing the adhering step against
    // the bound instead re-adhered too early where the sliding direction turns within a substep (beside a spin
    // pole, where G lies): 5 % of the bound off on whole streaks at the example point of issue 11.
    const double s_in = reAdhesionEntry(kin, cap, x_start, x1);
    if (s_in < 0.0)
    {
      cap.slide(u, x1, drive(kin, x1));
      slip_travel_[p] += travel;
      return;  // inside and sliding, as it was
    }
    x_start += s_in * (x1 - x_start);
    cap.slide(u, x_start, drive(kin, x_start));  // the capped deflection it re-adheres from
    t *= 1.0 - s_in;
  }
  const Eigen::Vector2d x_mid = 0.5 * (x_start + x1);
  const double over_start = u.norm() - p_.mu * cap.qz(x_start.squaredNorm()) / p_.k;  // <= 0 if it adhered
  u = coupling(u, drive(kin, x_mid), t);
  const Eigen::Vector2d adhering = u;
  const FrictionCap::Result r = cap.apply(u, x1, drive(kin, x1));
  if (!r.sliding)
    slip_travel_[p] = INFINITY;
  else
  {
    // onset in this substep (or after re-adhering in it): where |u| - bound crossed zero, linearly between its
    // start and end values
    const double over_end = adhering.norm() - p_.mu * r.q_z / p_.k;
    const double before = over_start < 0.0 && over_end > over_start ? -over_start / (over_end - over_start) : 0.0;
    slip_travel_[p] = (1.0 - before) * (x1 - x_start).norm();
    // at the onset |u| is the bound: the jump turns it from the adhering direction onto the sliding field
    const double n_adh = adhering.norm(), bound = p_.mu * r.q_z / p_.k;
    jump_[p] = n_adh > 0.0 ? Eigen::Vector2d(bound * adhering / n_adh - u) : Eigen::Vector2d::Zero();
  }
  inside_[p] = 1;
  sliding_[p] = r.sliding;
}

bool BrushTransient::advanceArcs(const ContactKinematics& kin, double dt, int count)
{
  // The same substeps as substep() (the roots' rigid motion of eq. 31 over each), taken bristle by bristle: the lattice's
  // pose moves over the whole update and the window is recentred on the patch's new place first, then each bristle
  // steps along its arc, x_k = Q x_(k-1) - c. An adhering bristle whose arc from a substep's end on cannot reach its
  // bound (arcStaysInside) is advanced over the rest of the update in closed form (arcMap): most bristles of a rolling
  // patch, which took every substep before.
  const double step = dt / count, rate = kin.omegaGamma();
  V_r_ = kin.V_r;
  omega_gamma_ = rate;
  const Eigen::Matrix2d Q = rotation(rate * step), R0 = R_;
  const Eigen::Vector2d c = rotationIntegral(rate, step) * kin.V_r, o0 = o_;
  for (int s = 0; s < count; ++s)
  {
    R_ = Q * R_;
    o_ = Q * o_ - c;
    suspect_centre_ = Q * suspect_centre_ - c;
  }
  const Eigen::Vector2i shift = recentre();  // bristle (i, j) now was (i, j) + shift at the start
  // the closed forms along arcs of at most a quarter turn (arcStaysInside's sagitta), each remaining span's map once
  const bool arcs = std::abs(rate) * dt <= 0.5 * boost::math::double_constants::pi;
  const auto clear = [&](std::vector<ArcMap>& maps, int substeps) {
    for (int k = 0; k <= std::min(substeps, kArcMaps); ++k)
      maps[k].ready = false;
  };
  clear(arc_maps_, count);
  const FrictionCap cap(p_);
  const double a2 = p_.a * p_.a;
  // an adhering bristle at x after k of n substeps of length h, out of reach of its bound over the rest: in closed form
  const auto adheres = [&](std::vector<ArcMap>& maps, std::size_t p, const Eigen::Vector2d& x,
                           const Eigen::Vector2d& x_end, int k, int n, double h) {
    if (!arcs || n > kArcMaps || !inside_[p] || sliding_[p] || !arcStaysInside(kin, cap, u_[p], x, x_end, (n - k) * h))
      return false;
    const ArcMap& m = arcMap(maps, kin, k, n, h);
    u_[p] = m.A * u_[p] - m.C * x + m.d;
    return true;
  };
  // The work: kBristleWork for a point outside at the end or a closed form, kPointWork for each substep, so at most
  // kPointWork a point and substep, as the lattice's loop counts. First every point that leaves the patch or adheres
  // out of reach from the start (most of a rolling patch); then the rest, which may take every substep. Each of those
  // takes every substep while the budget left pays for them all at the same share for it and every one after it; where
  // it does not, the bristle takes that share's fewer, longer substeps along its arc (still in closed form once out of
  // reach), so that a shortfall is shared among all the bristles left, not put on the last rows, and what a bristle
  // does not use goes to the ones after it. Such a bristle carries 3 bounds as its error (it and the true deflection
  // within the bound, and the rigid law's onset jump, at most one bound, in its cell), which the estimate sums with the
  // steps' errors until it leaves.
  // where bristle (i, j) starts the update (it stood at (i, j) + shift of the pose then) and ends it (position)
  const auto start = [&](int i, int j) -> Eigen::Vector2d {
    return o0 + R0 * (Eigen::Vector2d((i - c0_) * h_, (j - c0_) * h_) + h_ * shift.cast<double>());
  };
  long work = 0, visits = 0;
  std::size_t stepping = 0;
  for (int j = 0; j < w_; ++j)
    for (int i = 0; i < w_; ++i)
    {
      const std::size_t p = index(i, j);
      const Eigen::Vector2d x_end = position(i, j);
      if (x_end.squaredNorm() >= a2)
        leavePatch(p);
      else if (!adheres(arc_maps_, p, start(i, j), x_end, 0, count, step))
      {
        arc_stepping_[stepping++] = p;
        continue;
      }
      work += kBristleWork;
    }
  long pool = work_budget_ - work_ - afterStepsWork() - work;
  bool enough = true;
  const Coupling coupling(-kin.psi_dot, step);
  int level = count;  // the substeps of the coarse level whose coupling, motion and maps are kept
  Coupling coarse = coupling;
  Eigen::Matrix2d Q_level = Q;
  Eigen::Vector2d c_level = c;
  for (std::size_t n = 0; n < stepping; ++n)
  {
    const std::size_t p = arc_stepping_[n];
    const long share = pool / (static_cast<long>(stepping - n) * kPointWork);
    const int substeps = share >= count ? count : static_cast<int>(std::max(1L, share));
    const bool full = substeps == count;
    if (!full && substeps != level)
    {
      level = substeps;
      const double h = dt / level;
      coarse = Coupling(-kin.psi_dot, h);
      Q_level = rotation(rate * h);
      c_level = rotationIntegral(rate, h) * kin.V_r;
      clear(coarse_maps_, level);
    }
    const double h = full ? step : dt / substeps;
    const int i = static_cast<int>(p % w_), j = static_cast<int>(p / w_);
    const Eigen::Vector2d x_end = position(i, j);
    Eigen::Vector2d x = start(i, j);
    long used = 0;
    for (int k = 0; k < substeps; ++k)
    {
      if (k > 0 && adheres(full ? arc_maps_ : coarse_maps_, p, x, x_end, k, substeps, h))
      {
        used += kBristleWork;
        break;
      }
      const Eigen::Vector2d next =
          k + 1 == substeps ? x_end : Eigen::Vector2d(full ? Q * x - c : Q_level * x - c_level);
      substepBristle(kin, cap, full ? coupling : coarse, p, x, next, h);
      used += kPointWork;
      ++visits;
      x = next;
    }
    if (!full)
    {
      enough = false;
      if (inside_[p])
        step_error_[p] = 3.0 * p_.mu * cap.qz(x_end.squaredNorm()) / p_.k;
    }
    pool -= used;
    work += used;
  }
  work_ += work;
  // (cut short, what it would have taken: every bristle it stepped at every substep, so that auto does not read a cut
  // update as a cheap one)
  const double wanted = enough ? static_cast<double>(visits) : static_cast<double>(stepping) * count;
  arc_visit_share_ = wanted / (static_cast<double>(count) * w_ * w_);
  return enough;
}

bool BrushTransient::arcStaysInside(const ContactKinematics& kin, const FrictionCap& cap, const Eigen::Vector2d& u,
                                    const Eigen::Vector2d& x, const Eigen::Vector2d& x_end, double tau) const
{
  // The arc from x to x_end (an angle theta = |omega_gamma| tau <= pi / 2) lies within its sagitta, (L / 2) tan(theta /
  // 4) for a chord L, of the chord, on which |x| is largest at an end: r_max bounds |x| along it, and the bound
  // mu q_z / k is least there (q_z falls with r). In the coupling's frame (arcMap) |u| grows by at most the drive's
  // norm, |V_s| + |omega_z| r_max, over the time. Where that reach stays below the least bound, no onset.
  const double L = (x_end - x).norm(), theta = std::abs(kin.omegaGamma()) * tau;
  const double r_max = std::max(x.norm(), x_end.norm()) + 0.5 * L * std::tan(0.25 * theta);
  if (!(r_max < p_.a))
    return false;
  const double bound = p_.mu * cap.qz(r_max * r_max) / p_.k;
  const double reach = u.norm() + tau * (kin.V_s.norm() + std::abs(kin.omega_z) * r_max);
  return reach < (1.0 - 1e-9) * bound;
}

const BrushTransient::ArcMap& BrushTransient::arcMap(std::vector<ArcMap>& maps, const ContactKinematics& kin, int k,
                                                    int count, double step) const
{
  // An adhering bristle along its arc over tau (the docs' closed form, checked against these substeps: their difference
  // falls as their length cubed). In the frame turning with the coupling, v = R(psi_dot t) u, eq. 31's
  // du/dt = w - A_psi_dot u is dv/dt = R(psi_dot t) w(x(t)), with x(t) = R(omega_gamma t) x0 - S(omega_gamma, t) V_r,
  // w = -V_s - omega_z J x and S(alpha, t) the integral of R(alpha s) over [0, t]; integrated,
  //   u(tau) = R(-psi_dot tau) (u0 - S(psi_dot, tau) V_s - omega_z J S(psi_dot + omega_gamma, tau) x0
  //                              + omega_z J W V_r),   W = Int_0^tau R(psi_dot s) S(omega_gamma, s) ds,
  // affine in u0 and x0 with the same matrices for every bristle: u = A u0 - C x0 + d.
  ArcMap& m = maps[k];
  if (m.ready)
    return m;
  const double tau = (count - k) * step, psi_dot = kin.psi_dot, rate = kin.omegaGamma();
  const Eigen::Matrix2d J = (Eigen::Matrix2d() << 0.0, -1.0, 1.0, 0.0).finished();
  // W by Gauss-Legendre's five-point rule on panels that turn by at most half a radian (exact to rounding there)
  const numerics::GaussLegendre& rule = numerics::gaussLegendre(5);
  const int panels = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(psi_dot), std::abs(rate)) * tau / 0.5)));
  const double width = tau / panels;
  Eigen::Matrix2d W = Eigen::Matrix2d::Zero();
  for (int q = 0; q < panels; ++q)
    for (int n = 0; n < rule.m; ++n)
    {
      const double s = (q + 0.5 * (1.0 + rule.x[n])) * width;
      W += 0.5 * rule.w[n] * width * rotation(psi_dot * s) * rotationIntegral(rate, s);
    }
  m.A = rotation(-psi_dot * tau);
  m.C = kin.omega_z * m.A * J * rotationIntegral(psi_dot + rate, tau);
  m.d = m.A * (-(rotationIntegral(psi_dot, tau) * kin.V_s) + kin.omega_z * J * W * kin.V_r);
  m.ready = true;
  return m;
}

void BrushTransient::coulombStep(const ContactKinematics& kin, const FrictionCap& cap, const Coupling& coupling,
                                 std::size_t p, const Eigen::Vector2d& x_start, const Eigen::Vector2d& x1, double t,
                                 bool was_sliding)
{
  // The bristle as if it adhered over the step (eq. 1 with v_s = 0: the drive at the midpoint, the turn coupling's
  // rotation exact), then scaled back onto the bound where it would pass it: the implicit (backward Euler) step of eq.
  // (4b), the "return mapping". A sliding bristle thereby turns towards the drive by the angle its tip moves and
  // re-adheres wherever the trial falls inside the bound; u stays continuous, so no onset jumps (jump_ stays 0).
  const auto trial = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double dt) {
    return coupling(u, drive(kin, 0.5 * (a + b)), dt);
  };
  const auto bound = [&](const Eigen::Vector2d& x) { return p_.mu * cap.qz(x.squaredNorm()) / p_.k; };
  Eigen::Vector2d& u = u_[p];
  const Eigen::Vector2d u0 = u;
  const double over_start = u0.norm() - bound(x_start);  // <= 0 if it adhered
  const Eigen::Vector2d adhering = trial(u0, x_start, x1, t);
  u = adhering;
  const FrictionCap::Result r = cap.apply(u, x1, adhering);
  const double travel = (x1 - x_start).norm();
  if (!r.sliding)
    slip_travel_[p] = INFINITY;
  else if (was_sliding && over_start >= -1e-15 * bound(x_start))
    slip_travel_[p] += travel;
  else
  {
    // onset in this substep: where |u| - bound crossed zero, linearly between its start and end values
    const double over_end = adhering.norm() - p_.mu * r.q_z / p_.k;
    const double before = over_start < 0.0 && over_end > over_start ? -over_start / (over_end - over_start) : 0.0;
    slip_travel_[p] = (1.0 - before) * travel;
  }
  jump_[p].setZero();
  // Where it slides, the same over two half steps: the first-order method's error is twice their difference, and their
  // Richardson combination 2 u_half - u_one, put back on the bound, is second order. The first-order difference bounds
  // what the combination leaves; a direction error made sliding shrinks by the projection's ratio f / |trial| at each
  // later sliding step, and adhesion carries it unchanged.
  if (r.sliding)
  {
    const Eigen::Vector2d x_half = 0.5 * (x_start + x1);
    Eigen::Vector2d half = trial(u0, x_start, x_half, 0.5 * t);
    cap.apply(half, x_half, half);
    half = trial(half, x_half, x1, 0.5 * t);
    cap.apply(half, x1, half);
    const double n = adhering.norm(), b = p_.mu * r.q_z / p_.k;
    // the combination's own error is smaller than the first-order one by a further power of the step's expansion
    // parameter, the tip's motion over the bound
    const double theta = b > 0.0 ? std::min(1.0, (adhering - u0).norm() / b) : 1.0;
    step_error_[p] = step_error_[p] * (n > 0.0 ? std::min(1.0, b / n) : 1.0) + 2.0 * theta * (u - half).norm();
    const Eigen::Vector2d combined = 2.0 * half - u;
    const double c = combined.norm();
    if (c > 0.0)
      u = b / c * combined;
  }
  inside_[p] = 1;
  sliding_[p] = r.sliding;
}


}  // namespace sphere_contact_estimator
