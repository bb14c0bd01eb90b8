#include "coulomb_sliding.h"
#include "coulomb_collocation.h"
#include "rigid_sliding.h"
#include "travel_map.h"
#include "sphere_contact_estimator/core/numerics/illinois.h"

// STL
#include <algorithm>
#include <array>
#include <cmath>

namespace sphere_contact_estimator::path
{
namespace
{
constexpr double kMaxDriveTurn = 0.5;  // rad between a step's neighbouring points: the drive resolved
const double kCosMaxDriveTurn = std::cos(kMaxDriveTurn);
constexpr int kDipSamples = 32;  // points per step at which the sliding speed's quartic is searched for a dip
constexpr int kMaxSteps = 4000;      // attempted steps per piece; beyond, the path is flagged truncated
constexpr long kStepWork = 80;       // four nodes and two 2x2 exponentials (PathIntegrals::work units)
constexpr double kEdgeShare = 1e-2;  // of the tolerance: what the unintegrated ends of a piece may hold
constexpr double kRigidShare = 0.2;  // of the tolerance: the rigid part's rules (their bound is cheap to tighten)
constexpr double kMaxTurnError = 1e-2;  // rad per step, wherever the bound is: the events read the direction
constexpr double kStiffStep = 8.0;  // W h beyond which a relaxed direction follows the slow manifold (Magnus: h < pi / W)
constexpr double kMagnusReach = 2.0;  // W h within which the sixth-order step's error follows d^(7/5)
// Where the bound is below a tenth of its peak a step may be up to this many of the map's scale long: its forces are
// small, so the integrand's change over it matters less. A slow-manifold step never is: the quartic through its five
// points interpolates the manifold only over the map's scale (longer ones missed the error at 2 of 120 random points).
constexpr double kFaintStretch = 4.0;
constexpr double kRelaxed = 0.2;    // rad off the slow manifold: relaxed enough that the rest decays as if linear
// The sixth-order step's error against the difference d of the fourth- and sixth-order ones: both errors scale with
// powers of (|B| h), h^7 and h^5, so err6 ~ c d^(7/5) with c independent of the scale; c = 1.6 - 3.9 measured over
// steps of 0.2 - 1.6 on full-sliding paths (docs/benchmarks.md), taken 10.
constexpr double kSixthOrder = 10.0;

// Three Gauss-Legendre nodes on [0, 1] and their weights: the Magnus methods' and the forces' rule.
constexpr double kHalfSpread = 0.3872983346207417;  // sqrt(15) / 10
constexpr double kC[3] = { 0.5 - kHalfSpread, 0.5, 0.5 + kHalfSpread };
constexpr double kW[3] = { 5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0 };

// The quartic through a step's five points x = 0, the three Gauss nodes, 1: its value at x as weights of the five
// values, and its derivative (in x) at each of them.
constexpr double kFive[5] = { 0.0, kC[0], kC[1], kC[2], 1.0 };
double quarticValue(double x, int k)
{
  double v = 1.0;
  for (int j = 0; j < 5; ++j)
    if (j != k)
      v *= (x - kFive[j]) / (kFive[k] - kFive[j]);
  return v;
}
const auto kQuarticSlope = [] {
  std::array<std::array<double, 5>, 5> d{};
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 5; ++k)
    {
      // d/dx of the k-th Lagrange basis polynomial at x_i
      double sum = 0.0;
      for (int m = 0; m < 5; ++m)
      {
        if (m == k)
          continue;
        double term = 1.0 / (kFive[k] - kFive[m]);
        for (int j = 0; j < 5; ++j)
          if (j != k && j != m)
            term *= (kFive[i] - kFive[j]) / (kFive[k] - kFive[j]);
        sum += term;
      }
      d[i][k] = sum;
    }
  return d;
}();

// The quartic's weights at the interior points i / kDipSamples, where re-adhesion is searched between a step's samples
// (once, not at every step: each weight takes four divisions)
const auto kDipWeights = [] {
  std::array<std::array<double, 5>, kDipSamples - 1> w{};
  for (int i = 1; i < kDipSamples; ++i)
    for (int k = 0; k < 5; ++k)
      w[i - 1][k] = quarticValue(static_cast<double>(i) / kDipSamples, k);
  return w;
}();

/// A real 2x2 matrix [[a, b], [c, d]].
struct Mat
{
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
};
Mat operator+(const Mat& x, const Mat& y) { return { x.a + y.a, x.b + y.b, x.c + y.c, x.d + y.d }; }
Mat operator-(const Mat& x, const Mat& y) { return { x.a - y.a, x.b - y.b, x.c - y.c, x.d - y.d }; }
Mat operator*(double k, const Mat& x) { return { k * x.a, k * x.b, k * x.c, k * x.d }; }
Mat commutator(const Mat& x, const Mat& y)
{
  return { x.b * y.c - x.c * y.b, x.a * y.b + x.b * y.d - y.a * x.b - y.b * x.d,
           x.c * y.a + x.d * y.c - y.c * x.a - y.d * x.c, x.c * y.b - x.b * y.c };
}

struct Vec
{
  double x = 1.0, y = 0.0;
};
Vec normalized(Vec v)
{
  const double n2 = v.x * v.x + v.y * v.y;  // v is of order 1: no overflow
  if (!(n2 > 0.0))
    return Vec{};
  const double k = 1.0 / std::sqrt(n2);
  return { v.x * k, v.y * k };
}
// The unit direction e^{i theta} of the half-angle vector v = (cos theta/2, sin theta/2) (any length): v^2 / |v|^2.
cd direction(Vec v)
{
  const double n2 = v.x * v.x + v.y * v.y;
  return n2 > 0.0 ? cd(v.x * v.x - v.y * v.y, 2.0 * v.x * v.y) / n2 : cd(1.0, 0.0);
}
// A half-angle vector of the unit direction e.
// A half-angle vector of the unit direction e: the larger component from the cosine, the other as sin / (2 that),
// so that neither loses digits (sqrt(1 - cos) would near theta = 0).
Vec halfAngle(cd e)
{
  const double c = std::clamp(e.real(), -1.0, 1.0);
  if (c >= 0.0)
  {
    const double x = std::sqrt(0.5 * (1.0 + c));
    return { x, 0.5 * e.imag() / x };
  }
  const double y = std::copysign(std::sqrt(0.5 * (1.0 - c)), e.imag());
  return { 0.5 * e.imag() / y, y };
}
double angleOf(Vec v) { return 2.0 * std::atan2(v.y, v.x); }

// exp(O) v, up to a positive factor (only the direction counts), for a traceless O: O^2 = q I with q = a^2 + b c, so
// exp(O) = cosh(sqrt q) I + sinh(sqrt q) / sqrt(q) O, here divided by the cosh (no overflow in a stiff step).
Vec applyExp(const Mat& O, Vec v)
{
  const double a = 0.5 * (O.a - O.d);  // the traceless part (a trace only scales)
  const double q = a * a + O.b * O.c;
  double c, k;  // exp ~ c I + k [[a, b], [c, -a]]
  if (q > 1e-8)
  {
    const double mu = std::sqrt(q), e = std::exp(-2.0 * mu);  // tanh(mu) = (1 - e) / (1 + e)
    c = 1.0;
    k = (1.0 - e) / ((1.0 + e) * mu);
  }
  else if (q < -1e-8)
  {
    const double nu = std::sqrt(-q);
    c = std::cos(nu);
    k = std::sin(nu) / nu;
  }
  else  // the series of both to q^2
  {
    c = 1.0 + q / 2.0 + q * q / 24.0;
    k = 1.0 + q / 6.0 + q * q / 120.0;
  }
  return normalized({ c * v.x + k * (a * v.x + O.b * v.y), c * v.y + k * (O.c * v.x - a * v.y) });
}

// What the law needs at one point of the path, in the map's variable s (' = d/ds).
struct Node
{
  double s = 0.0, tau = 0.0, rest = 0.0;
  double g = 0.0;      // dtau/ds
  double f = 0.0;      // the bound
  double slope = 0.0;  // df/dtau
  cd z, w;             // root, drive
  cd w_hat;            // w / |w| (1 where w = 0)
  bool turns = false;  // w != 0: the drive's frame exists
  // The direction equation theta' = K + Im(W e^{-i theta}) with W = (g / f) w, K = g kappa; in the drive's frame
  // (Delta = theta - arg w): Delta' = Kd - |W| sin Delta with Kd = g (kappa - d arg(w) / dtau).
  double W_abs = 0.0, W_abs_s = 0.0, Kd = 0.0, Kd_s = 0.0;
  Mat B;   // the half-angle system in the patch's frame
  Mat Bd;  // and in the drive's
};

class CoulombSlider
{
public:
  CoulombSlider(const BristleField& field, const BristlePath& path, double tolerance)
    : f_(field)
    , p_(path)
    , law_(field.pressure)
    , m_(law_.squaredExponent())
    , map_(m_, path.length)
    , tol_(tolerance)
    , straight_(field.omega == 0.0)
  {
  }

