#include "sphere_contact_estimator/core/brush/brush_transient.h"

// The transient model's forces from its lattice: each bristle's share of the patch (cellSum, with the trailing layer
// at the rim), the sums over the lattice with the rows' correction, and their error estimate (sums).

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// The brush library's private rooms
#include "friction_cap.h"
#include "transient_rows.h"

namespace sphere_contact_estimator
{
Eigen::Vector2d BrushTransient::headingAt(const Eigen::Vector2d& x) const
{
  const Eigen::Vector2d v = Eigen::Vector2d(-omega_gamma_ * x.y(), omega_gamma_ * x.x()) - V_r_;
  return v.squaredNorm() > 0.0 ? v.normalized() : Eigen::Vector2d::Zero();
}

BrushTransient::Motion BrushTransient::motionAt(const Eigen::Vector2d& x, const Eigen::Vector2d& e) const
{
  // along this bristle's motion: how far the patch edge lies ahead and behind, and which lattice neighbour is upstream
  // (the lattice axis nearest the motion)
  Motion m;
  m.e = e;
  if (e.squaredNorm() > 0.0)
  {
    const double b = x.dot(e), c = x.squaredNorm() - p_.a * p_.a, root = std::sqrt(std::max(0.0, b * b - c));
    m.ahead = -b + root;
    m.behind = b + root;
    const Eigen::Vector2d l = R_.transpose() * e;  // the motion in lattice axes
    if (std::abs(l.x()) >= std::abs(l.y()))
      m.di = l.x() > 0.0 ? -1 : 1;
    else
      m.dj = l.y() > 0.0 ? -1 : 1;
  }
  return m;
}

Eigen::Vector2d BrushTransient::cellSum(int i, int j, const Motion& m, int k, double& weight) const
{
  // the cell, a strip of length h along the motion (2h on a sub-lattice): the part past the edge (or short of it), and
  // the part upstream of the onset of sliding, which still holds the deflection before the jump
  const std::size_t p = index(i, j);
  const Eigen::Vector2d& u = u_[p];
  const bool slides = sliding_[p];
  const double h = k == 0 ? h_ : 2.0 * h_;
  weight = 1.0;
  if (m.ahead <= h)
    weight += m.ahead / h - 0.5;
  if (m.behind <= h)
    weight += m.behind / h - 0.5;
  Eigen::Vector2d cell = weight * u;
  // a jump in space (not in time, as at standstill): the upstream neighbour on this lattice still adheres
  const int step = k == 0 ? 1 : 2, ui = i + step * m.di, uj = j + step * m.dj;
  if (slides && slip_travel_[p] < h && (m.di != 0 || m.dj != 0) && ui >= 0 && uj >= 0 && ui < w_ && uj < w_ &&
      inside_[index(ui, uj)] && !sliding_[index(ui, uj)])
    cell += (0.5 - slip_travel_[p] / h) * jump_[p];
  // the first cell from the leading edge, sliding: between its onset and the edge the bristle adhered, growing from 0
  // to the deflection before the jump, u + jump (half of it on average) instead of u. Unresolved, that ramp was a
  // first-order error where the adhesion zone is shorter than a spacing (stiff bristles; with the uniform pressure the
  // bound does not vanish at the edge: 0.1 % of mu F_z at resolution 128)
  else if (slides && m.behind <= h && slip_travel_[p] < m.behind)
    cell += (m.behind - slip_travel_[p]) / h * 0.5 * (jump_[p] - u);
  // the last cell before the trailing edge, adhering: where the bound falls below |u| within it, the bristle slides on
  // it (trailingLayer). That layer is (|u| / c)^m a / 2 wide (f^2 = t^m, c the bound at the centre); where it is
  // narrower than a spacing its error is one no spacing above its width reduces, and the sub-lattices, which make the
  // same one, did not see it: with the Hertzian pressure sweep seed 9018's robot (a = 7.8 mm, a layer of 40 um) stood
  // 7e-5 of mu F_z off the steady forces at every resolution from 128 to 400, up to 1.4 times the estimate; with the
  // parabolic one a robot of slips of 6e-4 (a layer of 2 um) 0.5 % of its forces off at every resolution from 64 to 512,
  // up to 1.6 times the estimate. (A sliding bristle there is on the bound, as q_z: the sum's normalisation to the rows'
  // load corrects its cell.)
  if (!slides && m.ahead <= h)
    cell += trailingLayer(position(i, j), u, m) / h;
  return cell;
}

Eigen::Vector2d BrushTransient::trailingLayer(const Eigen::Vector2d& x, const Eigen::Vector2d& u, const Motion& m) const
{
  const double un = u.norm();
  if (p_.pressure == PressureDistribution::Uniform || !(un > 0.0) || !(m.ahead > 0.0))
    return Eigen::Vector2d::Zero();
  const bool parabolic = p_.pressure == PressureDistribution::Parabolic;
  // along the motion back from the edge x_e = x + ahead e, at distance d: t = 1 - |x_e - d e|^2 / a^2 = g1 d + g2 d^2
  const double inv_a2 = 1.0 / (p_.a * p_.a);
  const Eigen::Vector2d x_e = x + m.ahead * m.e;
  const double g1 = 2.0 * x_e.dot(m.e) * inv_a2, g2 = -inv_a2;
  const double c = p_.mu / p_.k * p_.qz(0.0);  // the bound at the centre
  if (!(g1 > 0.0) || !(c > 0.0))
    return Eigen::Vector2d::Zero();
  // the layer: from the edge to where the bound c f(t) is |u| (t = (|u| / c)^(2 / m)), at most to the bristle (the
  // deflection taken as u throughout: its growth over a spacing is the sum's own first-order error)
  const double t_u = parabolic ? un / c : (un / c) * (un / c);
  double d = m.ahead;
  const double disc = g1 * g1 + 4.0 * g2 * t_u;
  if (disc >= 0.0)
    d = std::min(d, 2.0 * t_u / (g1 + std::sqrt(disc)));
  // the bound's integral over it: parabolic exactly; Hertzian with d' = d v^2 (its square root at the edge becomes
  // smooth), c d^1.5 2 int_0^1 v^2 sqrt(g1 + g2 d v^2) dv by Gauss-Legendre's five points
  double integral = c * d * d * (0.5 * g1 + g2 * d / 3.0);
  if (!parabolic)
  {
    static constexpr double kNodes[5] = { 0.04691007703066800, 0.23076534494715845, 0.5, 0.76923465505284155,
                                          0.95308992296933200 };
    static constexpr double kWeights[5] = { 0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                            0.23931433524968324, 0.11846344252809454 };
    double sum = 0.0;
    for (int n = 0; n < 5; ++n)
    {
      const double v2 = kNodes[n] * kNodes[n];
      sum += kWeights[n] * v2 * std::sqrt(std::max(0.0, g1 + g2 * d * v2));
    }
    integral = 2.0 * c * d * std::sqrt(d) * sum;
  }
  // there the bristle lies on the bound: along u (eq. 4b's direction is continuous at the onset and barely turns in so
  // thin a layer) or, under the rigid law, along the drive
  Eigen::Vector2d e = u / un;
  if (p_.sliding_law == SlidingLaw::Rigid && have_last_kin_)
  {
    const Eigen::Vector2d w(-last_kin_.V_s.x() + last_kin_.omega_z * x_e.y(),
                            -last_kin_.V_s.y() - last_kin_.omega_z * x_e.x());
    if (w.squaredNorm() > 0.0)
      e = w.normalized();
  }
  // The layer reaches the bristle as it nears its bound, where it is the sliding one's case, left to the normalisation
  // as theirs. Parabolic, the correction fades linearly to that (in full, the default robot's cells next to the edge,
  // most of them near their bound, moved the sub-lattices' sums apart: the recorded manoeuvre's flags rose by half);
  // Hertzian, in full (faded, half of seed 9018's error stayed, 0.8 of the estimate at resolution 448 and rising)
  const double share = parabolic ? std::max(0.0, 1.0 - d / m.ahead) : 1.0;
  return share * (integral * e - d * u);
}

BrushForces BrushTransient::forces() const
{
  if (forces_kept_)
    return kept_forces_;
  double fixed = 0.0, spread = 0.0;
  BrushForces f = sums(fixed, spread);
  f.error_estimate = estimate(fixed, spread) + cutShortError();
  return f;
}

void BrushTransient::gather(LatticeSums& g) const
{
  // the cells that differ between the lattice and its sub-lattices (near the edge or an onset) by lattice, into g; the
  // plain cells, the same on both, by sub-lattice only (the full lattice's are their sum)
  Eigen::Vector2d F_plain[5];
  double M_z_plain[5] = {}, load_plain[5] = {};
  int count_plain[5] = {};
  for (int k = 0; k < 5; ++k)
  {
    g.F[k].setZero();
    F_plain[k].setZero();
  }
  const FrictionCap cap(p_);
  const double mu_over_k = p_.mu / p_.k;
  // Whatever the motion, a bristle within a - 2h of the centre lies further than a sub-lattice cell (2h) from the edge
  // ahead and behind (weight 1, no ramp from the edge); the upstream neighbour matters only to a bristle that slid less
  // than that far: elsewhere the motion is not needed.
  const double inner = p_.a - 2.0 * h_, inner2 = inner > 0.0 ? inner * inner : -1.0;
  const Eigen::Vector2d along = rowStep();
  const bool turning = omega_gamma_ != 0.0;
  const Eigen::Vector2d heading = turning ? Eigen::Vector2d::Zero() : headingAt(Eigen::Vector2d::Zero());
  for (int j = 0; j < w_; ++j)
  {
    const Eigen::Vector2d first = rowStart(j);
    const std::size_t row = index(0, j);
    for (int i = 0; i < w_; ++i)
    {
      const std::size_t p = row + i;
      if (!inside_[p])
        continue;
      const Eigen::Vector2d x = first + i * along, &u = u_[p];
      const bool slides = sliding_[p];
      g.sliding += slides;
      const double r2 = x.squaredNorm(), q_z = cap.qz(r2);
      const double bound = mu_over_k * q_z;
      if (slides)
        g.utilisation2 = std::max(g.utilisation2, 1.0);
      else if (bound > 0.0)
        g.utilisation2 = std::max(g.utilisation2, u.squaredNorm() / (bound * bound));
      // plain: cellSum's weight is 1 and its cell u on both lattices, and the motion is not needed. Inside a - 2h only an
      // onset's jump changes the cell: one that did not jump (eq. 4b's are continuous) is plain however lately it began
      // to slide (spinning in place or parked a message rolls micrometres, and the bristles stayed "lately" for good)
      const bool plain = !(r2 > inner2 || (slides && slip_travel_[p] < 2.0 * h_ && jump_[p].squaredNorm() > 0.0));
      const int sub = 1 + (i & 1) + 2 * (j & 1);
      if (plain)
      {
        F_plain[sub] += u;
        M_z_plain[sub] += x.x() * u.y() - x.y() * u.x();
        load_plain[sub] += q_z;
        g.step_error += step_error_[p];
        ++count_plain[sub];
        continue;
      }
      const Motion motion = motionAt(x, turning ? headingAt(x) : heading);
      for (int k : { 0, sub })
      {
        double weight = 1.0;
        const Eigen::Vector2d cell = cellSum(i, j, motion, k, weight);
        g.F[k] += cell;
        g.M_z[k] += x.x() * cell.y() - x.y() * cell.x();
        g.load[k] += weight * q_z;
        if (k == 0)
          g.step_error += weight * step_error_[p];
        ++g.count[k];
      }
    }
  }
  for (int k = 1; k <= 4; ++k)
  {
    g.F[0] += F_plain[k];
    g.M_z[0] += M_z_plain[k];
    g.load[0] += load_plain[k];
    g.count[0] += count_plain[k];
    g.F[k] += F_plain[k];
    g.M_z[k] += M_z_plain[k];
    g.load[k] += load_plain[k];
    g.count[k] += count_plain[k];
  }
}

bool BrushTransient::adhesionResponse(AdhesionResponse& response, long& work, double band) const
{
  // F = k sum u dA, M_z = k sum (x_x u_y - x_y u_x) dA (sums()); an adhering bristle's u' = w with
  // dw / d(V_s,x, V_s,y, omega_z) = [[-1, 0, x_y], [0, -1, -x_x]] = -B^T, B = [I; (-x_y, x_x)] (eq. 1, drive()), so that
  // it moves (F_x, F_y, M_z) by -B B^T; dA as the sums weigh the cells. One held by its bound (sliding, or adhering
  // within `band` of it) moves only along it, by the drive's part across its normal n = u / |u| (eq. 4b on the bound):
  // -B (I - n n^T) B^T = -B B^T + c c^T with c = B n.
  const FrictionCap cap(p_);
  double load = 0.0, S0 = 0.0, S2 = 0.0;
  Eigen::Vector2d S1 = Eigen::Vector2d::Zero(), F = Eigen::Vector2d::Zero();
  Eigen::Matrix3d held = Eigen::Matrix3d::Zero();  // sum of c c^T
  // the roll's share, per metre along each direction e_j: the adhering field moves with the roots, its moment by
  // e_j x F (a sliding bristle stays on the bound the patch's pressure sets: its force stays put); and the bristles
  // within a spacing of the rim each leave with the chance (e_j . n)+ / h, taking (u, x x u) with them
  constexpr int kN = AdhesionResponse::kDirections;
  double lost_x[kN] = {}, lost_y[kN] = {}, lost_m[kN] = {};  // (plain arrays: the loop below vectorises)
  double e_x[kN], e_y[kN];
  for (int j = 0; j < kN; ++j)
  {
    e_x[j] = AdhesionResponse::directions()[j].x();
    e_y[j] = AdhesionResponse::directions()[j].y();
  }
  const double rim_band = p_.a - h_, mu_over_k = p_.mu / p_.k;
  long rim = 0;  // points in the band, each about 10 units more (callgrind: about 470 instructions, 32 directions)
  forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool sliding) {
    const double r2 = x.squaredNorm();
    load += cap.qz(r2);
    if (r2 > rim_band * rim_band)
    {
      ++rim;
      const double m = x.x() * u.y() - x.y() * u.x();
      const double r = std::sqrt(r2), n_x = x.x() / r, n_y = x.y() / r;
      for (int j = 0; j < kN; ++j)
      {
        const double out = std::max(0.0, n_x * e_x[j] + n_y * e_y[j]);
        lost_x[j] += out * u.x();
        lost_y[j] += out * u.y();
        lost_m[j] += out * m;
      }
    }
    if (!sliding)
      F += u;  // (the roll moves the adhering field with the roots)
    const double un = u.norm(), bound = mu_over_k * cap.qz(r2);
    // (undeformed inside the patch, as a lattice no motion has reached yet, or one whose noise was held: it adheres, and
    // the noise first moves it with the drive, in whichever direction; a band wider than its bound does not hold it)
    if ((sliding || (band > 0.0 && un > bound - band)) && !(un == 0.0 && bound > 0.0))
    {
      // held by its bound (the noise's reflected walk reaches it within the band, StandstillCovariance::band)
      if (!(un > 0.0))
        return;  // at the rim, with no bound: nothing moves it
      const Eigen::Vector2d n = u / un;
      const Eigen::Vector3d c(n.x(), n.y(), x.x() * n.y() - x.y() * n.x());
      held += c * c.transpose();
    }
    S0 += 1.0;
    S1 += x;
    S2 += r2;
  });
  work = sumsWork() + rim * 10;
  response = AdhesionResponse{};
  if (!(load > 0.0))
    return true;  // no load: no forces to move
  const double kdA = p_.k * rows_->load(0, p_.F_z) / load;
  response.drive << -S0, 0.0, S1.y(),  //
      0.0, -S0, -S1.x(),               //
      S1.y(), -S1.x(), -S2;
  response.drive = kdA * (response.drive + held);
  for (int j = 0; j < kN; ++j)
    response.roll.col(j) = kdA * (Eigen::Vector3d(0.0, 0.0, e_x[j] * F.y() - e_y[j] * F.x()) -
                                  Eigen::Vector3d(lost_x[j], lost_y[j], lost_m[j]) / h_);
  return true;
}

