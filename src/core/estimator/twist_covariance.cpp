#include "sphere_contact_estimator/core/estimator/twist_covariance.h"

// Package
#include "sphere_contact_estimator/core/numerics/covariance.h"

namespace sphere_contact_estimator
{
namespace
{
constexpr int kUsed[5] = { 0, 1, 3, 4, 5 };  // linear x, y; angular x, y, z
}  // namespace

const char* toString(CovarianceStatus status)
{
  switch (status)
  {
    case CovarianceStatus::Ok:
      return "ok";
    case CovarianceStatus::Disabled:
      return "disabled";
    case CovarianceStatus::Unknown:
      return "unknown";
    case CovarianceStatus::Invalid:
      return "invalid";
    case CovarianceStatus::Undefined:
      return "undefined";
    case CovarianceStatus::Approximate:
      return "approximate";
  }
  return "?";
}

CovarianceStatus checkTwistCovariance(const TwistCovariance& C, const char** reason)
{
  const auto why = [&](const char* text) {
    if (reason)
      *reason = text;
  };
  why(nullptr);
  Eigen::Matrix<double, 5, 5> used;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      used(i, j) = C(kUsed[i], kUsed[j]);
  for (int i = 0; i < 5; ++i)
    if (used(i, i) == -1.0)
    {
      why("a component the estimate uses is marked unknown (-1 on the diagonal)");
      return CovarianceStatus::Unknown;
    }
  if (const char* problem = covarianceProblem<5>(used))
  {
    why(problem);
    return CovarianceStatus::Invalid;
  }
  return CovarianceStatus::Ok;
}

TwistCovariance rotateTwistCovariance(const TwistCovariance& C, const Eigen::Matrix3d& R)
{
  TwistCovariance B = TwistCovariance::Zero();
  B.topLeftCorner<3, 3>() = R;
  B.bottomRightCorner<3, 3>() = R;
  return B * C * B.transpose();
}

}  // namespace sphere_contact_estimator
