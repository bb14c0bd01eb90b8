#include "sphere_contact_estimator/core/estimator/motion_hold.h"

namespace sphere_contact_estimator
{
MotionHold::Decision MotionHold::offer(const UsedTwist& x, const Eigen::Matrix<double, 5, 5>& S, double dt,
                                       double motion_to_noise)
{
  if (!(dt > 0.0))
    return Decision::Advance;  // nothing moves (a duplicate or jittered stamp): the held motion waits
  const bool within = motion_to_noise >= 0.0 && motion_to_noise <= kHoldWithinNoise;
  if (!within)
  {
    clear();  // a motion of its own (or no noise to judge it by): the sum before it was the noise it was judged to be
    return Decision::Advance;
  }
  displacement_ += dt * x;
  covariance_ += (dt * dt) * S;
  duration_ += dt;
  // the sum against its own noise: a creep leaves it after enough messages even where no message does
  const double sum = motionToNoise();
  return sum >= 0.0 && sum <= kHoldWithinNoise ? Decision::Hold : Decision::Release;
}

double MotionHold::motionToNoise() const
{
  return empty() ? 0.0 : sphere_contact_estimator::motionToNoise(displacement_, covariance_);
}

void MotionHold::clear()
{
  displacement_.setZero();
  covariance_.setZero();
  duration_ = 0.0;
}

}  // namespace sphere_contact_estimator
