#include "sphere_contact_estimator/core/estimator/motion_noise.h"

// STL
#include <cmath>
#include <limits>

// Eigen
#include <Eigen/Eigenvalues>

namespace sphere_contact_estimator
{
double motionToNoise(const UsedTwist& x, const Eigen::Matrix<double, 5, 5>& S)
{
  if (!S.allFinite() || !x.allFinite() || !S.isApprox(S.transpose(), 1e-9))
    return -1.0;
  // in units of each component's own sd (metres per second and radians per second do not mix in one tolerance):
  // a zero variance makes its component exact
  UsedTwist z = UsedTwist::Zero();
  Eigen::Matrix<double, 5, 1> sd;
  for (int i = 0; i < 5; ++i)
  {
    if (S(i, i) < 0.0)
      return -1.0;
    sd(i) = std::sqrt(S(i, i));
    if (sd(i) == 0.0)
    {
      if (x(i) != 0.0)
        return std::numeric_limits<double>::infinity();
    }
    else
      z(i) = x(i) / sd(i);
  }
  Eigen::Matrix<double, 5, 5> C = Eigen::Matrix<double, 5, 5>::Identity();  // the correlations
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      if (i != j && sd(i) > 0.0 && sd(j) > 0.0)
        C(i, j) = 0.5 * (S(i, j) + S(j, i)) / (sd(i) * sd(j));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 5, 5>> eig(C);  // fixed size: no allocation
  if (eig.info() != Eigen::Success || eig.eigenvalues().minCoeff() < -1e-9)
    return -1.0;
  // a correlation of +-1 leaves a direction without noise: motion along it is not noise
  constexpr double kExact = 1e-12;
  double d2 = 0.0;
  for (int k = 0; k < 5; ++k)
  {
    const double along = eig.eigenvectors().col(k).dot(z), lambda = eig.eigenvalues()(k);
    if (lambda > kExact)
      d2 += along * along / lambda;
    else if (std::abs(along) > 1e-9 * (1.0 + z.norm()))
      return std::numeric_limits<double>::infinity();
  }
  return std::sqrt(d2);
}

}  // namespace sphere_contact_estimator
