#include "coulomb_collocation.h"

// STL
#include <algorithm>
#include <array>
#include <cmath>

// Package
#include "sphere_contact_estimator/core/numerics/illinois.h"
#include "rigid_sliding.h"
#include "travel_map.h"

namespace sphere_contact_estimator::path
{
namespace
{
constexpr double kHalfPi = 1.5707963267948966;
// A step's work in PathIntegrals::work units of about 10 ns (50 instructions): its own arithmetic (the stages' guess,
// the estimate, the rotations; about 1 950 instructions, callgrind), each point along the path it evaluates (kPointWork:
// the travel map, the position, the drive and the bound, about 170) and each Newton iteration (kNewtonWork: about 210).
// A flat 60 a step (three points and the Newton iterations, 2 700-3 100 instructions along the recorded streams, 3.4
// points and 1.9 iterations a step) had heavy spin take up to 12 ns a unit (random robots at |phi a| 0.5-1.3, the
// steady model cut short by the work budget: 1.2 ms at 10^5 units; a stream's first message 1.03 ms): there a step
// locates re-adhesions by regula falsi along its cubic, 9 points and 3.7 iterations a step, 5 500 instructions.
constexpr long kStepWork = 40;
constexpr long kPointWork = 4;
constexpr long kNewtonWork = 4;
constexpr int kMaxSteps = 2000;      // attempted steps; beyond, the general solver takes the piece over
constexpr int kMaxNewton = 7;
constexpr double kNewtonStop = 1e-5;  // the last Newton correction on the stages' t
constexpr double kMaxTurn = 1.0;     // |tan(turn / 2)| within a step: the bristle turns by less than a right angle
constexpr double kCosMaxDriveTurn = 0.8775825618903728;  // cos(0.5): the drive turns by less between neighbours
constexpr double kTailShare = 0.05;  // of the tolerance: what the unintegrated stretches at the edges may hold
constexpr double kEdgeShare = 1e-2;  // of the tolerance: a piece that holds less is left to the general solver
// How much further in than the rim's stretch the steps start: the start's offset bound, carried at the pull, must leave
// the path's tolerance to the steps. e^-4 was taken when the pieces were first collocated (reference tolerances did
// not converge with none); 0.3 (e^-1.2) saves about one step in two pieces (the first steps are as long as steps get,
// 2 units of s) wherever the offset's carried bound stays within kStartShare of the tolerance (Collocation::carried):
// over 1320 paths across the Fig. 4 set at tolerances 1e-3 / 1e-4 / 1e-5 the work 10 / 5 / 3 % lower, the estimate
// above the error at every path, and above the tolerance at about as many paths as with e^-4 (50 / 44 / 31 against
// 49 / 54 / 36: it is the pieces' steps that meet the tolerance, not every part a path adds).
constexpr double kInset = 0.3;
constexpr double kDeepInset = 0.01831563888873418;  // e^-4: where kInset would leave the steps too little
// Between them 0.06 (e^-2.8), where that leaves the steps enough: the deep inset's first two steps (two units of s each,
// the longest) held a few per cent of their shares. Fig. 4 set: median instructions -2 % at 1e-3, -1 % at 1e-4.
constexpr double kInsetRung = 0.2;
// A step whose estimate is over its share (density * travel) is taken, up to this many shares, where the piece's earlier
// steps left that much of theirs unused, so that the piece's sum stays within the piece's share: the steps from the rim
// hold a few per cent of theirs, and the first step into the bulk was rejected at 1.5-3.5 shares in about one piece in
// two. Fig. 4 set: median instructions -2.4 % at 1e-3, -4.8 % at 1e-4 (callgrind); the estimate above the error at every
// comparison of model_accuracy --sweep (seeds 11 15 16 17 31 41 43 47).
constexpr double kMaxOver = 2.0;
// A remainder of the path up to this many times the step the controller proposes is taken whole: the steps ended
// short of the edge by a tenth of a step at about one path in four, each time one more attempt. Fig. 4 set: median
// instructions -2.5 % at 1e-3, -1.7 % at 1e-4 (with 2: -1.8 %, -1.0 %).
constexpr double kStretch = 1.5;
constexpr double kStartShare = 0.1;  // of the tolerance: what the start's offset may err the forces after it
constexpr double kRigidShare = 0.2;  // of the tolerance: the rigid part's rules (their bound is cheap to tighten)
constexpr double kDipReach = 0.5;    // above 0.4453: Radau::dip's cubic is positive where its values exceed this spread

// Radau IIA with three stages: nodes, coefficients (the last row is the quadrature's weights), and the constants of
// RADAU5's error estimate (Hairer and Wanner, Solving ODEs II, IV.8).
struct Radau
{
  double c[3], a[3][3], d[3], u1;
  double x4[4], inv4[4];  // 0, c1, c2, 1 and the reciprocals of their Lagrange denominators (the collocation cubic)
  double dip[15][4];      // the cubic's Lagrange weights at k / 16: where a dip of the sliding speed is sought
  Radau()
  {
    const double r = std::sqrt(6.0);
    c[0] = (4.0 - r) / 10.0;
    c[1] = (4.0 + r) / 10.0;
    c[2] = 1.0;
    a[0][0] = (88.0 - 7.0 * r) / 360.0;
    a[0][1] = (296.0 - 169.0 * r) / 1800.0;
    a[0][2] = (-2.0 + 3.0 * r) / 225.0;
    a[1][0] = (296.0 + 169.0 * r) / 1800.0;
    a[1][1] = (88.0 + 7.0 * r) / 360.0;
    a[1][2] = (-2.0 - 3.0 * r) / 225.0;
    a[2][0] = (16.0 - r) / 36.0;
    a[2][1] = (16.0 + r) / 36.0;
    a[2][2] = 1.0 / 9.0;
    d[0] = -(13.0 + 7.0 * r) / 3.0;
    d[1] = (-13.0 + 7.0 * r) / 3.0;
    d[2] = -1.0 / 3.0;
    u1 = 30.0 / (6.0 + std::cbrt(81.0) - std::cbrt(9.0));
    const double x[4] = { 0.0, c[0], c[1], 1.0 };
    for (int k = 0; k < 4; ++k)
    {
      x4[k] = x[k];
      double den = 1.0;
      for (int j = 0; j < 4; ++j)
        if (j != k)
          den *= x[k] - x[j];
      inv4[k] = 1.0 / den;
    }
    for (int i = 0; i < 15; ++i)
      for (int k = 0; k < 4; ++k)
        dip[i][k] = cubicWeight(k, (i + 1) / 16.0);
  }
  /// The Lagrange weight of the point x4[k] at y.
  double cubicWeight(int k, double y) const
  {
    double v = inv4[k];
    for (int j = 0; j < 4; ++j)
      if (j != k)
        v *= y - x4[j];
    return v;
  }
  /// The cubic through (x4[k], v[k]) at y.
  double cubic(const double* v, double y) const
  {
    const double d0 = y - x4[0], d1 = y - x4[1], d2 = y - x4[2], d3 = y - x4[3];
    return v[0] * inv4[0] * d1 * d2 * d3 + v[1] * inv4[1] * d0 * d2 * d3 + v[2] * inv4[2] * d0 * d1 * d3 +
           v[3] * inv4[3] * d0 * d1 * d2;
  }
};
const Radau kRadau;

/// What the collocation needs at one point of the path, in the map's variable s.
struct Point
{
  double s, tau, rest;
  double g;      // dtau/ds
  double f;      // the bound
  double slope;  // df/dtau
  double ratio;  // g / f: the law's pull per unit |w|
  cd z, w, w_hat;
  double w_abs;
};

/// The direction equation in the frame of a reference direction e_ref, in t = tan((theta - theta_ref) / 2): with the
/// law's pull W = (g / f) w e_ref* and K = g kappa, theta' = K + Im(W e^{-i (theta - theta_ref)}), which is the Riccati
/// equation t' = a + b t + c t^2 with a = (K + Im W) / 2, b = -Re W, c = (K - Im W) / 2.
struct Riccati
{
  double a, b, c;
  double rhs(double t) const { return a + t * (b + c * t); }
  double slope(double t) const { return b + 2.0 * c * t; }
  /// The slow manifold's leading term: the root of the right-hand side near 0 (the direction the pull holds the
  /// bristle in where it is strong).
  double manifold() const
  {
    const double disc = b * b - 4.0 * a * c;
    if (!(b < 0.0) || disc < 0.0)
      return 0.0;
    return 2.0 * a / (-b + std::sqrt(disc));
  }
};

// e^{i phi} from t = tan(phi / 2).
cd rotation(double t)
{
  const double k = 1.0 / (1.0 + t * t);
  return cd(k * (1.0 - t * t), k * 2.0 * t);
}

class Collocation
{
public:
  explicit Collocation(PathContext& ctx)
    : ctx_(ctx)
    , f_(ctx.field)
    , p_(ctx.path)
    , law_(ctx.field.pressure)
    , m_(law_.squaredExponent())
    , map_(m_, ctx.path.length)
    , straight_(ctx.field.omega == 0.0)
    , exit_(ctx.path.position(ctx.path.length))
    , exit_velocity_(cd(-1.0, 0.0) + timesI(ctx.field.omega, exit_))
    , f_mid_(boundAt(0.5 * ctx.path.length))
  {
  }

