#pragma once

// STL
#include <algorithm>
#include <array>

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/brush/brush_parameters.h"

namespace sphere_contact_estimator
{
/// How far the true (transient) bristle state lags the steady state of the current inputs, when the inputs are
/// held between messages (odometry) and change at each one.
///
/// For the linear brush theory (adhering bristles, straight paths) the answer is exact: a bristle that has
/// travelled S from the leading edge carries the drive of its last S of travel, so a change of the inputs that
/// happened a travel delta ago still weighs, in the force, the share of the patch's memory not yet renewed,
/// g(delta) (1 at delta = 0, 0 past 2a). The share depends on which drive and which force (memory()); the slowest
/// of them is used for all, so the lag |sum_j dF_j g(s - s_j)| over the steady-state changes dF_j made at travel
/// s_j bounds the true one for any mix of slip and spin changes (a spin ramp alone: exact). A ramp gives about
/// 0.91 a |dF/ds| (the integral of g), slow inputs next to nothing, and a step longer than the patch nothing at all; noise
/// makes large changes that the next steps soon renew. Under limited friction sliding caps the deflection of the rear
/// bristles at the bound and so moves the force towards the leading edge, where it stays longest: a change of the
/// slips from a partly sliding state keeps more than the linear theory's share, up to the share of the load on the
/// bristles that entered more than delta ago (memorySliding, the fully sliding state's: along a path the sliding
/// state's deflection over the linear one's grows towards the front, so the load's distribution dominates). Changes of
/// the steady model (not split) forget at a rate between the slips' kernel (an adhering state) and a slow end that
/// keeps at least that share. When the changes alternate in sign (noise) the slow end's sum may cancel where a faster
/// kernel's does not (sweep seed 1073 at 1 kHz: 1.1x short), so lag() sums both ends and takes the larger, which
/// bounds every mixture of the two (its sum is affine in the mixture's weight).
class SteadyLag
{
public:
  /// @param longest the longest straight bristle path through the patch, 2a [m] (Sect. 3). On the arcs of
  ///        Sect. 4 the caller shortens each step's travel by the arcs' stretch over their chords.
  /// @param pressure the pressure law whose load memorySliding follows
  explicit SteadyLag(double longest, PressureDistribution pressure = PressureDistribution::Parabolic);

  /// The steady forces (F_x, F_y, M_z / a, any unit) of the inputs in force during a step that then rolled
  /// `travel` [m]: the parts the slips and the spin drive, when `split` (the linear theory, whose kernels forget at
  /// different rates, memory()), else their sum in `slip` with `spin` zero, and `spin_share` in [0, 1], how much
  /// of the change since the last step the spin made (in the linear theory's forces): F's kernel then runs from
  /// the slip's to the slowest; and a quantity `held` of those inputs whose largest value over the memory is
  /// wanted.
  void step(const Eigen::Vector3d& slip, const Eigen::Vector3d& spin, bool split, double spin_share, double travel,
            double held = 0.0);
  /// Forgets the history (standstill, a reset): the next step starts afresh.
  void reset();
  /// The frame turned by alpha [rad] about z: the recorded force changes turn with it.
  void rotate(double alpha);

  /// |sum_j dF_j g(s - s_j)| (the largest component) after the last step, in the unit of the forces given.
  double lag() const;

  /// The largest `held` over the steps the patch still remembers (ended less than the longest path ago; at
  /// least the last step).
  double largestHeld() const;

  /// The share of the force memory left after a travel delta [m], for straight paths (closed forms): of a
  /// change of the slips in F_x and F_y (memorySlip), and the slowest of the linear theory's kernels, that of a
  /// change of the spin in F_y or of the lateral slip in M_z (memory).
  double memory(double delta) const;
  double memorySlip(double delta) const;
  /// The share of the load q_z on bristles that entered more than delta [m] ago (straight paths), from a table of
  /// kTable intervals read at the interval's start (the share falls with delta: never below it). For the parabolic
  /// law it is memory(delta): the spin's linear drive deflects a bristle as the parabolic bound.
  double memorySliding(double delta) const;
  /// The slowest renewal of any state: max(memory, memorySliding).
  double slowest(double delta) const { return std::max(memory(delta), memorySliding(delta)); }

  static constexpr int kTable = 512;  // intervals of memorySliding's table over delta in [0, 2a]

private:
  static constexpr int kCapacity = 256;  // changes kept: the oldest has the least weight and goes first
  const double* sliding_;                 // memorySliding's table of this pressure law (kTable + 1 values, shared)
  double a_;  // half the longest path: the memory is that of a disc of this radius
  double s_ = 0.0;  // travel so far
  bool have_ = false;
  Eigen::Vector3d last_slip_ = Eigen::Vector3d::Zero(), last_spin_ = Eigen::Vector3d::Zero();
  bool last_split_ = false;
  struct Change
  {
    double s;
    Eigen::Vector3d slip, spin, other;  // weighed by (slip, slip, slowest), (slowest, slowest, slip), (mixed, mixed, slowest)
    double spin_share;                  // of `other`: F's kernel from the slip's (0) to the slowest (1)
  };
  std::array<Change, kCapacity> changes_{};
  int first_ = 0, count_ = 0;  // a ring
  struct Held
  {
    double s;  // travel at the step's end
    double held;
  };
  std::array<Held, kCapacity> held_{};
  int held_first_ = 0, held_count_ = 0;  // a ring
};

}  // namespace sphere_contact_estimator
