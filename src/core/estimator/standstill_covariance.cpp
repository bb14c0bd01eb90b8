#include "sphere_contact_estimator/core/estimator/standstill_covariance.h"

// STL
#include <cmath>

// Eigen
#include <Eigen/Eigenvalues>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/estimator/paper_frame.h"

namespace sphere_contact_estimator
{
namespace
{
// L(v) (ROS) for a displacement v (ROS) from the model's table (paper frame), linear between its directions
Eigen::Vector3d roll(const AdhesionResponse& r, const Eigen::Vector2d& v_ros)
{
  const Eigen::Vector2d v = paper_frame::fromRos(v_ros);
  const double size = v.norm();
  if (!(size > 0.0))
    return Eigen::Vector3d::Zero();
  constexpr int n = AdhesionResponse::kDirections;
  double t = std::atan2(v.y(), v.x()) / boost::math::double_constants::two_pi * n;
  t -= n * std::floor(t / n);
  const int j = std::min(static_cast<int>(t), n - 1);
  const double f = t - j;
  return size * paper_frame::toRos(Eigen::Vector3d((1.0 - f) * r.roll.col(j) + f * r.roll.col((j + 1) % n)));
}
}  // namespace

void StandstillCovariance::restart(const Eigen::Matrix3d& start)
{
  sigma_ = start;
  known_ = true;
  pushed2_ = 0.0;
}

double StandstillCovariance::push2(const Eigen::Matrix<double, 5, 5>& drive, double dt, double a)
{
  // along a normal n, Var(n . dw) dt^2 with dw = -dV_s - d omega_z J x: V_s's variance averaged over the normal's
  // directions, and omega_z's times (J x . n)^2 averaged over the patch (a^2 / 4)
  return dt * dt * (0.5 * (drive(0, 0) + drive(1, 1)) + 0.25 * a * a * drive(2, 2));
}

double StandstillCovariance::band(const Eigen::Matrix<double, 5, 5>& drive, double dt, double a) const
{
  return kBand * std::sqrt(pushed2_ + push2(drive, dt, a));
}

void StandstillCovariance::advance(const AdhesionResponse& response, const Eigen::Matrix<double, 5, 5>& drive,
                                   double dt, const Eigen::Vector3d& limits, double a)
{
  if (!known_ || !(dt > 0.0))
    return;
  pushed2_ += push2(drive, dt, a);
  // the linear part, dt R w with w = (V_s, omega_z)
  const Eigen::Matrix3d A = dt * paper_frame::toRos(response.drive);  // (paper to ROS: the forces and the drive alike)
  Eigen::Matrix3d step = A * drive.topLeftCorner<3, 3>() * A.transpose();
  // the roll, L(d) with d = -V_r dt: d = Sigma_d^(1/2) z, z standard normal, and L homogeneous of degree one, so
  // E[L] = E|z| <L(Sigma^(1/2) e)>, E[L L^T] = E|z|^2 <L L^T>, E[d L^T] = E|z|^2 Sigma^(1/2) <e L^T>, the means over
  // the unit circle (kRollNodes directions; |z| Rayleigh: E|z| = sqrt(pi / 2), E|z|^2 = 2)
  const Eigen::Matrix2d Sigma_d = dt * dt * drive.bottomRightCorner<2, 2>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(Sigma_d);
  const Eigen::Vector2d lambda = eig.eigenvalues().cwiseMax(0.0);
  if (lambda.maxCoeff() > 0.0)
  {
    const Eigen::Matrix2d& V = eig.eigenvectors();
    const Eigen::Matrix2d root = V * lambda.cwiseSqrt().asDiagonal() * V.transpose();
    Eigen::Vector2d inverse_root_diagonal = Eigen::Vector2d::Zero();  // (the pseudo-inverse where Sigma_d is singular)
    for (int i = 0; i < 2; ++i)
      if (lambda(i) > 1e-12 * lambda.maxCoeff())
        inverse_root_diagonal(i) = 1.0 / std::sqrt(lambda(i));
    const Eigen::Matrix2d inverse_root = V * inverse_root_diagonal.asDiagonal() * V.transpose();
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    Eigen::Matrix<double, 2, 3> along = Eigen::Matrix<double, 2, 3>::Zero();
    for (const Eigen::Vector2d& e : AdhesionResponse::directions())  // (kRollNodes of them)
    {
      const Eigen::Vector3d L = roll(response, root * e);
      mean += L / kRollNodes;
      second += L * L.transpose() / kRollNodes;
      along += e * L.transpose() / kRollNodes;
    }
    mean *= std::sqrt(0.5 * boost::math::double_constants::pi);
    second *= 2.0;
    along *= 2.0;
    // Cov(dt R w, L) = Cov(dt R w, d) Sigma_d^-1 E[d L^T] (w's regression on d; w and d jointly Gaussian)
    const Eigen::Matrix<double, 3, 2> with_d = A * drive.topRightCorner<3, 2>() * (-dt);
    const Eigen::Matrix3d cross = with_d * inverse_root * along;
    step += second - mean * mean.transpose() + cross + cross.transpose();
  }
  sigma_ += step;
  sigma_ = 0.5 * (sigma_ + sigma_.transpose());
  for (int i = 0; i < 3; ++i)
  {
    const double limit2 = limits(i) * limits(i);
    if (sigma_(i, i) > limit2)
    {
      const double scale = std::sqrt(limit2 / sigma_(i, i));
      sigma_.row(i) *= scale;
      sigma_.col(i) *= scale;
    }
  }
}

}  // namespace sphere_contact_estimator
