#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_parameters.h"
#include "sphere_contact_estimator/core/brush/contact_kinematics.h"
#include "pressure_law.h"

namespace sphere_contact_estimator::lattice
{
/// What the lattice keeps of one bristle between updates.
struct BristleState
{
  Eigen::Vector2d u = Eigen::Vector2d::Zero();  ///< deflection [m]
  bool sliding = false;
  double slip_travel = 0.0;                       ///< travel since the onset of sliding [m] (infinite while adhering)
  Eigen::Vector2d jump = Eigen::Vector2d::Zero();  ///< rigid law: deflection before minus after that onset [m]
  double step_error = 0.0;                        ///< eq. (4b): bound on the deflection's error from the time steps [m]
  bool cut = false;  ///< the advance was cut short (its sliding steps past max_steps, its events past kMaxEvents)
};

/// One bristle over a whole update along its straight path (no tilt: the roots move at -V_r, eq. 31 with
/// omega_gamma = 0), its events located within the update instead of one lattice spacing per substep.
///
/// With the inputs held over the update the drive of eq. (1), w = -V_s - A_omega_z x, is affine in the time tau
/// along the path (x = x_s - V_r tau), so an adhering bristle (v_s = 0) has the closed form
///     u(tau) = u_s + w_s tau + (1/2) w' tau^2,   w' = omega_z J V_r,
/// and the bound mu q_z / k = c f(t) with f^2 = t^m, t = 1 - |x|^2 / a^2 quadratic in tau (pressure_law.h): the onset
/// of sliding, |u|^2 = (mu q_z / k)^2, is the first sign change of a quartic (numerics::signChanges, exact isolation).
/// Sliding:
/// - rigid law (Sect. 6): u = (mu q_z / k) w / |w|, no history; it re-adheres where the path enters G, where the bound
///   grows along the motion faster than |w| (d(mu q_z / k)/dtau >= |w|, a polynomial condition of degree 2 or 4):
///   exact.
/// - eq. (4b): on the bound u = b e, the direction's Riccati equation in the frame of each step's start, as the ratio of
///   a traceless linear system's solution, by the sixth-order Magnus step where the pull |w| / b is not stiff over the
///   step (near a rim crossing in the stretched time du = ds / f, RimIntegral; where the drive's turn against its pull
///   barely changes over it, the exponential step below first); where it is stiff, an exponential step in the drive's
///   frame (its error bounded at any pull; near a rim crossing the decay integrated against the bound's shape, where
///   1 / b has its pole; from the leading rim under the parabolic pressure, where the pull ~ kappa / s, the solution
///   regular there in closed form against (s / d)^kappa, RimEntry), else the trial deflection (the closed form over a step) scaled back onto the bound, the
///   implicit form of eq. (4b), against two half steps; each step's error within `tolerance`. The sliding speed
///   w.e - db/dtau is watched at the nodes (a re-adhesion located, then stepped to), and no step passes the path's
///   entry into G (|w| <= db/dtau), where the bristle has re-adhered at the latest. Without rolling (V_r = 0: parked,
///   spin in place) drive and bound are constant along the "path" and the direction relaxes towards the drive in
///   closed form, tan(delta / 2) ~ e^{-|w| tau / b}: exact, one step. Rolling far less than they change over (a parked
///   or spinning robot's noise at 1 kHz), the same with both frozen at the path's middle, its third-order error bound
///   well within the tolerance (coulombSlideFrozen): no step.
class BristleAdvance
{
public:
  /// tolerance: what each sliding step's error estimate may reach [m]
  BristleAdvance(const BrushParameters& p, const ContactKinematics& kin, double tolerance);