  bool run(const SlideStart& start, SlideEnd& end, SlideStart& resume);

private:
  Point at(double s) const
  {
    ctx_.out.work += kPointWork;
    Point n;
    n.s = s;
    double g_s;
    map_.at(s, n.tau, n.rest, n.g, g_s);
    double t;
    if (straight_)  // z = z_e - tau, 1 - r^2 = tau (L - tau): g / f is constant
    {
      n.z = cd(p_.entry.real() - n.tau, p_.entry.imag());
      t = n.tau * n.rest;
      n.ratio = m_ == 2 ? 1.0 / p_.length : 1.0;
    }
    else
    {
      // from the nearer end, both by one sincos: z = z_end + d phi_1(i omega d) v_end, 1 - r^2 = 2 |d| (x_e + |d|
      // Re(phi_2(i omega |d|) v_e)) (BristlePath::position, edgeDistanceNear; the path is symmetric about x = 0)
      const bool front = n.tau <= n.rest;
      const double d = front ? n.tau : -n.rest, x = f_.omega * d;
      cd phi1, phi2;
      if (std::abs(x) < 0.1)
      {
        const double x2 = x * x;
        // (products by the reciprocals: a division costs several multiplications, and these run at every stage)
        constexpr double k6 = 1.0 / 6.0, k12 = 1.0 / 12.0, k20 = 1.0 / 20.0, k24 = 1.0 / 24.0, k30 = 1.0 / 30.0,
                         k42 = 1.0 / 42.0, k56 = 1.0 / 56.0, k72 = 1.0 / 72.0;
        phi1 = cd(1.0 - x2 * k6 * (1.0 - x2 * k20), 0.5 * x * (1.0 - x2 * k12 * (1.0 - x2 * k30)));
        phi2 = cd(0.5 - x2 * k24 * (1.0 - x2 * k30 * (1.0 - x2 * k56)),
                  x * k6 * (1.0 - x2 * k20 * (1.0 - x2 * k42 * (1.0 - x2 * k72))));
      }
      else
      {
        double sh, ch;
        ::sincos(0.5 * x, &sh, &ch);
        phi1 = cd(2.0 * sh * ch / x, 2.0 * sh * sh / x);
        phi2 = cd(2.0 * sh * sh / (x * x), (x - 2.0 * sh * ch) / (x * x));
      }
      n.z = (front ? p_.entry : exit_) + d * phi1 * (front ? p_.velocity : exit_velocity_);
      // phi_2 at -|d| omega is the conjugate of that at |d| omega, and the exit's velocity the entry's mirrored
      const double a = std::abs(d);
      t = 2.0 * a * (p_.entry.real() + a * (front ? phi2 * p_.velocity : std::conj(phi2) * p_.velocity).real());
      if (m_ == 2)
        n.ratio = t > 0.0 ? n.tau * n.rest / (p_.length * t) : 1.0 / p_.length;
      else if (m_ == 1)
        n.ratio = t > 0.0 ? std::sqrt(n.tau * n.rest / t) : 1.0;
      else
        n.ratio = 1.0;
    }
    n.f = m_ == 0 ? 1.0 : law_.shape(t);
    n.slope = law_.shapeSlope(t) * 2.0 * n.z.real();  // dt/dtau = 2 x on any path
    n.w = f_.drive(n.z);
    n.w_abs = std::sqrt(std::norm(n.w));
    n.w_hat = n.w_abs > 0.0 ? n.w * (1.0 / n.w_abs) : cd(0.0);
    return n;
  }

