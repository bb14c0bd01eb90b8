// Slips and spins from the kinematics of a spherical wheel (Romano et al. eqs. 2, 12, 13, 36, 42).

// GTest
#include <gtest/gtest.h>

// Package
#include "sphere_contact_estimator/core/brush/contact_kinematics.h"

namespace sphere_contact_estimator
{
namespace
{
TEST(BrushKinematics, PureRollingHasNoSlip)
{
  // docs/conventions.md: V_r = [-omega_y, omega_x] R_r; a sphere rolling without slip has V_C = V_r.
  const double R = 0.2;
  const Eigen::Vector3d omega(0.3, -5.0, 0.0);
  const Eigen::Vector2d V_C(-omega.y() * R, omega.x() * R);
  const Slips s = computeSlips(ContactKinematics::fromWheel(omega, V_C, R, 0.0));
  ASSERT_TRUE(s.defined);
  EXPECT_NEAR(s.sigma.norm(), 0.0, 1e-15);
  EXPECT_NEAR(s.V_r, std::hypot(omega.x(), omega.y()) * R, 1e-15);
  EXPECT_NEAR(s.epsilon.norm(), 1.0, 1e-15);  // ||epsilon|| = 1 (after eq. 12)
}

TEST(BrushKinematics, Eqs12And13)
{
  const double R = 0.1;
  const Eigen::Vector3d omega(0.0, -10.0, 2.0);  // rolling along +x at 1 m/s: epsilon = (0, 1)
  const Eigen::Vector2d V_C(1.1, -0.05);
  const double psi_dot = 0.5;
  const ContactKinematics k = ContactKinematics::fromWheel(omega, V_C, R, psi_dot);
  const Slips s = computeSlips(k);
  ASSERT_TRUE(s.defined);
  EXPECT_NEAR(s.epsilon.x(), 0.0, 1e-15);
  EXPECT_NEAR(s.epsilon.y(), 1.0, 1e-15);
  EXPECT_NEAR(s.sigma.x(), -0.1, 1e-12);   // -V_sx / V_r: the centre outruns the rolling speed
  EXPECT_NEAR(s.sigma.y(), 0.05, 1e-12);
  EXPECT_NEAR(s.phi, -2.0, 1e-12);          // -omega_z / V_r
  EXPECT_NEAR(s.phi_psi, -0.5, 1e-12);      // -psi_dot / V_r
  EXPECT_NEAR(s.phi_gamma, -1.5, 1e-12);    // -(omega_z - psi_dot) / V_r
  EXPECT_NEAR(s.phi_gamma + s.phi_psi, s.phi, 1e-12);
  EXPECT_NEAR(*s.chi_gamma + *s.chi_psi, 1.0, 1e-15);
  EXPECT_NEAR(*s.chi_gamma * s.phi, s.phi_gamma, 1e-12);
  EXPECT_NEAR((*s.tilting_centre - s.epsilon / s.phi_gamma).norm(), 0.0, 1e-15);   // eq. 36
  EXPECT_NEAR((*s.turning_centre + s.epsilon / s.phi_psi).norm(), 0.0, 1e-15);     // eq. 42
}

TEST(BrushKinematics, TiltRatioSplitsTheSpin)
{
  const ContactKinematics k =
      ContactKinematics::fromWheelWithTiltRatio(Eigen::Vector3d(0.0, -10.0, 3.0), Eigen::Vector2d(1.0, 0.0), 0.1, 0.9);
  EXPECT_NEAR(k.omegaGamma(), 2.7, 1e-12);
  EXPECT_NEAR(k.psi_dot, 0.3, 1e-12);
  const Slips s = computeSlips(k);
  EXPECT_NEAR(*s.chi_gamma, 0.9, 1e-12);
}

TEST(BrushKinematics, FromSlipsRoundTrip)
{
  const ContactKinematics k = ContactKinematics::fromSlips(Eigen::Vector2d(0.1, -0.2), 3.33, 0.9, 2.5);
  const Slips s = computeSlips(k);
  EXPECT_NEAR(s.sigma.x(), 0.1, 1e-14);
  EXPECT_NEAR(s.sigma.y(), -0.2, 1e-14);
  EXPECT_NEAR(s.phi, 3.33, 1e-14);
  EXPECT_NEAR(s.phi_gamma, 0.9 * 3.33, 1e-13);
  EXPECT_NEAR(s.epsilon.y(), 1.0, 1e-15);
}

TEST(BrushKinematics, StandstillIsGuarded)
{
  for (double v : { 0.0, 1e-12, 0.999e-3 })
  {
    const ContactKinematics k = ContactKinematics::fromWheel(Eigen::Vector3d(0.0, -v / 0.1, 5.0),
                                                             Eigen::Vector2d(0.3, 0.0), 0.1, 0.0);
    const Slips s = computeSlips(k);
    EXPECT_FALSE(s.defined) << v;
    for (double x : { s.sigma.x(), s.sigma.y(), s.phi, s.phi_gamma, s.phi_psi, s.epsilon.x(), s.epsilon.y() })
      EXPECT_EQ(x, 0.0) << v;  // never inf or NaN
    EXPECT_FALSE(s.tilting_centre);
  }
  EXPECT_TRUE(computeSlips(ContactKinematics::fromSlips(Eigen::Vector2d::Zero(), 0.0, 1.0, 1e-3)).defined);
  // omega_z = 0: ratios undefined, spins still defined
  const Slips s = computeSlips(ContactKinematics::fromWheel(Eigen::Vector3d(0, -10, 0), Eigen::Vector2d(1, 0), 0.1, 0.2));
  EXPECT_FALSE(s.chi_gamma);
  EXPECT_NEAR(s.phi, 0.0, 1e-15);
  EXPECT_NEAR(s.phi_gamma, -s.phi_psi, 1e-15);
}

}  // namespace
}  // namespace sphere_contact_estimator
