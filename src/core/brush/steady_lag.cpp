#include "steady_lag.h"

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "pressure_law.h"
#include "sphere_contact_estimator/core/numerics/quadrature_rules.h"

namespace sphere_contact_estimator
{
namespace
{
// memorySliding's table for one pressure law, in units of a (it depends on nothing else)
using SlidingTable = std::array<double, SteadyLag::kTable + 1>;

SlidingTable slidingTable(PressureDistribution pressure)
{
  // The load on the disc (units of a) ahead of x = d - l(y) on every path, over the whole load: across the paths
  // y = Y sin(phi) (Y where the chord 2l equals d), which smooths the ends where a chord just fits, by a 32-point
  // Gauss rule on each of 4 panels (the table's values to about 1e-12, far inside the interval reading's margin)
  const PressureLaw law(pressure);
  const numerics::GaussLegendre& rule = numerics::gaussLegendre(32);
  const auto load = [&](double d) {
    const double Y = std::sqrt(std::max(0.0, 1.0 - 0.25 * d * d));
    constexpr int kPanels = 4;
    const double h = boost::math::double_constants::pi / kPanels;
    double sum = 0.0;
    for (int k = 0; k < kPanels; ++k)
      for (int i = 0; i < rule.m; ++i)
      {
        const double phi = -0.5 * boost::math::double_constants::pi + h * (k + 0.5 * (rule.x[i] + 1.0));
        const double y = Y * std::sin(phi), c = std::sqrt(std::max(0.0, 1.0 - y * y));
        sum += 0.5 * h * rule.w[i] * Y * std::cos(phi) * law.chordIntegralAfter(c, d);
      }
    return sum;
  };
  SlidingTable table;
  const double total = load(0.0);
  for (int k = 0; k <= SteadyLag::kTable; ++k)
    table[k] = k == 0 ? 1.0 : std::clamp(load(2.0 * k / SteadyLag::kTable) / total, 0.0, 1.0);
  return table;
}

// Built once per law (about a millisecond each), when a model of that law is first made: not at every model's
// construction (each reconfiguration), nor for the laws nobody uses (each static is initialised only where reached).
const double* slidingTableOf(PressureDistribution pressure)
{
  switch (pressure)
  {
    case PressureDistribution::Hertzian:
    {
      static const SlidingTable table = slidingTable(pressure);
      return table.data();
    }
    case PressureDistribution::Uniform:
    {
      static const SlidingTable table = slidingTable(pressure);
      return table.data();
    }
    default:
    {
      static const SlidingTable table = slidingTable(PressureDistribution::Parabolic);
      return table.data();
    }
  }
}
}  // namespace

SteadyLag::SteadyLag(double longest, PressureDistribution pressure)
  : sliding_(slidingTableOf(pressure)), a_(0.5 * longest)
{
}

double SteadyLag::memorySliding(double delta) const
{
  const double d = delta / a_;
  if (!(d > 0.0))
    return 1.0;
  if (d >= 2.0)
    return 0.0;
  return sliding_[static_cast<int>(d * (0.5 * kTable))];
}

double SteadyLag::memory(double delta) const
{
  // Straight paths across the disc (units of a): a path at y runs 2l = 2 sqrt(1 - y^2) from the leading edge, a
  // bristle at travel S has x = l - S, and the part of its deflection older than d is the drive's integral over
  // its first S - d of travel. Of the linear theory's kernels the spin's drive on F_y (phi x, weighted 1) and the
  // lateral slip's on M_z (1, weighted x) forget slowest: the old share int (l T^2/2 - T^3/6) dy / int 2l^3/3 dy
  // with T = 2l - d, i.e. int_{-Y}^{Y} (4l^3 - 3l d^2 + d^3) / 6 dy / (pi / 4), Y where 2l = d. The slip's drive on
  // F (1, weighted 1) keeps less, int (2l - d)^2 dy / int 4l^2 dy (0.50 against 0.80 at d = 0.5): taking the
  // slowest for every force keeps the lag an upper bound for any mix of slip and spin changes.
  const double d = delta / a_;
  if (d <= 0.0)
    return 1.0;
  if (d >= 2.0)
    return 0.0;
  const double Y = std::sqrt(1.0 - 0.25 * d * d), half = 0.5 * d;  // sqrt(1 - Y^2) = d / 2
  const double I1 = Y * half + std::asin(Y);                                       // int_{-Y}^{Y} l dy
  const double I3 = 0.5 * Y * half * half * half + 0.75 * (Y * half + std::asin(Y));  // int_{-Y}^{Y} l^3 dy
  const double old = (4.0 * I3 - 3.0 * d * d * I1 + 2.0 * d * d * d * Y) / 6.0;
  return std::clamp(old / (0.25 * boost::math::double_constants::pi), 0.0, 1.0);
}

double SteadyLag::memorySlip(double delta) const
{
  // a change of the slips drives every bristle alike: the old share of a path of 2l is (2l - d)^2 / (2l)^2 of its
  // force; over y in (-Y, Y), Y where 2l = d: int (2l - d)^2 dy = 8Y - 8Y^3/3 - 4d (Y d/2 + asin Y) + 2 d^2 Y,
  // against int 4 l^2 dy = 16/3
  const double d = delta / a_;
  if (d <= 0.0)
    return 1.0;
  if (d >= 2.0)
    return 0.0;
  const double Y = std::sqrt(1.0 - 0.25 * d * d);
  const double old = 8.0 * Y - 8.0 * Y * Y * Y / 3.0 - 4.0 * d * (0.5 * d * Y + std::asin(Y)) + 2.0 * d * d * Y;
  return std::clamp(old / (16.0 / 3.0), 0.0, 1.0);
}

void SteadyLag::step(const Eigen::Vector3d& slip, const Eigen::Vector3d& spin, bool split, double spin_share,
                     double travel, double held)
{
  if (have_)
  {
    // the state still holds part of the old steady forces
    Change c{ s_, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1.0 };
    if (split && last_split_)
    {
      c.slip = last_slip_ - slip;
      c.spin = last_spin_ - spin;
    }
    else
    {
      c.other = (last_slip_ + last_spin_) - (slip + spin);
      c.spin_share = std::clamp(spin_share, 0.0, 1.0);
    }
    if (c.slip.squaredNorm() + c.spin.squaredNorm() + c.other.squaredNorm() > 0.0)
    {
      if (count_ == kCapacity)
      {
        first_ = (first_ + 1) % kCapacity;
        --count_;
      }
      changes_[(first_ + count_) % kCapacity] = c;
      ++count_;
    }
  }
  last_slip_ = slip;
  last_spin_ = spin;
  last_split_ = split;
  have_ = true;
  s_ += travel;
  if (held_count_ == kCapacity)
  {
    held_first_ = (held_first_ + 1) % kCapacity;
    --held_count_;
  }
  held_[(held_first_ + held_count_) % kCapacity] = { s_, held };
  ++held_count_;
  // changes older than the longest memory (2a) weigh nothing; a step that ended that long ago is forgotten
  while (count_ > 0 && s_ - changes_[first_].s >= 2.0 * a_)
  {
    first_ = (first_ + 1) % kCapacity;
    --count_;
  }
  while (held_count_ > 1 && s_ - held_[held_first_].s >= 2.0 * a_)
  {
    held_first_ = (held_first_ + 1) % kCapacity;
    --held_count_;
  }
}

double SteadyLag::largestHeld() const
{
  double largest = 0.0;
  for (int i = 0; i < held_count_; ++i)
    largest = std::max(largest, held_[(held_first_ + i) % kCapacity].held);
  return largest;
}

void SteadyLag::reset()
{
  have_ = false;
  count_ = 0;
  first_ = 0;
  held_count_ = 0;
  held_first_ = 0;
  s_ = 0.0;
}

void SteadyLag::rotate(double alpha)
{
  // F_x, F_y in axes turned by alpha (x' = R(-alpha) x); M_z is invariant
  const double c = std::cos(alpha), s = std::sin(alpha);
  const auto turn = [c, s](Eigen::Vector3d& v) { v = Eigen::Vector3d(c * v.x() + s * v.y(), -s * v.x() + c * v.y(), v.z()); };
  turn(last_slip_);
  turn(last_spin_);
  for (int i = 0; i < count_; ++i)
  {
    Change& ch = changes_[(first_ + i) % kCapacity];
    turn(ch.slip);
    turn(ch.spin);
    turn(ch.other);
  }
}

double SteadyLag::lag() const
{
  // The steady model's changes (not split) forget at a rate between the slips' kernel and the slowest one: F's kernel
  // for a change of both drives, and at least the load's share, which a sliding state keeps (the class's comment).
  // Taking the slowest as an upper envelope bounds changes of one sign, not noise that alternates in sign, whose
  // slow kernel's sum can cancel where the state's has not. For a true kernel that mixes the two ends, the sum is
  // affine in the mixture's weight, so its size is largest at one of the ends: both ends are summed and the larger
  // taken, per component.
  Eigen::Vector3d slow_end = Eigen::Vector3d::Zero(), slip_end = Eigen::Vector3d::Zero();
  for (int i = 0; i < count_; ++i)
  {
    const Change& c = changes_[(first_ + i) % kCapacity];
    const double slow = memory(s_ - c.s), slip = memorySlip(s_ - c.s);
    const double sliding = memorySliding(s_ - c.s);
    const double mixed = std::max(slip + c.spin_share * (slow - slip), sliding), slowest = std::max(slow, sliding);
    const Eigen::Vector3d split =
        Eigen::Vector3d(slip, slip, slow).cwiseProduct(c.slip) + Eigen::Vector3d(slow, slow, slip).cwiseProduct(c.spin);
    slow_end += split + Eigen::Vector3d(mixed, mixed, slowest).cwiseProduct(c.other);
    slip_end += split + slip * c.other;
  }
  return slow_end.cwiseAbs().cwiseMax(slip_end.cwiseAbs()).maxCoeff();
}

}  // namespace sphere_contact_estimator