  /// Advances `s` from position x_start [m] over `duration` [s]; at_rim: x_start is on the patch edge (an entering
  /// bristle, u = 0 there). max_steps bounds the sliding steps it may take (the remainder in one step, its error
  /// counted). Returns the steps taken (work), and with them each event located by isolating a polynomial's root (an
  /// onset's quartic, the rigid law's re-adhesion: about a step's work; where nearly every bristle reaches its bound in
  /// an update, the first one of a transient model at 10 ms, they had been a third of its instructions, uncounted).
  ///
  /// first_step (eq. 4b; may be null): the first try of each sliding piece's steps, where a neighbour's suggests a
  /// shorter one than the whole span; it is updated to the step controller's next length after this bristle's first
  /// Magnus step from a piece's start. The lattice passes one along each row (its bristles' paths ask for about the same
  /// steps): a whole span tried first was rejected for its error in 18 % of the Magnus steps of Fig. 4's message at
  /// resolution 128, each rejected try as dear as an accepted one. Along a row, not across rows: the answers stay
  /// mirror-symmetric (a mirrored lattice visits its rows in the mirrored order). A first try only: each step's error
  /// is estimated and held to the tolerance as before.
  int advance(BristleState& s, const Eigen::Vector2d& x_start, double duration, bool at_rim, int max_steps,
              double* first_step = nullptr) const;

  /// An adhering bristle that cannot reach its bound within `duration` from x_start (staysInside): u advanced over it
  /// in closed form, true (what advance() does there, without its events' machinery); else false, u untouched.
  bool adhereThrough(Eigen::Vector2d& u, const Eigen::Vector2d& x_start, double duration) const
  {
    const Eigen::Vector2d w = drive(x_start);
    if (!staysInside(u, w, tAlong(x_start), duration))
      return false;
    u += duration * (w + 0.5 * duration * w_dot_);
    return true;
  }

  /// The bound mu q_z / k [m] at x.
  double bound(const Eigen::Vector2d& x) const { return c_ * pressure_.shape(1.0 - x.squaredNorm() * inv_a2_); }

