#include "sphere_contact_estimator/core/steady_lag.h"

// STL
#include <algorithm>
#include <cmath>

namespace sphere_contact_estimator
{
double SteadyLag::memory(double delta) const
{
  // straight paths across the disc (units of a): a path at y is 2 l = 2 sqrt(1 - y^2) long, and
  // int_0^{2l} (Sigma - d)+ dSigma = (2l - d)^2 / 2 against int Sigma dSigma = 2 l^2; over y in (-Y, Y), Y where
  // 2l = d: int (2l - d)^2 dy = 8Y - 8Y^3/3 - 4d (Y d/2 + asin Y) + 2 d^2 Y, and int 4 l^2 dy = 16/3
  const double d = delta / a_;
  if (d <= 0.0)
    return 1.0;
  if (d >= 2.0)
    return 0.0;
  const double Y = std::sqrt(1.0 - 0.25 * d * d);
  const double num = 8.0 * Y - 8.0 * Y * Y * Y / 3.0 - 4.0 * d * (0.5 * d * Y + std::asin(Y)) + 2.0 * d * d * Y;
  return std::clamp(num / (16.0 / 3.0), 0.0, 1.0);
}

void SteadyLag::step(const Eigen::Vector3d& steady, double travel)
{
  if (have_)
  {
    const Eigen::Vector3d change = last_ - steady;  // the state still holds part of the old steady forces
    if (change.squaredNorm() > 0.0)
    {
      if (count_ == kCapacity)
      {
        first_ = (first_ + 1) % kCapacity;
        --count_;
      }
      changes_[(first_ + count_) % kCapacity] = { s_, change };
      ++count_;
    }
  }
  last_ = steady;
  have_ = true;
  s_ += travel;
  // changes older than the longest memory (2a) weigh nothing
  while (count_ > 0 && s_ - changes_[first_].s >= 2.0 * a_)
  {
    first_ = (first_ + 1) % kCapacity;
    --count_;
  }
}

void SteadyLag::reset()
{
  have_ = false;
  count_ = 0;
  first_ = 0;
  s_ = 0.0;
}

void SteadyLag::rotate(double alpha)
{
  // F_x, F_y in axes turned by alpha (x' = R(-alpha) x); M_z is invariant
  const double c = std::cos(alpha), s = std::sin(alpha);
  const auto turn = [c, s](Eigen::Vector3d& v) { v = Eigen::Vector3d(c * v.x() + s * v.y(), -s * v.x() + c * v.y(), v.z()); };
  turn(last_);
  for (int i = 0; i < count_; ++i)
    turn(changes_[(first_ + i) % kCapacity].dF);
}

double SteadyLag::lag() const
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < count_; ++i)
  {
    const Change& c = changes_[(first_ + i) % kCapacity];
    sum += memory(s_ - c.s) * c.dF;
  }
  return sum.cwiseAbs().maxCoeff();
}

}  // namespace sphere_contact_estimator
