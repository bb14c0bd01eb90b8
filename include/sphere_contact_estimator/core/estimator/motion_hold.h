#pragma once

// Eigen
#include <Eigen/Core>

// Package
#include "sphere_contact_estimator/core/estimator/motion_noise.h"

namespace sphere_contact_estimator
{
/// The motion held back from the bristles while it is within the odometry's noise (hold_within_noise): a zero-velocity
/// update, as inertial navigation applies to a vehicle at rest.
///
/// Why: the bristles' state is a nonlinear function of the path their roots and tips travel. A parked robot's odometry
/// is its noise, and integrated message by message it moves the bristles back and forth; where a bristle lies on its
/// bound (after spinning in place, nearly all of them) each push outward is capped and each push inward is kept, so the
/// noise ratchets the deflection down: along the recorded manoeuvre (100 Hz, four noise seeds) the parked robot's M_z
/// fell from the -0.210 N m it keeps without noise to -0.02..-0.05 N m within 3 s, outside the walk's +-2 sigma band.
/// Held, the state stays where the motion left it, and the walk (StandstillCovariance) still says how far the noise
/// could have moved it.
///
/// Each held message's twist times its dt is summed with its covariance (S dt^2, messages independent, as a twist
/// covariance per message says), and the sum is applied as one step of its mean twist over the held time as soon as it
/// leaves the noise as a whole (a creep too slow for any one message to show: its sum grows as the time, the noise's as
/// its square root). The bristles respond to the path's geometry, not its pace (eq. 1 is linear in the velocities), so
/// the held motion arrives whole, along a straight path instead of the noise's zigzag. A message that leaves the noise
/// on its own (the robot moves off) advances the state alone, and the sum held before it, still within its noise, is
/// let go as the noise it was judged to be: for a robot that was at rest that is exact, for one that crept it loses
/// less than the sum's noise bound, and the message keeps one update (a second one, for the sum, had doubled that
/// message's work and left auto short of its budget for seconds along data/manoeuvre.bag).
///
/// The estimator offers it only the messages of a parked patch (V_r and the drive |V_s| + |omega_z| a below
/// standstill_speed): a covariance declared far too large then holds no robot that moves.
///
/// "Leaves the noise" is kHoldWithinNoise, not the flag's kMotionWithinNoise: the flag's 99.9 % point is passed by a
/// parked robot's noise at one message in a thousand, and each such message would release the held sum, a step of
/// the noise's size at once (along data/manoeuvre.bag's park, M_z fell from -0.209 to -0.081 N m in one message).
class MotionHold
{
public:
  /// sqrt of chi2_5's point passed with probability 1.7e-9: a parked robot's message about once in seven days at 1 kHz.
  /// Its sum, a random walk normalised by its own spread, crossed it in none of 2 000 simulated walks of 3 000 messages
  /// (the flag's 4.53: 4.4 %). Moving, a twist of 7 standard deviations in any one component passes it; at the demo's
  /// noise (5 mm/s on V_C) that is 35 mm/s, below the standstill speed, and a slower steady creep within a few messages.
  static constexpr double kHoldWithinNoise = 7.0;

  enum class Decision
  {
    Advance,  ///< advance the state by this message as usual (nothing is held: what was, within its noise, let go)
    Hold,     ///< this message's motion is within the noise, and the sum with it too: held, the state not advanced
    Release   ///< this message joined the held motion, whose sum left the noise: the state advanced by the sum alone
              ///< (meanTwist() over duration()), then clear()
  };

  /// Offers one message: its used twist x (ROS ground frame), covariance S, time step dt [s], and its own motionToNoise
  /// (negative: unknown, as without a usable covariance: nothing is held). Messages that do not advance the clock
  /// (dt <= 0) change nothing (Advance). After a Release, meanTwist() and duration() describe the motion to apply until
  /// clear().
  Decision offer(const UsedTwist& x, const Eigen::Matrix<double, 5, 5>& S, double dt, double motion_to_noise);

  /// The held motion's mean twist [m/s, rad/s] and its time [s] (zero when nothing is held).
  UsedTwist meanTwist() const { return duration_ > 0.0 ? UsedTwist(displacement_ / duration_) : UsedTwist::Zero(); }
  double duration() const { return duration_; }
  bool empty() const { return duration_ == 0.0; }
  /// The held sum's distance from rest in units of its own noise (0 when nothing is held).
  double motionToNoise() const;
  /// Forgets the held motion (after it was applied, a reset, a gap, new settings).
  void clear();

private:
  UsedTwist displacement_ = UsedTwist::Zero();                                 // sum of x dt
  Eigen::Matrix<double, 5, 5> covariance_ = Eigen::Matrix<double, 5, 5>::Zero();  // sum of S dt^2
  double duration_ = 0.0;                                                     // sum of dt
};

}  // namespace sphere_contact_estimator