  /// The drive -V_s - A_omega_z x [m/s] at x.
  Eigen::Vector2d drive(const Eigen::Vector2d& x) const
  {
    return { -V_s_.x() + omega_z_ * x.y(), -V_s_.y() - omega_z_ * x.x() };
  }

private:
  // A stretch of a path from its start x_s (tau = 0): t(tau) = 1 - |x_s - V_r tau|^2 / a^2 = t0 + t1 tau + t2 tau^2.
  struct Piece
  {
    Eigen::Vector2d x, u;
    double t0, t1, t2;
  };
  struct Along;  // the same for a sliding piece: position and drive at its start
  class CoulombSlide;  // eq. (4b)'s steps along one sliding piece (coulomb_slide.cpp)
  struct Quadratic;  // t along a path (tAlong)
  struct Point   // what eq. (4b) needs at a time along a sliding piece
  {
    Eigen::Vector2d w;
    double b, b_dot;
  };
  Point at(const Along& piece, double tau) const;
  // the exponential step of a sliding bristle's direction over [tau, tau + d] from e0 (coulombSlide; w0, w1 the drive's
  // norms at the ends): false where it does not apply (more than a right angle from the drive, a drive through zero).
  // Its error bounds the turn term's and the decay's at any pull; first_try (a step that is not stiff, tried before the
  // Magnus step): the push at the middle checked along the nearer of the ends' angles
  struct Exponential
  {
    Eigen::Vector2d e1;  // the direction at the end
    double error, Lambda;
    bool pushed;         // still pushed outward at the middle and the end
  };
  // Lambda, the integral of lambda = |w| / b over a step of length d, and its error, where the step reaches towards a
  // rim crossing (1 / b has its pole, or branch point, there, which Simpson's rule does not see: a stiff 10-ms step
  // ending by the rim took Lambda as 12.9 against 4.0): |w| as its quadratic through its values at the ends and the
  // middle (w0, wm, w1; w_start the drive at its start), integrated against the bound's shape in closed form, its
  // error from |w|'s third derivative (driveNormThird, rim_integral.h); elsewhere leaves Simpson's rule untouched. t: t from the step's
  // start.
  void nearRim(const Quadratic& t, double d, const Eigen::Vector2d& w_start, double w0, double wm, double w1,
               double& Lambda, double& error) const;
  bool exponentialStep(const Along& piece, const Point& q0, const Point& q1, double w0, double w1,
                       const Eigen::Vector2d& e0, double tau, double d, bool first_try, Exponential& out) const;
  // one return-mapping step (and two half steps) of a sliding bristle at tau along the piece; returns the factor a
  // carried direction error shrinks by
  double returnMapping(BristleState& s, const Along& piece, double tau, double d, double& error, bool& slides) const;
  // the first time in (0, span] where an adhering bristle reaches the bound (INFINITY if it does not); `isolated` is
  // raised where that took the polynomial's exact root isolation (work the caller counts as a step's: kStepWork), and
  // where that was needed but not `may_isolate` (the work budget spent), NAN
  double onset(const Piece& piece, double span, bool at_rim, bool may_isolate, bool& isolated) const;
  double rigidReAdhesion(const Piece& piece, double span, bool may_isolate, bool& isolated) const;
  // The rest of an update from x over span in one return mapping where its events are not located (the work budget
  // spent, or past kMaxEvents; CoulombSlide::remainder too): the adhering closed form, put back on the bound b_end at
  // the end where it lies beyond (then true: it slides there); no claim beyond the bound, |u - u_true| <= 2 max(b_start,
  // b_end), cut
  bool remainder(BristleState& s, const Eigen::Vector2d& x, double span, double b_start, double b_end) const;
  // eq. (4b)'s sliding from the piece's start over span (CoulombSlide, coulomb_slide.cpp): returns when it ended
  // (re-adhered: < span) and the steps
  double coulombSlide(BristleState& s, const Eigen::Vector2d& x_start, double span, int& steps, int max_steps,
                      double* first_step) const;
  double coulombSlideStill(BristleState& s, const Eigen::Vector2d& x, double span) const;
  // A piece that rolls far less than its drive and bound change over: coulombSlideStill at the path's middle, its error
  // bounded by how far they move; true where that is within the tolerance and the bristle slides throughout (then
  // s advanced, its error carried), else false and s untouched
  bool coulombSlideFrozen(BristleState& s, const Eigen::Vector2d& x, double span) const;
  // t = 1 - r^2 / a^2 along the path from x (r = |x - V_r tau|): t0 + t1 tau + t2 tau^2
  struct Quadratic
  {
    double t0, t1, t2;
  };
  Quadratic tAlong(const Eigen::Vector2d& x) const
  {
    return { 1.0 - x.squaredNorm() * inv_a2_, 2.0 * x.dot(V_r_) * inv_a2_, -speed2_ * inv_a2_ };
  }
  // onset()'s rounding margin on |u|^2 - (mu q_z / k)^2, over c^2
  static constexpr double kRounding = 1e-12;
  // Whether an adhering bristle with deflection u and drive w at the start surely stays inside its bound over
  // (0, span]: |u(tau)| <= |u| + |w| tau + |w'| tau^2 / 2, and the bound over the span is smallest at one of its ends
  // (t is a concave quadratic, f grows with t). Where that reach stays below it by more than the rounding margin,
  // |u|^2 - (mu q_z / k)^2 < -kRounding c^2 throughout: no onset. Most adhering bristles lie well inside their bound:
  // this spares them the onset's quartic.
  bool staysInside(const Eigen::Vector2d& u, const Eigen::Vector2d& w, const Quadratic& t, double span) const
  {
    const double reach = u.norm() + span * (w.norm() + 0.5 * span * w_dot_norm_);
    const double b = c_ * std::min(pressure_.shape(t.t0), pressure_.shape(t.t0 + span * (t.t1 + span * t.t2)));
    return reach * reach < b * b - kRounding * c_ * c_;
  }
  Eigen::Vector2d adhere(const Eigen::Vector2d& x_start, const Eigen::Vector2d& u_start, double tau) const
  {
    return u_start + tau * (drive(x_start) + 0.5 * tau * w_dot_);
  }

  PressureLaw pressure_;
  SlidingLaw law_;
  int m_;                                // f^2 = t^m
  double c_;                             // the bound at the centre, mu q_z(0) / k [m]
  double inv_a2_;
  Eigen::Vector2d V_r_, V_s_, w_dot_;    // w' = d w / d tau along a path
  double w_dot_norm_;                    // |w'|, the same along every path
  double omega_z_, speed2_;
  double tolerance_;
};

}  // namespace sphere_contact_estimator::lattice