  // g / f, finite at the ends (t vanishes as tau (L - tau) times a positive factor)
  double ratio(double tau, double rest, double g, double t) const
  {
    if (m_ == 2)
      return t > 0.0 ? tau * rest / (p_.length * t) : 1.0 / p_.length;
    if (m_ == 1)
      return t > 0.0 ? std::sqrt(tau * rest / t) : 1.0;
    (void)g;
    return 1.0;
  }

  Node node(double s) const
  {
    Node n;
    n.s = s;
    double g_s;
    map_.at(s, n.tau, n.rest, n.g, g_s);
    double t, ratio_value, ratio_s = 0.0;
    cd z_tau(-1.0, 0.0);
    if (straight_)  // z = z_e - tau, 1 - r^2 = tau (L - tau): g / f is constant
    {
      n.z = cd(p_.entry.real() - n.tau, p_.entry.imag());
      t = n.tau * n.rest;
      ratio_value = m_ == 2 ? 1.0 / p_.length : 1.0;
    }
    else
    {
      n.z = p_.position(n.tau);
      z_tau += timesI(f_.omega, n.z);
      t = p_.edgeDistanceNear(std::min(n.tau, n.rest));
      ratio_value = ratio(n.tau, n.rest, n.g, t);
      if (m_ != 0)  // its derivative along the arc, by a central difference (smooth, and only where it matters)
      {
        const double d = 1e-5 * std::min(n.tau, n.rest);
        if (d > 0.0)
        {
          const auto at = [&](double tau) {
            const double rest = p_.length - tau;
            return ratio(tau, rest, 0.0, p_.edgeDistanceNear(std::min(tau, rest)));
          };
          ratio_s = n.g * (at(n.tau + d) - at(n.tau - d)) / (2.0 * d);
        }
      }
    }
    // (a node is on the path, inside the patch or at its ends: a constant bound is its value there, not the 0 beyond)
    n.f = m_ == 0 ? 1.0 : law_.shape(t);
    n.slope = law_.shapeSlope(t) * 2.0 * n.z.real();  // dt/dtau = -d(r^2)/dtau = 2 x on any path
    n.w = f_.drive(n.z);
    const cd W = ratio_value * n.w;
    const double K = n.g * f_.kappa;
    n.B = { 0.5 * W.real(), 0.5 * (W.imag() - K), 0.5 * (W.imag() + K), -0.5 * W.real() };
    const double w2 = std::norm(n.w), w_abs = std::sqrt(w2);
    n.turns = w_abs > 0.0;
    n.w_hat = n.turns ? n.w / w_abs : cd(1.0, 0.0);
    if (n.turns)
    {
      const cd w_tau = timesI(f_.phi, z_tau), w_tautau = timesI(f_.phi, timesI(f_.omega, z_tau));
      const cd inv_w = std::conj(n.w) / w2;
      const cd q = w_tau * inv_w;                 // d log(w) / dtau: Im is the drive's turn rate
      const cd q_tau = w_tautau * inv_w - q * q;
      n.W_abs = ratio_value * w_abs;
      n.W_abs_s = ratio_s * w_abs + ratio_value * n.g * w_abs * q.real();
      n.Kd = n.g * (f_.kappa - q.imag());
      n.Kd_s = g_s * (f_.kappa - q.imag()) - n.g * n.g * q_tau.imag();
      n.Bd = { 0.5 * n.W_abs, -0.5 * n.Kd, 0.5 * n.Kd, -0.5 * n.W_abs };
    }
    return n;
  }

