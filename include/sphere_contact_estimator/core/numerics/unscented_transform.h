#pragma once

// STL
#include <cmath>

// Eigen
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace sphere_contact_estimator
{
/// The mean and covariance of y = f(x) for x ~ (mean, P) in N dimensions, by the unscented transform: the 2N
/// sigma points mean +- sqrt(N + kappa) columns of a square root of P, weighted 1 / (2 (N + kappa)), and the mean
/// itself weighted kappa / (N + kappa). The transform is exact for the mean and covariance of f linear, and for
/// the mean of f quadratic; beyond, it matches the moments of a Gaussian x to the fourth order along each axis
/// when N + kappa = 3.
///
/// The square root comes from the symmetric eigen-decomposition, so a semi-definite P (a variable known exactly,
/// a perfectly correlated pair) needs no special case: a zero eigenvalue gives sigma points on the mean, where f is
/// evaluated once for all of them. With kappa = 0 the mean's own weight is zero, and f is evaluated 2 rank(P)
/// times. Fixed sizes: nothing is allocated.
template <int N, int M>
struct Unscented
{
  Eigen::Matrix<double, M, 1> mean;
  Eigen::Matrix<double, M, M> covariance;
  int evaluations = 0;  ///< how often f was called
  /// With check_curvature: how far f is from linear over the spread, the largest |y+ + y- - 2 y(mean)| over
  /// |y+ - y-| along a principal axis, over the outputs whose change along that axis is at least a tenth of their
  /// largest. 0 for f linear; about 1 or more at a kink or a jump inside the spread, where the transform's
  /// moments stop matching those of the distribution (0 when not checked).
  double curvature = 0.0;
};

/// f(const Eigen::Matrix<double, N, 1>&) -> Eigen::Matrix<double, M, 1>. P must be symmetric positive semi-definite
/// (negative eigenvalues from rounding count as zero); kappa > -N.
template <int N, int M, class F>
Unscented<N, M> unscentedTransform(const Eigen::Matrix<double, N, 1>& mean, const Eigen::Matrix<double, N, N>& P,
                                   F&& f, double kappa = 3.0 - N, bool check_curvature = false)
{
  Unscented<N, M> out;
  out.mean.setZero();
  out.covariance.setZero();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(P);
  const double spread = std::sqrt(N + kappa);
  const double w_mean = kappa / (N + kappa), w = 0.5 / (N + kappa);
  Eigen::Matrix<double, M, 2 * N + 1> y;
  y.setZero();
  bool have_mean = false;
  const auto atMean = [&]() -> Eigen::Matrix<double, M, 1> {
    if (!have_mean)
    {
      y.col(2 * N) = f(mean);
      ++out.evaluations;
      have_mean = true;
    }
    return y.col(2 * N);
  };
  if (w_mean != 0.0 || check_curvature)
    atMean();
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  for (int i = 0; i < N; ++i)
  {
    const double lambda = eig.eigenvalues()(i);
    if (!(lambda > 1e-14 * largest))  // no spread along this axis (or rounding of a zero)
    {
      y.col(2 * i) = y.col(2 * i + 1) = atMean();
      continue;
    }
    const Eigen::Matrix<double, N, 1> step = spread * std::sqrt(lambda) * eig.eigenvectors().col(i);
    y.col(2 * i) = f(Eigen::Matrix<double, N, 1>(mean + step));
    y.col(2 * i + 1) = f(Eigen::Matrix<double, N, 1>(mean - step));
    out.evaluations += 2;
  }
  if (check_curvature)
  {
    Eigen::Matrix<double, M, 1> slope_max = Eigen::Matrix<double, M, 1>::Zero();
    for (int i = 0; i < N; ++i)
      slope_max = slope_max.cwiseMax((y.col(2 * i) - y.col(2 * i + 1)).cwiseAbs());
    for (int i = 0; i < N; ++i)
      for (int k = 0; k < M; ++k)
      {
        const double slope = std::abs(y(k, 2 * i) - y(k, 2 * i + 1));
        const double bend = std::abs(y(k, 2 * i) + y(k, 2 * i + 1) - 2.0 * y(k, 2 * N));
        if (slope > 0.0 && slope >= 0.1 * slope_max(k))
          out.curvature = std::max(out.curvature, bend / slope);
        else if (slope_max(k) > 0.0 && bend >= 0.1 * slope_max(k))
          out.curvature = std::max(out.curvature, bend / slope_max(k));  // a kink with no slope along this axis
      }
  }
  for (int j = 0; j < 2 * N; ++j)
    out.mean += w * y.col(j);
  if (w_mean != 0.0)
    out.mean += w_mean * y.col(2 * N);
  for (int j = 0; j < 2 * N; ++j)
  {
    const Eigen::Matrix<double, M, 1> d = y.col(j) - out.mean;
    out.covariance += w * d * d.transpose();
  }
  if (w_mean != 0.0)
  {
    const Eigen::Matrix<double, M, 1> d = y.col(2 * N) - out.mean;
    out.covariance += w_mean * d * d.transpose();
  }
  return out;
}

}  // namespace sphere_contact_estimator