  // A bound on the integral of f g e^{-W (s - s0)} ds from s0 on (m = 2): what a unit offset of the direction at s0,
  // decaying at the pull W (per unit s), errs the path's forces by. With f at most its value mid-path (its peak on a
  // straight path; on an arc near it) and g = L e^s / (1 + e^s)^2 at most min(L e^s, L / 4), in closed form.
  double carried(double s0, double W) const
  {
    const double f_peak = f_mid_, L = p_.length;
    const double s1 = -1.3862943611198906;  // ln(1/4): where L e^s meets L / 4
    if (!(W > 0.0))
      return INFINITY;
    double I = 0.0;
    if (s0 < s1)
    {
      // int_{s0}^{s1} e^{-W (s - s0)} e^s ds = e^{s0} int_0^{s1 - s0} e^{(1 - W) x} dx
      const double d = s1 - s0, k = 1.0 - W;
      I += std::exp(s0) * (std::abs(k * d) < 1e-8 ? d : std::expm1(k * d) / k);
    }
    I += 0.25 * std::exp(-W * (std::max(s1, s0) - s0)) / W;
    return f_peak * L * I;
  }

  // The bound at travel tau.
  double boundAt(double tau) const
  {
    if (m_ == 0)
      return 1.0;
    return law_.shape(straight_ ? tau * (p_.length - tau) : p_.edgeDistance(tau));
  }

  Riccati riccati(const Point& p, cd e_ref) const
  {
    const cd W = p.ratio * p.w * std::conj(e_ref);
    const double K = p.g * f_.kappa;
    return { 0.5 * (K + W.imag()), -W.real(), 0.5 * (K - W.imag()) };
  }

  // The law's sliding speed (up to the positive factor f): Re(w e*) - df/dtau, eq. (4b) with lambda >= 0.
  static double pushing(const Point& p, cd e) { return dot(p.w, e) - p.slope; }

  // The collocation's stages T over a step (T = 0 at its start, in the frame of the start's direction) from the guess:
  // Newton's method on the 3x3 system. False if it does not converge.
  bool collocate(const Riccati* R, double step, const double* guess, double* T) const;

