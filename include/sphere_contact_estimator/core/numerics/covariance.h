#pragma once

// STL
#include <cmath>
#include <cstdint>

// Eigen
#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace sphere_contact_estimator
{
/// How a covariance was carried from a model's inputs to its outputs; the numbers are those of ContactEstimate.
enum class CovarianceMethod : std::uint8_t
{
  None = 0,       ///< not propagated (no covariance given, or it could not be: see the status)
  Zero = 1,       ///< the inputs are exact: the outputs' covariance is exactly zero
  Jacobian = 2,   ///< linearised: J Sigma J^T with the model's exact Jacobian
  Unscented = 3,  ///< the unscented transform (unscented_transform.h) through the model
  RandomWalk = 4,  ///< each message's input noise integrated by the model's state (StandstillCovariance)
};

inline const char* toString(CovarianceMethod method)
{
  switch (method)
  {
    case CovarianceMethod::None:
      return "none";
    case CovarianceMethod::Zero:
      return "zero";
    case CovarianceMethod::Jacobian:
      return "jacobian";
    case CovarianceMethod::Unscented:
      return "unscented";
    case CovarianceMethod::RandomWalk:
      return "random_walk";
  }
  return "?";
}

/// What is wrong with a covariance matrix, if anything: not finite, not symmetric (beyond 1e-9 of its largest
/// entry), or not positive semi-definite (an eigenvalue below -1e-9 of the largest, which rounding does not
/// explain). Returns nullptr for a valid one (zero included).
template <int N>
const char* covarianceProblem(const Eigen::Matrix<double, N, N>& P)
{
  if (!P.allFinite())
    return "not finite";
  const double scale = P.cwiseAbs().maxCoeff();
  if (scale == 0.0)
    return nullptr;
  if (((P - P.transpose()).cwiseAbs().maxCoeff()) > 1e-9 * scale)
    return "not symmetric";
  for (int i = 0; i < N; ++i)
    if (P(i, i) < 0.0)
      return "a negative variance";
  // positive semi-definite: the pivoted LDL^T's diagonal, none below rounding (a twentieth the cost of the
  // eigenvalues, on every odometry message)
  const Eigen::LDLT<Eigen::Matrix<double, N, N>> ldlt(P);
  if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() < -1e-9 * P.diagonal().maxCoeff())
    return "not positive semi-definite (a correlation beyond +-1)";
  return nullptr;
}

}  // namespace sphere_contact_estimator