  // The law's sliding speed sign, Re(w e*) - df/dtau: sliding goes on while it is >= 0 (eq. 4b, lambda >= 0).
  static double pushing(const Node& n, cd e) { return dot(n.w, e) - n.slope; }

  // The direction the law gives a bristle entering sliding where the bound vanishes: the growing mode of B.
  static Vec growingMode(const Mat& B)
  {
    const double a = 0.5 * (B.a - B.d), q = a * a + B.b * B.c;
    if (!(q > 0.0))
      return halfAngle(cd(1.0, 0.0));
    const double mu = std::sqrt(q);
    const Vec v1{ B.b, mu - a }, v2{ mu + a, B.c };
    return normalized(v1.x * v1.x + v1.y * v1.y >= v2.x * v2.x + v2.y * v2.y ? v1 : v2);
  }

  // Runs the piece; accumulates into `out` unless it is null; stops at stop_tau (drawing) or at a re-adhesion.
  SlideEnd run(const SlideStart& start, double stop_tau, PathContext* ctx);

private:
  // A step's direction: at its end (end) with its error (err), and inside it at a share x of the step: on the slow
  // manifold (quasi: the quartic through its values at the five points), the quintic Hermite interpolant of Delta in
  // the drive's frame (smooth), else the fourth-order Magnus approximation over [0, x h] of the quadratic through the
  // nodes, B(y) = P0 + P1 (y - 1/2) + P2 (y - 1/2)^2, from the start's half-angle vector v0.
  struct StepDirection
  {
    double step = 0.0;
    bool in_drive = false, quasi = false, smooth = false;
    double manifold[5] = {};
    double eta0 = 0.0, lambda = 0.0;  // quasi: the start's deviation from the manifold and the rate it decays at
    Mat P0, P1, P2;
    Vec v0;
    double y0 = 0.0, y1 = 0.0, p0 = 0.0, p1 = 0.0, q0 = 0.0, q1 = 0.0;  // the Hermite interpolant's end data
    cd end;
    double err = 0.0;