  // A stretch of length len beside an edge where the bound vanishes (parabolic bound), the drive there w_edge: its
  // correction is bounded, not integrated. There |Delta| <= (pi / 2) sup |Kd| / W = (pi / 2) sup f |kappa - psi'| / |w|
  // (Delta = theta - arg w; the law pulls it back wherever it is larger; f <= 2 len, since t = 1 - r^2 changes by at
  // most 2 per unit travel), so the stretch holds at most that times the integral of f, <= len^2. Where `entering`, the
  // bristle must be pushed outward all along it (no re-adhesion in it). The longest stretch within the tolerance's
  // share, halving.
  bool edgeStretch(cd w_edge, bool entering, double& len, double& dmax) const
  {
    const double drift = std::abs(f_.phi) * (1.0 + std::abs(f_.omega));  // |dw/dtau| <= |phi| |dz/dtau|
    const double w_e = std::sqrt(std::norm(w_edge));
    const double budget = kTailShare * ctx_.tolerance;
    len = 0.05 * p_.length;
    for (int k = 0; k < 40; ++k, len *= 0.5)
    {
      const double w_min = w_e - drift * len;
      if (!(w_min > 0.0))
        continue;
      dmax = kHalfPi * 2.0 * len * (std::abs(f_.kappa) + drift / w_min) / w_min;
      // df/dtau = 2 x, and x moves by at most 1 + |omega| per unit travel
      const double reach = 2.0 * (p_.entry.real() + (straight_ ? 0.0 : (1.0 + std::abs(f_.omega)) * len));
      if (dmax > 0.5 || (entering && w_min * std::cos(dmax) <= reach))
        continue;
      if (dmax * len * len <= budget)
        return true;
    }
    return false;
  }

  // run()'s rooms (each inlined there):
  // from the rim (parabolic bound), the first step's start s, direction e, the stretch's error and the direction's
  // bound inside of it; false where the general solver takes the piece
  [[gnu::always_inline]] bool startInside(double& s, cd& e, double& error, double& drift) const;
  // the stages' first guess: the previous step's cubic continued (previous: its stages, or null), or the slow
  // manifold
  [[gnu::always_inline]] static void guessStages(const Riccati* R, const Riccati& R0, double step,
                                                 const double* previous, double previous_step, double* guess);
  // re-adhesion within the step (from p0, the stages P with directions E = e rotated by T): where the bristle, once
  // pushed outward (armed), is no longer (eq. 4b's lambda < 0), as a share of the step (< 0: none); armed_next at
  // its end
  [[gnu::always_inline]] double reAdhesion(const Point& p0, const Point* P, const cd* E, const double* T, cd e,
                                           double s, double step, bool armed, bool& armed_next) const;
  // A step's forces and estimate: the stress's integral over it and its moment (the quadrature's last stage), the
  // integral of f g, the law's least pull back onto the drive, the travel, the quadrature's error and the
  // direction's, and the larger of what they err the path by against the step's share of the tolerance (over)
  struct StepEstimate
  {
    cd force;
    double moment, gf, pull, travel, quad_err, dir_err, over;
  };
  [[gnu::always_inline]] StepEstimate estimate(const Point& p0, const Point* P, const cd* E, const double* T,
                                               const Riccati& R0, cd e, double step, bool referenced,
                                               bool rejected) const;

