#include "sphere_contact_estimator/core/estimator/estimate_covariance.h"

// STL
#include <cmath>

namespace sphere_contact_estimator
{
namespace
{
constexpr int kUsed[5] = { 0, 1, 3, 4, 5 };  // linear x, y; angular x, y, z

// Ground -> contact frame (ROS axes): the rotation by -heading.
Eigen::Matrix2d toContact(double heading)
{
  const double c = std::cos(heading), s = std::sin(heading);
  return (Eigen::Matrix2d() << c, s, -s, c).finished();
}

// dV_r / du in the ground frame: V_r = R_r (omega_y, -omega_x) (docs/conventions.md)
Eigen::Matrix<double, 2, 5> rollingVelocityJacobian(double R_r)
{
  Eigen::Matrix<double, 2, 5> d = Eigen::Matrix<double, 2, 5>::Zero();
  d(0, 3) = R_r;
  d(1, 2) = -R_r;
  return d;
}
}  // namespace

Eigen::Matrix<double, 5, 5> usedTwistCovariance(const TwistCovariance& C)
{
  Eigen::Matrix<double, 5, 5> out;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      out(i, j) = C(kUsed[i], kUsed[j]);
  return out;
}

Eigen::Matrix<double, 5, 5> driveJacobian(double R_r, double heading)
{
  const Eigen::Matrix2d Rc = toContact(heading);
  Eigen::Matrix<double, 2, 5> dV_C = Eigen::Matrix<double, 2, 5>::Zero();
  dV_C(0, 0) = dV_C(1, 1) = 1.0;
  const Eigen::Matrix<double, 2, 5> dV_r = Rc * rollingVelocityJacobian(R_r);
  Eigen::Matrix<double, 5, 5> J = Eigen::Matrix<double, 5, 5>::Zero();
  J.topRows<2>() = Rc * dV_C - dV_r;  // V_s = V_C - V_r, turned into the contact frame
  J(2, 4) = 1.0;  // omega_z: the same about the ground's z and the contact frame's
  J.bottomRows<2>() = dV_r;
  return J;
}

Eigen::Matrix<double, 1, 5> speedJacobian(double R_r, double heading)
{
  return driveJacobian(R_r, heading).row(3);  // V_r lies along the contact frame's x
}

Eigen::Matrix<double, 4, 5> slipJacobian(const Eigen::Vector3d& omega, const Eigen::Vector2d& v_contact, double R_r,
                                         double heading)
{
  const Eigen::Matrix2d Rc = toContact(heading);
  const Eigen::Vector2d V_r = R_r * Eigen::Vector2d(omega.y(), -omega.x());
  const double V = (Rc * V_r).x();  // the contact frame's x is along V_r
  const Eigen::Vector2d V_s = Rc * (v_contact - V_r);  // contact frame, ROS axes
  const Eigen::Matrix<double, 5, 5> drive = driveJacobian(R_r, heading);
  const Eigen::Matrix<double, 2, 5> dV_s = drive.topRows<2>();
  const Eigen::Matrix<double, 2, 5> dV_r = drive.bottomRows<2>();
  const Eigen::Matrix<double, 1, 5> dV = dV_r.row(0);
  // sigma = -V_s / V (eq. 12) and phi = -omega_z / V in the paper frame, where omega_z and y change sign (eq. 13)
  const Eigen::Matrix<double, 2, 5> dsigma = -dV_s / V + V_s * dV / (V * V);
  Eigen::Matrix<double, 1, 5> dphi = -omega.z() * dV / (V * V);
  dphi(4) += 1.0 / V;
  Eigen::Matrix<double, 4, 5> K;
  K.row(0) = dsigma.row(0);
  K.row(1) = -dsigma.row(1);
  K.row(2) = dphi;
  K.row(3) = -dV_r.row(1) / V;  // the rolling direction turns by dV_r,y / V about z up: minus that about z down
  return K;
}

}  // namespace sphere_contact_estimator
