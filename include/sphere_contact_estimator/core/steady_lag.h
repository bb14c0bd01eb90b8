#pragma once

// STL
#include <array>

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// How far the true (transient) bristle state lags the steady state of the current inputs, when the inputs are
/// held between messages (odometry) and change at each one.
///
/// For the linear brush theory (adhering bristles, straight paths) the answer is exact: a bristle that has
/// travelled Sigma from the leading edge carries the drive of its last Sigma of travel, so a change of the
/// inputs that happened a travel delta ago still weighs, in the force, the share of the patch's memory not yet
/// renewed, g(delta) = integral (Sigma - delta)+ dA / integral Sigma dA (1 at delta = 0, 0 past 2a). The lag is
/// then |sum_j dF_j g(s - s_j)| over the steady-state changes dF_j made at travel s_j. A ramp gives about
/// (2a / 3) |dF/ds|, slow inputs next to nothing, and a step longer than the patch nothing at all; noise makes
/// large changes that the next steps soon renew. Sliding erases a bristle's memory sooner, so for the
/// limited-friction models this overestimates the lag.
class SteadyLag
{
public:
  /// @param a patch radius [m]
  explicit SteadyLag(double a) : a_(a) {}

  /// The steady forces (F_x, F_y, M_z / a, any unit) of the inputs in force during a step that then rolled
  /// `travel` [m].
  void step(const Eigen::Vector3d& steady, double travel);
  /// Forgets the history (standstill, a reset): the next step starts afresh.
  void reset();
  /// The frame turned by alpha [rad] about z: the recorded force changes turn with it.
  void rotate(double alpha);

  /// |sum_j dF_j g(s - s_j)| after the last step, in the unit of the forces given.
  double lag() const;

  /// g(delta), the share of the force memory left after a travel delta [m] (closed form on straight paths).
  double memory(double delta) const;

private:
  static constexpr int kCapacity = 256;  // changes kept: the oldest has the least weight and goes first
  double a_;
  double s_ = 0.0;  // travel so far
  bool have_ = false;
  Eigen::Vector3d last_ = Eigen::Vector3d::Zero();
  struct Change
  {
    double s;
    Eigen::Vector3d dF;
  };
  std::array<Change, kCapacity> changes_{};
  int first_ = 0, count_ = 0;  // a ring
};

}  // namespace sphere_contact_estimator