    cd magnus(double x) const
    {
      const double y = x - 0.5, ym = 0.5 * x - 0.5;
      const Mat integral = x * P0 + (0.5 * (y * y - 0.25)) * P1 + ((y * y * y + 0.125) / 3.0) * P2;
      const Mat mid = P0 + ym * P1 + (ym * ym) * P2, rate = P1 + (2.0 * ym) * P2;
      return direction(applyExp(step * integral - (x * x * x * step * step / 12.0) * commutator(mid, rate), v0));
    }
    double hermite(double x) const
    {
      const double x2 = x * x, x3 = x2 * x, x4 = x3 * x, x5 = x4 * x;
      return (1.0 - 10.0 * x3 + 15.0 * x4 - 6.0 * x5) * y0 + (x - 6.0 * x3 + 8.0 * x4 - 3.0 * x5) * p0 +
             (0.5 * x2 - 1.5 * x3 + 1.5 * x4 - 0.5 * x5) * q0 + (10.0 * x3 - 15.0 * x4 + 6.0 * x5) * y1 +
             (-4.0 * x3 + 7.0 * x4 - 3.0 * x5) * p1 + (0.5 * x3 - x4 + 0.5 * x5) * q1;
    }
    cd at(double x, const Node& node) const
    {
      if (quasi)
      {
        double value = 0.0;
        for (int k = 0; k < 5; ++k)
          value += quarticValue(x, k) * manifold[k];
        return std::polar(1.0, value) * node.w_hat;
      }
      if (smooth)
        return std::polar(1.0, hermite(x)) * node.w_hat;
      return in_drive ? magnus(x) * node.w_hat : magnus(x);
    }
  };
  // A step's correction to the rigid field, f g (e - w / |w|) (and its moment), by the Gauss rule with its error from
  // Simpson's; the law's pull mid-step; and the step's errors against its share of the tolerance (over 1: rejected).
  struct StepForces
  {
    cd e_at[3];  // the direction at the Gauss nodes
    cd gauss_f;
    double gauss_m = 0.0, quad_err = 0.0, pull = 0.0, over = 0.0;
  };
  static cd rigid(const Node& at) { return at.turns ? at.w_hat : cd(0.0); }
  static void correction(const Node& at, cd dir, cd& force, double& moment)
  {
    force = at.g * at.f * (dir - rigid(at));
    moment = cross(at.z, force);
  }
  // run()'s rooms, each inlined there: the slow manifold's step (d.quasi on entry; false where it does not hold), the
  // Magnus step where that does not hold (with the matrices of the interpolant it leaves), the step's forces and
  // estimate, and the share of the step that slides before a re-adhesion (1: none; armed as eq. 4b's events leave it).
  [[gnu::always_inline]] void slowManifold(const Node& n0, const Node* n, const Node& nE, cd e, StepDirection& d) const;
  [[gnu::always_inline]] void magnusStep(const Node& n0, const Node* n, const Node& nE, cd e, double W_max,
                                         StepDirection& d) const;
  [[gnu::always_inline]] StepForces stepForces(const Node& n0, const Node* n, const Node& nE, cd e,
                                               const StepDirection& d, double f_max, double density) const;
  [[gnu::always_inline]] double slidingShare(const Node& n0, const Node* n, const Node& nE, cd e,
                                             const StepDirection& d, const StepForces& q, double s, bool edge,
                                             bool& armed) const;