BrushForces BrushTransient::sums(double& fixed, double& spread) const
{
  fixed = spread = 0.0;
  // The lattice sum, and the same over each of the four sub-lattices of twice the spacing (the parities of
  // the lattice indices): how far those move from the full sum bounds the error. An error C h^p with p >= 1
  // makes the difference (2^p - 1) C h^p, at least the error itself; kSpreadFactor times it covers the irregular
  // part that the cells cut by the patch edge and by the onsets add (measured over noisy histories at random points,
  // test_brush_transient: without a factor the estimate fell short at 0.2-0.5 % of them, by up to 2.7x).
  BrushForces f;
  LatticeSums g;
  gather(g);
  const auto& F = g.F;
  const auto& M_z = g.M_z;
  const auto& load = g.load;
  const auto& count = g.count;
  if (count[0] == 0)
    return f;
  // Cell weight normalised so that the lattice sum of q_z is F_z: every bristle obeys |q| <= mu q_z, so
  // |F_t| <= mu F_z then holds exactly. Where the rows are corrected across (TransientRows), the sum of q_z is
  // normalised to the same rows' exact integrals of q_z instead: the normalisation then corrects the cells along the
  // rows (cut by the edge) and leaves across them to the correction, which would otherwise count the midpoint rule's
  // error across the rows twice (0.1 % of mu F_z at resolution 128 with the uniform pressure). Without load, the
  // patch area over the bristle count.
  const auto weight = [&](int k) {
    const double total = rows_->load(k, p_.F_z);
    return load[k] > 0.0 ? total / load[k] : boost::math::double_constants::pi * p_.a * p_.a / std::max(count[k], 1);
  };
  const auto sum = [&](int k) {
    BrushForces g;
    const double dA = weight(k);
    g.F_x = p_.k * F[k].x() * dA;
    g.F_y = p_.k * F[k].y() * dA;
    g.M_z = p_.k * M_z[k] * dA;
    const Eigen::Vector3d c = rows_->correction(k, p_.a);
    g.F_x += c.x();
    g.F_y += c.y();
    g.M_z += c.z();
    return g;
  };
  BrushForces full = sum(0);
  // the corrections may carry the sum past mu F_z, which the exact answer never passes: the nearest point on that
  // (convex) circle is never further from it
  const double norm = std::hypot(full.F_x, full.F_y), limit = p_.mu * p_.F_z;
  if (norm > limit)
  {
    full.F_x *= limit / norm;
    full.F_y *= limit / norm;
  }
  f.F_x = full.F_x;
  f.F_y = full.F_y;
  f.M_z = full.M_z;
  f.sliding_fraction = static_cast<double>(g.sliding) / count[0];
  f.max_utilisation = std::sqrt(g.utilisation2);
  const double scale = p_.mu * p_.F_z;
  fixed = streak_estimate_;
  if (scale > 0.0)
    fixed += p_.k * g.step_error * weight(0) / scale;
  fixed += rows_->error(p_.pressure);
  spread = 0.0;
  if (scale > 0.0)
    for (int k = 1; k <= 4; ++k)
    {
      const BrushForces g = count[k] > 0 ? sum(k) : BrushForces{};
      spread = std::max(spread, kSpreadFactor *
                                          std::max({ std::abs(g.F_x - full.F_x), std::abs(g.F_y - full.F_y),
                                                     std::abs(g.M_z - full.M_z) / p_.a }) / scale);
    }
  f.error_estimate = fixed + spread;
  return f;
}

}  // namespace sphere_contact_estimator
