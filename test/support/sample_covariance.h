#pragma once

// STL
#include <vector>

// Eigen
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// The unbiased sample covariance of draws (the Monte Carlo side of every check of a published covariance:
/// test_uncertainty, model_accuracy --parked-walk). At least two draws.
template <int M>
Eigen::Matrix<double, M, M> sampleCovariance(const std::vector<Eigen::Matrix<double, M, 1>>& draws)
{
  const auto n = static_cast<double>(draws.size());
  Eigen::Matrix<double, M, 1> mean = Eigen::Matrix<double, M, 1>::Zero();
  for (const auto& y : draws)
    mean += y / n;
  Eigen::Matrix<double, M, M> C = Eigen::Matrix<double, M, M>::Zero();
  for (const auto& y : draws)
    C += (y - mean) * (y - mean).transpose();
  return C / (n - 1.0);
}

}  // namespace sphere_contact_estimator