  PathContext& ctx_;
  const BristleField& f_;
  const BristlePath& p_;
  PressureLaw law_;
  int m_;
  TravelMap map_;
  bool straight_;
  cd exit_, exit_velocity_;  // the trailing edge's point and velocity
  double f_mid_;             // the bound mid-path, where it peaks
};

bool Collocation::collocate(const Riccati* R, double step, const double* guess, double* T) const
{
  double Z[3] = { guess[0], guess[1], guess[2] };
  double hA[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      hA[i][j] = step * kRadau.a[i][j];
  for (int it = 0; it < kMaxNewton; ++it)
  {
    ctx_.out.work += kNewtonWork;
    double F[3], J[3];
    for (int i = 0; i < 3; ++i)
    {
      F[i] = R[i].rhs(Z[i]);
      J[i] = R[i].slope(Z[i]);
    }
    double M[3][3], r[3];
    for (int i = 0; i < 3; ++i)
    {
      r[i] = step * (kRadau.a[i][0] * F[0] + kRadau.a[i][1] * F[1] + kRadau.a[i][2] * F[2]) - Z[i];
      for (int j = 0; j < 3; ++j)
        M[i][j] = (i == j ? 1.0 : 0.0) - hA[i][j] * J[j];
    }
    // Cramer's rule on the 3x3 system
    const double c00 = M[1][1] * M[2][2] - M[1][2] * M[2][1], c01 = M[1][2] * M[2][0] - M[1][0] * M[2][2],
                 c02 = M[1][0] * M[2][1] - M[1][1] * M[2][0];
    const double det = M[0][0] * c00 + M[0][1] * c01 + M[0][2] * c02;
    if (!(std::abs(det) > 1e-300))
      return false;
    const double k = 1.0 / det;
    const double d0 =
        k * (r[0] * c00 + M[0][1] * (M[1][2] * r[2] - r[1] * M[2][2]) + M[0][2] * (r[1] * M[2][1] - M[1][1] * r[2]));
    const double d1 =
        k * (M[0][0] * (r[1] * M[2][2] - M[1][2] * r[2]) + r[0] * c01 + M[0][2] * (M[1][0] * r[2] - r[1] * M[2][0]));
    const double d2 =
        k * (M[0][0] * (M[1][1] * r[2] - r[1] * M[2][1]) + M[0][1] * (r[1] * M[2][0] - M[1][0] * r[2]) + r[0] * c02);
    Z[0] += d0;
    Z[1] += d1;
    Z[2] += d2;
    // Newton's convergence is quadratic: what this correction leaves is of the order of its square, 1e-10 (a direction
    // error of 2e-10 rad, far below any step's share of a tolerance the solver takes; 1e-7 cost a third iteration at
    // some steps and bought nothing the sweeps could see)
    if (std::max({ std::abs(d0), std::abs(d1), std::abs(d2) }) <= kNewtonStop)
    {
      for (int i = 0; i < 3; ++i)
        T[i] = Z[i];
      return std::isfinite(T[0]) && std::isfinite(T[1]) && std::isfinite(T[2]);
    }
  }
  return false;
}

inline bool Collocation::startInside(double& s, cd& e, double& error, double& drift) const
{
  // The start on the slow manifold in the drive's frame, off by at most twice the stretch's bound on |Delta|. That
  // offset decays only at the pull (about e^-s), while the forces it errs grow as e^2s: the steps start further in by
  // kInset, where the stretch's bound (proportional to its length) is that much smaller, and resolve the rest.
  double tau0, dmax;
  if (m_ != 2 || !edgeStretch(f_.drive(p_.entry), true, tau0, dmax))
    return false;
  // kInset where the offset's bound, carried at the pull there, would err the path's forces by at most kStartShare
  // of the tolerance; otherwise e^-4 (only the cost depends on the choice: the offset's bound is carried and added
  // to the estimate either way)
  const double tol = ctx_.tolerance;
  double inset = kInset;
  s = map_.of(tau0 * inset);
  Point p = at(s);
  while (inset > kDeepInset && 2.0 * dmax * inset * carried(s, p.ratio * p.w_abs) > kStartShare * tol)
  {
    inset = std::max(kDeepInset, kInsetRung * inset);
    s = map_.of(tau0 * inset);
    p = at(s);
  }
  tau0 *= inset;
  dmax *= inset;
  if (!(p.w_abs > 0.0))
    return false;
  e = p.w_hat * rotation(riccati(p, p.w_hat).manifold());
  error += dmax * tau0 * tau0;
  drift = 2.0 * dmax;
  return true;
}

inline void Collocation::guessStages(const Riccati* R, const Riccati& R0, double step, const double* previous,
                                      double previous_step, double* guess)
{
  if (previous)
  {
    // the previous step's cubic, continued, turned into this step's frame (its end): tan((x - y) / 2) from tangents
    const double r = step / previous_step, t_end = previous[3];
    for (int i = 0; i < 3; ++i)
    {
      const double v = kRadau.cubic(previous, 1.0 + kRadau.c[i] * r);
      guess[i] = (v - t_end) / (1.0 + v * t_end);
    }
  }
  else
  {
    // the slow manifold, the start's offset from it decaying at the pull
    const double offset = -R0.manifold();
    for (int i = 0; i < 3; ++i)
      guess[i] = R[i].manifold() + offset * std::exp(std::max(R0.b, -50.0) * kRadau.c[i] * step);
  }
}

inline double Collocation::reAdhesion(const Point& p0, const Point* P, const cd* E, const double* T, cd e, double s,
                                      double step, bool armed, bool& armed_next) const
{
  double lam[4] = { pushing(p0, e), pushing(P[0], E[0]), pushing(P[1], E[1]), pushing(P[2], E[2]) };
  double xs[6] = { 0.0, kRadau.c[0], kRadau.c[1], 1.0 }, ls[6] = { lam[0], lam[1], lam[2], lam[3] };
  int count = 4;
  const double lam_min = *std::min_element(lam, lam + 4), lam_max = *std::max_element(lam, lam + 4);
  // the cubic dips below its smallest point value by at most 0.4453 times their spread (the largest sum of the
  // negative Lagrange weights on [0, 1]): where that leaves it positive, no dip is sought
  if (lam_min >= 0.0 && lam_min <= kDipReach * (lam_max - lam_min))
  {
    double lowest = 0.0, at_x = 0.0;
    for (int i = 0; i < 15; ++i)
    {
      const double v = kRadau.dip[i][0] * lam[0] + kRadau.dip[i][1] * lam[1] + kRadau.dip[i][2] * lam[2] +
                       kRadau.dip[i][3] * lam[3];
      if (v < lowest)
        lowest = v, at_x = (i + 1) / 16.0;
    }
    if (lowest < 0.0)
    {
      const double Tx[4] = { 0.0, T[0], T[1], T[2] };
      const Point probe = at(s + at_x * step);
      const double v = pushing(probe, e * rotation(kRadau.cubic(Tx, at_x)));
      int k = 0;
      while (k < count && xs[k] < at_x)
        ++k;
      for (int j = count; j > k; --j)
        xs[j] = xs[j - 1], ls[j] = ls[j - 1];
      xs[k] = at_x;
      ls[k] = v;
      ++count;
    }
  }
  // (the start is the previous step's end, judged there)
  double stop = -1.0, prev = 0.0;
  armed_next = armed;
  for (int j = 1; j < count; ++j)
  {
    if (ls[j] > 0.0)
      armed_next = true;
    else if (armed_next && ls[j] < 0.0)
    {
      // bracketed in (prev, x]: regula falsi (Illinois) on the step's cubic
      const double Tx[4] = { 0.0, T[0], T[1], T[2] };
      const auto g = [&](double y) {
        const Point at_y = at(s + y * step);
        return pushing(at_y, e * rotation(kRadau.cubic(Tx, y)));
      };
      stop = numerics::illinoisNegativeEnd(g, prev, xs[j], std::max(ls[j - 1], 0.0), ls[j], 1e-12, 60);
      break;
    }
    prev = xs[j];
  }
  return stop;
}

inline Collocation::StepEstimate Collocation::estimate(const Point& p0, const Point* P, const cd* E, const double* T,
                                                      const Riccati& R0, cd e, double step, bool referenced,
                                                      bool rejected) const
{
  const double L = p_.length, density = ctx_.tolerance / L;
  // RADAU5's estimate of the direction's local error (an embedded third-order solution, filtered through the
  // stiff part so that it stays bounded where the pull is strong); the start is t = 0 in the step's frame
  const double dz = kRadau.d[0] * T[0] + kRadau.d[1] * T[1] + kRadau.d[2] * T[2];
  double err_t = (step * R0.a + dz) / (kRadau.u1 - step * R0.b);
  // The stress f g (e - w / |w|) (or f g e) and its moment: the collocation's quadrature over the stages, the
  // quadrature components of the ODE system (order 5 like the direction's end value). Their part of RADAU5's estimate:
  // with J_Ft = dq/dt = f g e 2i at the start the only coupling, err_F = (h q0 + sum d_i Z^F_i + h J_Ft err_t) / u1.
  const auto stress = [&](const Point& p, cd dir) { return p.g * p.f * (referenced ? dir - p.w_hat : dir); };
  cd q[4];
  double qm[4], gf = 0.0;
  q[0] = stress(p0, e);
  qm[0] = cross(p0.z, q[0]);
  for (int i = 0; i < 3; ++i)
  {
    q[i + 1] = stress(P[i], E[i]);
    qm[i + 1] = cross(P[i].z, q[i + 1]);
    gf += kRadau.a[2][i] * P[i].g * P[i].f;
  }
  gf *= step;
  cd ZF[3];
  double ZM[3];
  for (int i = 0; i < 3; ++i)
  {
    ZF[i] = step * (kRadau.a[i][0] * q[1] + kRadau.a[i][1] * q[2] + kRadau.a[i][2] * q[3]);
    ZM[i] = step * (kRadau.a[i][0] * qm[1] + kRadau.a[i][1] * qm[2] + kRadau.a[i][2] * qm[3]);
  }
  const cd J_Ft = p0.g * p0.f * e * cd(0.0, 2.0);
  const cd dZF = kRadau.d[0] * ZF[0] + kRadau.d[1] * ZF[1] + kRadau.d[2] * ZF[2];
  const double dZM = kRadau.d[0] * ZM[0] + kRadau.d[1] * ZM[1] + kRadau.d[2] * ZM[2];
  double scale = 0.0;  // the step's stress
  for (int i = 0; i < 4; ++i)
    scale = std::max({ scale, std::norm(q[i]), qm[i] * qm[i] });
  scale = std::sqrt(scale) * step;
  // RADAU5's estimates are those of an embedded third-order solution; the fifth-order solution's error is smaller
  // by about the estimate's own size relative to the step's stress (or the direction's change), to the power 1/4:
  // against the same steps taken by 64 substeps, over 9e4 steps of random paths, true / modelled was at most 1.1 for
  // the stress, and for the direction where the pull is weak (W h < 1; where it is strong the raw estimate, as stiff
  // solvers use it).
  // What it must hold is checked on the totals: the paths' against the general stepper (test BrushCollocation.*) and
  // the patch's over random operating points (model_accuracy --sweep).
  double pull = INFINITY, W_max = 0.0;  // the law's pull back onto the drive, (g / f) Re(w e*), per unit s
  for (int i = 0; i < 3; ++i)
  {
    pull = std::min(pull, P[i].ratio * dot(P[i].w, E[i]));
    W_max = std::max(W_max, P[i].ratio * P[i].w_abs);
  }
  const double change = std::abs(T[2]) + 1e-12;
  const bool stiff = W_max * step >= 1.0;
  const auto quadErr = [&](double e_t) {
    const cd eF = (step * q[0] + dZF + step * J_Ft * e_t) / kRadau.u1;
    const double eM = (step * qm[0] + dZM + step * cross(p0.z, J_Ft) * e_t) / kRadau.u1;
    const double raw = std::sqrt(std::max(std::norm(eF), eM * eM));
    if (!(scale > 0.0))
      return raw;
    const double relative = raw / scale;
    return raw * std::min(1.0, std::sqrt(std::sqrt(relative)));
  };
  const auto dirErr = [&](double e_t) {
    const double v = std::abs(e_t);
    return stiff ? v : v * std::min(1.0, std::sqrt(std::sqrt(v / change)));
  };
  // A direction error (dtheta = 2 dt / (1 + t^2) <= 2 dt) errs the forces over this step and, decaying at the pull,
  // over the travel after it: its share of the tolerance covers both.
  const double travel = P[2].tau - p0.tau;
  const double after = std::min(std::max(L - P[2].tau, 0.0), pull > 0.0 ? P[1].g / pull : INFINITY);
  // the bound over the step and the travel after it (it peaks mid-path)
  // (its value mid-path is the path's constant; at the step's end it is P[2].f)
  const double tau_f = std::clamp(0.5 * L, P[2].tau, P[2].tau + after);
  const double f_after = tau_f == P[2].tau ? P[2].f : tau_f == 0.5 * L ? f_mid_ : boundAt(tau_f);
  const double f_max = std::max({ p0.f, P[0].f, P[1].f, P[2].f, f_after });
  double quad_err = 0.0;
  const auto overOf = [&](double e_t) {
    quad_err = quadErr(e_t);
    return std::max(2.0 * dirErr(e_t) * f_max * (travel + after), quad_err) / std::max(density * travel, 1e-300);
  };
  double over = overOf(err_t);
  if (over > 1.0 && rejected)
  {
    err_t = (step * R0.rhs(err_t) + dz) / (kRadau.u1 - step * R0.b);
    over = overOf(err_t);
  }
  return { ZF[2], ZM[2], gf, pull, travel, quad_err, dirErr(err_t), over };
}

bool Collocation::run(const SlideStart& start, SlideEnd& end, SlideStart& resume)
{
  PathIntegrals& out = ctx_.out;
  const double L = p_.length, tol = ctx_.tolerance;
  resume = start;
  const double tau_a = std::max(start.tau, 0.0);
  if (!(tau_a < L))
    return false;
  // a piece whose bound is too small for its forces to count: the general solver bounds it at once
  if ((L - tau_a) * law_.shape(p_.edgeDistance(0.5 * L)) <= kEdgeShare * tol)
    return false;

  double s;
  cd e;                // the bristle's direction between steps
  double error = 0.0;  // bound on what this piece adds
  double drift = 0.0;  // bound on the direction's error carried into the next step [rad]
  if (start.from_rim)
  {
    if (!startInside(s, e, error, drift))
      return false;
  }
  else
  {
    s = map_.of(tau_a);
    e = start.direction;
  }
  bool armed = start.armed;

  // where to stop: the trailing edge, less (f ~ t) the stretch whose bound is below what counts; where that stretch
  // cannot be bounded (the drive vanishes there), the general solver takes the last part
  double s_end = map_.end(), rest_end = 0.0, dmax_end = 0.0;
  bool edge_end = m_ == 2;
  if (m_ == 2)
  {
    if (!edgeStretch(f_.drive(p_.position(L)), false, rest_end, dmax_end))
    {
      edge_end = false;
      rest_end = 1e-3 * L;
    }
    s_end = std::log((L - rest_end) / rest_end);
  }
  if (!(s_end > s))
    return false;

  cd force = 0.0;
  double moment = 0.0;
  const double density = tol / L;  // error allowed per unit travel
  // the rigid field's part, f w / |w|, is integrated by the rigid law's rules over each run of steps whose correction
  // is taken against it (where the drive is resolved), so that the steps integrate only the small correction
  bool in_run = true;
  double run_from = start.from_rim ? 0.0 : tau_a;
  double h = std::min((start.from_rim ? 2.0 : 1.0) * map_.longestStep(), s_end - s);  // the rim: on the slow manifold
  const double longest = 2.0 * map_.longestStep();  // beyond, the estimates' models were seen to fail
  double slack = 0.0;    // what the accepted steps left of their shares of the tolerance
  bool rejected = true;  // RADAU5 filters its estimate once more on a first or rejected step
  bool done = false, re_adheres = false;
  // the last accepted step's stages, in its frame: extrapolated, the next step's guess
  bool have_previous = false;
  double previous[4] = {}, previous_step = 0.0;
  Point p0 = at(s);
  for (int attempt = 0; attempt < kMaxSteps; ++attempt)
  {
    if (out.work > ctx_.work_limit)
      break;
    out.work += kStepWork;
    bool last = h >= s_end - s;
    double step = last ? s_end - s : h;
    const double tiny = 1e-7 * (1.0 + std::abs(s));
    if (step < tiny)
      break;
    Point P[3];
    for (int i = 0; i < 3; ++i)
      P[i] = at(i == 2 && last ? s_end : s + kRadau.c[i] * step);
    Riccati R[3];
    for (int i = 0; i < 3; ++i)
      R[i] = riccati(P[i], e);
    const Riccati R0 = riccati(p0, e);
    double guess[3];
    guessStages(R, R0, step, have_previous ? previous : nullptr, previous_step, guess);
    double T[3];
    if (!collocate(R, step, guess, T) || std::max({ std::abs(T[0]), std::abs(T[1]), std::abs(T[2]) }) > kMaxTurn)
    {
      h = 0.5 * step;
      rejected = true;
      continue;
    }
    cd E[3];
    for (int i = 0; i < 3; ++i)
      E[i] = e * rotation(T[i]);

    bool armed_next;
    {
      const double stop = reAdhesion(p0, P, E, T, e, s, step, armed, armed_next);
      if (stop > 0.0)
      {
        // the step up to the re-adhesion, collocated on its own
        step *= stop;
        last = true;
        for (int i = 0; i < 3; ++i)
        {
          P[i] = at(s + kRadau.c[i] * step);
          R[i] = riccati(P[i], e);
        }
        const double Tx[4] = { 0.0, T[0], T[1], T[2] };
        for (int i = 0; i < 3; ++i)
          guess[i] = kRadau.cubic(Tx, kRadau.c[i] * stop);
        if (!collocate(R, step, guess, T) || std::max({ std::abs(T[0]), std::abs(T[1]), std::abs(T[2]) }) > kMaxTurn)
          break;  // the general solver finds it
        for (int i = 0; i < 3; ++i)
          E[i] = e * rotation(T[i]);
        re_adheres = true;
      }
    }

    // The correction's reference: the rigid field where the drive is resolved over the step (it swings by up to pi beside
    // a spin pole, and has no direction at it); there the steps integrate the whole stress instead.
    const bool referenced = p0.w_abs > 0.0 && P[0].w_abs > 0.0 && P[1].w_abs > 0.0 && P[2].w_abs > 0.0 &&
                            dot(P[0].w_hat, p0.w_hat) >= kCosMaxDriveTurn &&
                            dot(P[1].w_hat, P[0].w_hat) >= kCosMaxDriveTurn &&
                            dot(P[2].w_hat, P[1].w_hat) >= kCosMaxDriveTurn;
    const StepEstimate x = estimate(p0, P, E, T, R0, e, step, referenced, rejected);
    // over its share where the accepted steps left the room (kMaxOver)
    const double room = std::min(kMaxOver, 1.0 + slack / std::max(density * x.travel, 1e-300));
    if (x.over > room && step > 10.0 * tiny)
    {
      h = step * std::max(0.2, 0.85 / std::sqrt(std::sqrt(x.over)));
      rejected = true;
      re_adheres = false;
      continue;
    }
    // accepted
    slack = std::max(0.0, slack + density * x.travel * (1.0 - x.over));
    armed = armed_next;
    if (referenced && !in_run)
    {
      in_run = true;
      run_from = p0.tau;
    }
    else if (!referenced && in_run)
    {
      integrateRigid(ctx_, run_from, p0.tau, kRigidShare * tol);
      in_run = false;
    }
    force += x.force;
    moment += x.moment;
    error += drift * x.gf + x.quad_err;  // the direction's error carried in errs |e - e_exact| <= drift on this step
    drift = drift * std::exp(std::clamp(-x.pull * step, -50.0, 2.0)) + 2.0 * x.dir_err;
    previous[0] = 0.0;
    previous[1] = T[0];
    previous[2] = T[1];
    previous[3] = T[2];
    previous_step = step;
    have_previous = true;
    s = last && !re_adheres ? s_end : s + step;
    e = E[2] * (1.0 / std::sqrt(std::norm(E[2])));
    p0 = P[2];
    rejected = false;
    if (re_adheres)
      break;
    if (last)
    {
      done = true;
      break;
    }
    h = step * std::clamp(0.85 / std::sqrt(std::sqrt(std::max(x.over, 1e-12))), 0.2, 3.0);
    h = std::min(h, longest);
    if (const double rest = s_end - s; rest > h && rest <= kStretch * h && rest <= longest)
      h = rest;
  }

  // to the trailing edge (its last stretch bounded), to a re-adhesion, or to where the general solver goes on
  const bool finished = (done && edge_end) || re_adheres;
  const double tau_stop = done && edge_end ? L : p0.tau;
  if (in_run)
    integrateRigid(ctx_, run_from, tau_stop, kRigidShare * tol);
  else if (done && edge_end)
    integrateRigid(ctx_, p0.tau, L, kRigidShare * tol);
  out.force += force;
  out.moment += moment;
  out.sliding += tau_stop - tau_a;
  out.utilisation2 = 1.0;
  if (done && edge_end)
  {
    // the trailing stretch (edgeStretch): |Delta| stays within the larger of its value where the stretch starts and the
    // stretch's bound
    const double lag = (p0.w_abs > 0.0 ? std::abs(std::arg(e * std::conj(p0.w_hat))) : kHalfPi) + drift;
    error += std::max(lag, dmax_end) * rest_end * rest_end;
  }
  else
    error += drift * (L - p0.tau);  // the direction's error carried on (the general solver's or the next piece's): f <= 1
  out.error += error;
  if (finished)
  {
    end.tau = tau_stop;
    end.direction = e;
    end.re_adheres = re_adheres;
    return true;
  }
  resume = SlideStart{};
  resume.tau = p0.tau;
  resume.direction = e;
  resume.from_rim = false;
  resume.armed = armed;
  return false;
}
}  // namespace

bool slideCollocation(PathContext& ctx, const SlideStart& start, SlideEnd& end, SlideStart& resume)
{
  return Collocation(ctx).run(start, end, resume);
}

}  // namespace sphere_contact_estimator::path