  const BristleField& f_;
  const BristlePath& p_;
  PressureLaw law_;
  int m_;
  TravelMap map_;
  double tol_;
  bool straight_;
};

// Delta and its first two derivatives at a node: the quintic Hermite interpolant of the drive's frame
double slopeOf(const Node& n, double delta) { return n.Kd - n.W_abs * std::sin(delta); }
double curvatureOf(const Node& n, double delta)
{
  return n.Kd_s - n.W_abs_s * std::sin(delta) - n.W_abs * std::cos(delta) * slopeOf(n, delta);
}

inline void CoulombSlider::slowManifold(const Node& n0, const Node* n, const Node& nE, cd e, StepDirection& d) const
{
  // In the drive's frame, where the law pulls the bristle onto the drive much faster than the step is long (W h
  // beyond the Magnus series' reach, pi) and the direction has relaxed onto it: the slow manifold of
  // Delta' = Kd - W sin Delta, an expansion in 1 / W, Delta* = arcsin((Kd - D0') / W) with D0 = arcsin(Kd / W); its
  // last term, halved, bounds the next. What is left of the start's deviation decays at the law's rate W cos Delta*.
  bool& quasi = d.quasi;
  const double step = d.step;
  double qs_err = 0.0;
  // the five points of the step, x = 0, the three Gauss nodes, 1 (the quartic through them interpolates Delta*)
  const Node* at5[5] = { &n0, &n[0], &n[1], &n[2], &nE };
  double* const manifold = d.manifold;
  // three terms: D0 = arcsin(Kd / W), D1 = arcsin((Kd - D0') / W), D2 = arcsin((Kd - D1') / W), D0' exact from the
  // nodes' derivatives, D1' from the quartic through the five points; the next term is estimated from the last two
  // (it is smaller by their ratio, about 1 / (W l), l the inputs' scale)
  double d0[5], d1[5];
  for (int j = 0; j < 5 && quasi; ++j)
  {
    const Node& x = *at5[j];
    const double r = x.Kd / x.W_abs;
    const double r_s = (x.Kd_s * x.W_abs - x.Kd * x.W_abs_s) / (x.W_abs * x.W_abs);
    const double r1 = std::abs(r) < 0.5 ? (x.Kd - r_s / std::sqrt(1.0 - r * r)) / x.W_abs : 1.0;
    quasi = std::abs(r1) < 0.5;
    if (quasi)
    {
      d0[j] = std::asin(r);
      d1[j] = std::asin(r1);
    }
  }
  double term1 = 0.0, term2 = 0.0;
  for (int j = 0; j < 5 && quasi; ++j)
  {
    double d1_x = 0.0;
    for (int k = 0; k < 5; ++k)
      d1_x += kQuarticSlope[j][k] * d1[k];
    const double r2 = (at5[j]->Kd - d1_x / step) / at5[j]->W_abs;
    quasi = std::abs(r2) < 0.5;
    manifold[j] = std::asin(r2);
    term1 = std::max(term1, std::abs(d1[j] - d0[j]));
    term2 = std::max(term2, std::abs(manifold[j] - d1[j]));
  }
  qs_err = term2 * std::min(1.0, 3.0 * term2 / std::max(term1, 1e-300));
  if (quasi)
  {
    d.eta0 = std::arg(e * std::conj(n0.w_hat) * std::polar(1.0, -manifold[0]));
    d.lambda = n0.W_abs * std::cos(manifold[0]);
    quasi = std::abs(d.eta0) <= kRelaxed && d.lambda * step >= kStiffStep;
  }
  if (quasi)
  {
    d.end = std::polar(1.0, manifold[4] + d.eta0 * std::exp(-d.lambda * step)) * nE.w_hat;
    // The manifold's next term; and the start's deviation eta0, integrated below in closed form to first order
    // (it decays within 1 / lambda << h): its second-order part and the change of f g over its decay, per unit of f
    // over the step.
    d.err = qs_err + std::abs(d.eta0) * (std::abs(d.eta0) + 1.0 / d.lambda) / (d.lambda * step);
    d.smooth = true;
  }
}

inline void CoulombSlider::magnusStep(const Node& n0, const Node* n, const Node& nE, cd e, double W_max,
                                      StepDirection& d) const
{
  const double step = d.step;
  const bool in_drive = d.in_drive;
  // sixth- and fourth-order Magnus approximations of the step's log from the same Gauss nodes
  const Mat& B1 = in_drive ? n[0].Bd : n[0].B;
  const Mat& B2 = in_drive ? n[1].Bd : n[1].B;
  const Mat& B3 = in_drive ? n[2].Bd : n[2].B;
  const cd frame0 = in_drive ? n0.w_hat : cd(1.0, 0.0), frame1 = in_drive ? nE.w_hat : cd(1.0, 0.0);
  d.v0 = halfAngle(e * std::conj(frame0));
  d.P0 = B2;
  d.P1 = (0.5 / kHalfSpread) * (B3 - B1);
  d.P2 = (0.5 / (kHalfSpread * kHalfSpread)) * (B3 - 2.0 * B2 + B1);
  const Mat a1 = step * B2, a2 = (1.2909944487358056 * step) * (B3 - B1) /* sqrt(15) / 3 */,
            a3 = (10.0 * step / 3.0) * (B3 - 2.0 * B2 + B1);
  const Mat c1 = commutator(a1, a2);
  const Mat c2 = (-1.0 / 60.0) * commutator(a1, 2.0 * a3 + c1);
  const Mat base = a1 + (1.0 / 12.0) * a3;
  const Mat omega6 = base + (1.0 / 240.0) * commutator(-20.0 * a1 - a3 + c1, a2 + c2);
  const Mat omega4 = base - (1.0 / 12.0) * c1;
  const Vec v6 = applyExp(omega6, d.v0), v4 = applyExp(omega4, d.v0);
  d.end = direction(v6) * frame1;
  const double de = std::sqrt(std::norm(d.end - direction(v4) * frame1));
  // The direction inside the step. In the drive's frame: the quintic Hermite interpolant of Delta from its value
  // and first two derivatives at both ends (sixth order). Where that does not hold (a fast transient) or in the
  // patch's frame: from the start by the fourth-order Magnus approximation over [0, x h] of the quadratic through
  // the nodes, B(y) = P0 + P1 (y - 1/2) + P2 (y - 1/2)^2.
  d.y0 = angleOf(d.v0);
  d.y1 = d.y0 + std::arg(direction(v6) * std::conj(direction(d.v0)));
  d.p0 = step * slopeOf(n0, d.y0);
  d.p1 = step * slopeOf(nE, d.y1);
  d.q0 = step * step * curvatureOf(n0, d.y0);
  d.q1 = step * step * curvatureOf(nE, d.y1);
  d.smooth = in_drive && std::norm(d.magnus(0.5) - std::polar(1.0, d.hermite(0.5))) <= std::max(de * de, 1e-26);
  // the sixth-order error model holds within the Magnus series' reach (W h well below pi); beyond, the difference
  d.err = d.smooth && W_max * step <= kMagnusReach ? kSixthOrder * std::pow(de, 1.4) : de;
}

inline CoulombSlider::StepForces CoulombSlider::stepForces(const Node& n0, const Node* n, const Node& nE, cd e,
                                                          const StepDirection& d, double f_max, double density) const
{
  const double step = d.step, L = p_.length;
  StepForces q;
  for (int j = 0; j < 3; ++j)
    q.e_at[j] = d.at(kC[j], n[j]);
  // the correction f (e - w / |w|) g and its moment: the Gauss rule, and Simpson's on the ends and the middle node
  // for its error
  cd qf[3], qf0, qfE;
  double qm[3], qm0, qmE;
  for (int j = 0; j < 3; ++j)
    correction(n[j], q.e_at[j], qf[j], qm[j]);
  correction(n0, e, qf0, qm0);
  correction(nE, d.end, qfE, qmE);
  q.gauss_f = step * (kW[0] * qf[0] + kW[1] * qf[1] + kW[2] * qf[2]);
  q.gauss_m = step * (kW[0] * qm[0] + kW[1] * qm[1] + kW[2] * qm[2]);
  // Simpson's rule is two orders below the Gauss rule: its difference, scaled as QUADPACK scales its Kronrod
  // difference (by a power of its size relative to the step's scale), estimates the Gauss rule's error.
  const double simpson_diff = std::max(std::sqrt(std::norm(q.gauss_f - step / 6.0 * (qf0 + 4.0 * qf[1] + qfE))),
                                       std::abs(q.gauss_m - step / 6.0 * (qm0 + 4.0 * qm[1] + qmE)));
  double scale = 0.0;
  for (int j = 0; j < 3; ++j)
    scale = std::max({ scale, std::sqrt(std::norm(qf[j])), std::abs(qm[j]) });
  scale = std::max({ scale, std::sqrt(std::norm(qf0)), std::sqrt(std::norm(qfE)) }) * step;
  q.quad_err =
      scale > 0.0 ? simpson_diff * std::min(1.0, 10.0 * std::pow(simpson_diff / scale, 0.4)) : simpson_diff;
  const double travel = nE.tau - n0.tau;
  // A direction error made here errs the forces over this step and, decaying at the rate the law pulls the bristle back
  // (d(delta theta)/ds = -(g / f) Re(w e*) delta theta), over the travel after it: the step gets its share of the
  // tolerance for both. The direction must also stay resolved where the bound is too small for its forces to count:
  // the events read it.
  q.pull = n[1].W_abs > 0.0 ? n[1].W_abs * dot(n[1].w_hat, q.e_at[1]) : 0.0;
  const double after = std::min(std::max(L - nE.tau, 0.0), q.pull > 0.0 ? n[1].g / q.pull : INFINITY);
  const double share = travel > 0.0 ? std::max(0.1, travel / (travel + after)) : 1.0;  // at most 10x stricter
  q.over = std::max({ d.err * f_max / (density * share), d.err / kMaxTurnError, 1e-300 });
  if (q.quad_err > 0.0)
    q.over = std::max(q.over, q.quad_err / (density * travel));
  return q;
}

inline double CoulombSlider::slidingShare(const Node& n0, const Node* n, const Node& nE, cd e, const StepDirection& d,
                                          const StepForces& q, double s, bool edge, bool& armed) const
{
  // re-adhesion: the first sample where the bristle is no longer pushed outward faster than the bound grows. Beside
  // the step's own samples, a probe where the quartic through the sliding speed at the step's five points is least,
  // if that dips below zero between them: a re-adhesion window narrower than the samples' spacing (beside a spin
  // pole) was otherwise found at some step sizes and missed at others, and the paths' structure flickered with the
  // tolerance.
  const double step = d.step;
  double stop = 1.0;  // share of the step that slides
  double xs[5] = { kC[0], kC[1], kC[2], 1.0, 0.0 };
  double Es[5] = { pushing(n[0], q.e_at[0]), pushing(n[1], q.e_at[1]), pushing(n[2], q.e_at[2]), pushing(nE, d.end),
                   0.0 };
  int samples = edge ? 3 : 4;
  {
    const double E5[5] = { pushing(n0, e), Es[0], Es[1], Es[2], Es[3] };
    double lowest = 0.0, at_x = 0.0;
    for (int i = 1; i < kDipSamples; ++i)
    {
      double value = 0.0;
      for (int k = 0; k < 5; ++k)
        value += kDipWeights[i - 1][k] * E5[k];
      if (value < lowest)
        lowest = value, at_x = static_cast<double>(i) / kDipSamples;
    }
    if (lowest < 0.0 && *std::min_element(E5, E5 + 5) >= 0.0 && !(edge && at_x > kC[2]))
    {
      const Node probe = node(s + at_x * step);
      const int k = static_cast<int>(std::upper_bound(xs, xs + samples, at_x) - xs);
      for (int i = samples; i > k; --i)
        xs[i] = xs[i - 1], Es[i] = Es[i - 1];
      xs[k] = at_x;
      Es[k] = pushing(probe, d.at(at_x, probe));
      ++samples;
    }
  }
  double prev = 0.0;
  for (int j = 0; j < samples; ++j)
  {
    const double x = xs[j], E = Es[j];
    if (E > 0.0)
      armed = true;
    else if (armed && E < 0.0)
    {
      // bracketed in (prev, x]: regula falsi (Illinois) on the step's interpolant
      const auto g = [&](double y) {
        const Node at = node(s + y * step);
        return pushing(at, d.at(y, at));
      };
      stop = numerics::illinoisNegativeEnd(g, prev, x, std::max(g(prev), 0.0), E, 1e-13, 60);
      break;
    }
    prev = x;
  }
  return stop;
}

SlideEnd CoulombSlider::run(const SlideStart& start, double stop_tau, PathContext* ctx)
{
  PathIntegrals* out = ctx ? &ctx->out : nullptr;
  const long work_limit = ctx ? ctx->work_limit : kUnlimitedWork;
  SlideEnd end;
  const double L = p_.length;
  const double tau_a = std::max(start.tau, 0.0);
  end.tau = std::min(stop_tau, L);
  end.direction = start.direction;
  if (!(tau_a < end.tau))
  {
    end.tau = tau_a;
    return end;
  }
  // The forces are the rigid field's, f w / |w|, integrated by the rigid law's own rules over the piece once its end
  // is known, plus the correction f (e - w / |w|) by the steps' Gauss rule: small and smooth where the direction
  // follows the drive closely, which is where the steps are long.
  double s0;
  cd e;  // the state between steps: the unit direction of u
  double error = 0.0;
  if (start.from_rim && m_ == 2)
  {
    // the first stretch, where the bound is below what counts: its correction is bounded, not integrated
    const Node entry = node(map_.of(1e-9 * L));
    const double rate = std::max(std::abs(entry.slope), 1e-3);  // df/dtau at the rim
    const double tau_s = std::min(1e-3 * L, std::sqrt(kEdgeShare * tol_ / rate));
    s0 = map_.of(tau_s);
    e = direction(growingMode(node(s0).B));
    error += 2.0 * (0.5 * rate * tau_s * tau_s);  // |e - w/|w|| <= 2 times the integral of f over [0, tau_s]
  }
  else
  {
    s0 = map_.of(tau_a);
    e = start.direction;
  }
  // where to stop: the trailing edge, less the stretch whose bound is below what counts (f ~ t only), or stop_tau
  double s_end = map_.of(end.tau);
  double tail = 0.0;
  if (end.tau >= L && m_ == 2)
  {
    const Node last = node(map_.of(L * (1.0 - 1e-9)));
    const double rate = std::max(std::abs(last.slope), 1e-3);
    const double rest = std::min(1e-3 * L, std::sqrt(kEdgeShare * tol_ / rate));
    s_end = map_.of(L - rest);
    tail = 0.5 * rate * rest * rest;
  }
  if (!(s_end > s0))
    s_end = s0;
  const auto finish = [&](double extra_error) {
    if (!end.re_adheres)
      end.tau = std::min(stop_tau, L);
    if (out)
    {
      integrateRigid(*ctx, tau_a, end.tau, kRigidShare * tol_);
      if (!end.re_adheres && end.tau >= L)
        error += 2.0 * tail;
      out->sliding += end.tau - tau_a;
      out->utilisation2 = 1.0;
      out->error += error + extra_error;
    }
    return end;
  };
  // A piece whose bound is too small for any force it holds to count (paths grazing the rim, where the direction
  // equation is as stiff as the path is short): the drive's direction, which the law makes it take there, bounded.
  {
    const double most = (node(s_end).tau - node(s0).tau) * law_.shape(p_.edgeDistance(0.5 * L));  // >= int f
    if (out && most <= kEdgeShare * tol_)
    {
      end.direction = node(s_end).w_hat;
      return finish(2.0 * most);
    }
  }
  bool armed = start.armed;
  bool was_quasi = false;
  int quasi_refused = 5;  // steps since the slow manifold last served (a refused attempt waits a few steps to retry)
  double drift = 0.0;                                 // direction error carried into later steps
  const double density = tol_ / std::max(L, 1e-12);  // error allowed per unit travel
  double h = std::isfinite(map_.end()) ? 0.1 * (map_.end() - s0) : 0.5;
  h = std::min(h, s_end - s0);
  int attempts = 0;
  double s = s0;
  Node n0 = node(s0);
  while (s < s_end)
  {
    if (++attempts > kMaxSteps || (out && out->work > work_limit))
    {
      if (out)
        out->truncated = true;
      break;
    }
    if (out)
      out->work += kStepWork;
    const double faint = was_quasi ? 1.0 : std::clamp(0.1 / std::max(n0.f, 1e-300), 1.0, kFaintStretch);
    const double step = std::min({ h, s_end - s, map_.longestStep() * faint });
    const bool last = step >= s_end - s;
    const Node n[3] = { node(s + kC[0] * step), node(s + kC[1] * step), node(s + kC[2] * step) };
    const Node nE = node(s + step);
    // The drive's frame, where the direction hardly turns, unless the drive turns faster there than the law pulls
    // the bristle (beside a spin pole) or vanishes.
    bool in_drive = n0.turns && nE.turns;
    double W_max = 0.0, K_max = 0.0, f_max = 0.0;
    for (const Node& x : n)
    {
      in_drive = in_drive && x.turns;
      W_max = std::max(W_max, x.W_abs);
      K_max = std::max(K_max, std::abs(x.Kd));
      f_max = std::max(f_max, x.f);
    }
    in_drive = in_drive && K_max <= W_max;
    // The drive must be resolved: where the path passes close to a spin pole its direction swings by up to pi over the
    // distance of closest approach, and a step whose five points straddle the swing sees neither it nor the bristle's
    // lag behind it (whose sliding speed may vanish there: a re-adhesion that some step sizes found and others missed,
    // so that the paths' structure flickered with the tolerance).
    {
      const Node* five[5] = { &n0, &n[0], &n[1], &n[2], &nE };
      // |turn| > kMaxDriveTurn between unit directions: the cosine of the turn below that of the limit (no atan2)
      bool swings = false;
      for (int j = 0; j < 4; ++j)
        swings = swings || (five[j]->turns && five[j + 1]->turns && dot(five[j + 1]->w_hat, five[j]->w_hat) < kCosMaxDriveTurn);
      if (swings && step > 1e-9 * (1.0 + std::abs(s)))
      {
        h = 0.5 * step;
        continue;
      }
    }
    // the step's direction: on the slow manifold where the law pulls hard and the bristle has relaxed onto it, else
    // by the Magnus step
    StepDirection d;
    d.step = step;
    d.in_drive = in_drive;
    const double W_min = std::min({ n0.W_abs, n[0].W_abs, n[1].W_abs, n[2].W_abs, nE.W_abs });
    d.quasi = in_drive && W_min * step >= kStiffStep;
    if (d.quasi)
      slowManifold(n0, n, nE, e, d);
    if (!d.quasi)  // (also where the slow manifold did not hold after all)
      magnusStep(n0, n, nE, e, W_max, d);
    const bool quasi = d.quasi;
    const StepForces q = stepForces(n0, n, nE, e, d, f_max, density);
    if (q.over > 1.0 && step > 1e-9 * (1.0 + std::abs(s)))
    {
      h = step * std::max(0.2, 0.9 * std::pow(1.0 / q.over, d.smooth && !quasi ? 1.0 / 7.0 : 0.2));
      if (quasi)
        quasi_refused = 0;
      continue;
    }
    const double stop = out || stop_tau >= L ? slidingShare(n0, n, nE, e, d, q, s, last && end.tau >= L, armed) : 1.0;
    double integral = 0.0;  // of f over the sliding part of the step
    if (stop < 1.0)
    {
      const double part = stop * step;
      for (int j = 0; j < 3; ++j)
      {
        const Node at = node(s + kC[j] * part);
        cd qf_j;
        double qm_j;
        correction(at, d.at(kC[j] * stop, at), qf_j, qm_j);
        if (out)
        {
          out->force += kW[j] * part * qf_j;
          out->moment += kW[j] * part * qm_j;
        }
        integral += kW[j] * part * at.g * at.f;
      }
      const Node at = node(s + part);
      end.tau = at.tau;
      end.direction = d.at(stop, at);
      end.re_adheres = true;
    }
    else
    {
      if (out)
      {
        out->force += q.gauss_f;
        out->moment += q.gauss_m;
      }
      for (int j = 0; j < 3; ++j)
        integral += kW[j] * step * n[j].g * n[j].f;
      end.direction = d.end;
    }
    if (quasi && out)
    {
      // the start's deviation, decaying at lambda: f g (e^{i eta} - 1) e* to first order, integrated in closed form
      const cd transient = cd(0.0, d.eta0 / d.lambda * (1.0 - std::exp(-d.lambda * step * stop))) * n0.g * n0.f *
                           std::polar(1.0, d.manifold[0]) * n0.w_hat;
      out->force += transient;
      out->moment += cross(n0.z, transient);
    }
    // The direction's error: this step's, and what earlier steps left, carried at the rate the law pulls the
    // direction back (d(delta theta)/ds = -(g/f) Re(w e*) delta theta); it errs each force by at most that times f.
    // And the quadrature's.
    drift = drift * std::exp(std::clamp(-q.pull * step * stop, -50.0, 2.0)) + d.err;
    error += 2.0 * drift * integral + stop * q.quad_err;
    e = d.end;
    s += step;
    n0 = nE;
    if (stop < 1.0)
      break;
    h = step * std::clamp(0.9 * std::pow(1.0 / q.over, d.smooth && !quasi ? 1.0 / 7.0 : 0.2), 0.2, 4.0);
    // A Magnus step in the drive's frame that ends relaxed onto the drive where the law pulls hard: the next step may be
    // long enough for the slow manifold (the Magnus steps would stay below pi / W).
    was_quasi = quasi;
    if (quasi)
      quasi_refused = 0;
    if (!quasi && in_drive && nE.W_abs * h < kStiffStep && ++quasi_refused > 4)
    {
      const double r = nE.Kd / nE.W_abs, wanted = 1.25 * kStiffStep / nE.W_abs;
      if (std::abs(r) < 0.5 && std::abs(std::arg(d.end * std::conj(nE.w_hat)) - std::asin(r)) <= kRelaxed &&
          wanted <= map_.longestStep())
      {
        h = std::max(h, wanted);
        was_quasi = true;   // the attempt is capped as a slow-manifold step
        quasi_refused = 0;  // and is not repeated for a few steps if it fails (it was at every step)
      }
    }
  }
  return finish(0.0);
}
}  // namespace

SlideEnd slideCoulomb(PathContext& ctx, const SlideStart& start)
{
  const int piece = ctx.addPiece(start.tau, ctx.path.length, false, start.direction);
  // The stiff collocation (coulomb_collocation.h) as far as it goes; from where it stops short, the steps here.
  SlideEnd end;
  SlideStart rest;
  rest = start;
  if (ctx.stepper == CoulombStepper::Collocation && slideCollocation(ctx, start, end, rest))
  {
    if (piece >= 0)
      ctx.out.piece[piece].end = end.tau;
    return end;
  }
  CoulombSlider slider(ctx.field, ctx.path, ctx.tolerance);
  end = slider.run(rest, ctx.path.length, &ctx);
  if (piece >= 0)
    ctx.out.piece[piece].end = end.tau;
  return end;
}

cd coulombDirectionAt(const BristleField& field, const BristlePath& path, const SlideStart& start, double tau)
{
  CoulombSlider slider(field, path, 1e-6);
  return slider.run(start, tau, nullptr).direction;
}

}  // namespace sphere_contact_estimator::path
