#include "sphere_contact_estimator/core/brush/force_covariance.h"

// STL
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

// Package
#include "sphere_contact_estimator/core/brush/brush_linear.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/numerics/unscented_transform.h"

// The brush library's private rooms
#include "plane_rotation.h"

namespace sphere_contact_estimator
{
namespace
{
constexpr double kCovarianceFloor = 1e-4;  // the tightest tolerance of a sigma point's evaluation [mu F_z]

// d(F_x, F_y, M_z) / d(sigma_x, sigma_y, phi, psi) of the linear model at psi = 0: eqs. 61-62 (and the spin term of
// M_z), with the scaling onto the friction circle past mu F_z, where F_t' = s F_t and M_z' = s M_z with
// s = mu F_z / |F_t|, so that dF_t' = s (I - n n^T) dF_t and dM_z' = s (dM_z - M_z n^T dF_t / |F_t|), n = F_t / |F_t|;
// and the turn psi of the rolling direction: F(psi) = R(psi) F_r(R(-psi) sigma), dF/dpsi = G F_r - dF_r/dsigma G sigma
// with G the quarter turn (dM_z/dpsi = -dM_z/dsigma G sigma).
Eigen::Matrix<double, 3, 4> linearJacobian(const BrushLinear& model, const Eigen::Vector2d& sigma, double phi)
{
  Eigen::Matrix3d A;
  A << model.C_sigma(), 0.0, 0.0,  //
      0.0, model.C_sigma(), model.C_phi(),  //
      0.0, -model.C_Msigma_y(), model.C_Mphi();
  Eigen::Vector2d F = model.C_sigma() * sigma + Eigen::Vector2d(0.0, model.C_phi() * phi);
  double M = -model.C_Msigma_y() * sigma.y() + model.C_Mphi() * phi;
  const BrushParameters& p = model.parameters();
  const double limit = p.mu * p.F_z, norm = F.norm();
  Eigen::Matrix3d J = A;
  if (norm > limit && norm > 0.0)
  {
    const double s = limit / norm;
    const Eigen::Vector2d n = F / norm;
    J.topRows<2>() = s * (Eigen::Matrix2d::Identity() - n * n.transpose()) * A.topRows<2>();
    J.row(2) = s * (A.row(2) - M / norm * n.transpose() * A.topRows<2>());
    F *= s;
    M *= s;
  }
  const Eigen::Matrix2d G = (Eigen::Matrix2d() << 0.0, -1.0, 1.0, 0.0).finished();
  Eigen::Matrix<double, 3, 4> out;
  out.leftCols<3>() = J;
  const Eigen::Vector2d turned = G * sigma;
  out.col(3).head<2>() = G * F - J.topLeftCorner<2, 2>() * turned;
  out(2, 3) = -J.block<1, 2>(2, 0).dot(turned);
  return out;
}

template <int N>
ForceCovariance propagate(BrushModelKind kind, const BrushParameters& p, const Eigen::Vector2d& sigma, double phi,
                          double chi_gamma, const Eigen::Matrix<double, N, N>& Sigma, long max_work);

// The rolling direction's turn psi matters only through what is not isotropic in the slips (the spin's term, the
// adhesion zone's shape): where the linear model says that its share of the forces' variance is below 1 %, the
// slips alone are transformed (6 sigma points instead of 8).
ForceCovariance propagateWithTurn(BrushModelKind kind, const BrushParameters& p, const Eigen::Vector2d& sigma,
                                  double phi, double chi_gamma, const Eigen::Matrix4d& Sigma, long max_work)
{
  if (kind != BrushModelKind::Linear && covarianceProblem<4>(Sigma) == nullptr)
  {
    const Eigen::Matrix<double, 3, 4> J = linearJacobian(BrushLinear(p), sigma, phi);
    const Eigen::Vector3d turn = J.col(3).cwiseAbs2() * Sigma(3, 3);
    const Eigen::Vector3d all = (J * Sigma * J.transpose()).diagonal();
    if ((turn.array() <= 0.01 * all.array()).all())
      return propagate<3>(kind, p, sigma, phi, chi_gamma, Eigen::Matrix3d(Sigma.topLeftCorner<3, 3>()), max_work);
  }
  return propagate<4>(kind, p, sigma, phi, chi_gamma, Sigma, max_work);
}

template <int N>
ForceCovariance propagate(BrushModelKind kind, const BrushParameters& p, const Eigen::Vector2d& sigma, double phi,
                          double chi_gamma, const Eigen::Matrix<double, N, N>& Sigma, long max_work)
{
  if (const char* problem = covarianceProblem<N>(Sigma))
    throw std::invalid_argument(std::string("slip covariance: ") + problem);
  ForceCovariance out;
  out.defined = true;
  if (Sigma.isZero(0.0))
  {
    out.method = CovarianceMethod::Zero;
    return out;
  }
  const BrushLinear linear(p);
  const Eigen::Matrix<double, 3, N> J = linearJacobian(linear, sigma, phi).template leftCols<N>();
  if (kind == BrushModelKind::Linear)
  {
    out.method = CovarianceMethod::Jacobian;
    out.covariance = J * Sigma * J.transpose();
    return out;
  }
  // The steady model at the sigma points, each to a twentieth of the spread (its errors move each sigma point's
  // deviation, of sqrt(3) or 2 standard deviations, by at most that: 3 % of the spread): first of the linear model's
  // spread, then, where saturation made the spread far smaller, again of the spread the first pass found.
  const BrushSteady steady(p);
  bool exists = true;
  // the budget shared by the sigma points (2N + 1 of them; a second pass only in what the first left): an evaluation
  // stopped by its share flags the transform, which then gives way to the linear model's Jacobian
  const long points = 2 * N + 1;
  long share = max_work / points;
  bool short_of_work = false;
  long work = 0;
  Eigen::Matrix<double, N, 1> mean = Eigen::Matrix<double, N, 1>::Zero();
  mean.template head<3>() << sigma.x(), sigma.y(), phi;
  const auto transform = [&](double tolerance) {
    return unscentedTransform<N, 3>(
        mean, Sigma,
        [&](const Eigen::Matrix<double, N, 1>& x) {
          const double psi = N > 3 ? x(N - 1) : 0.0;
          if (short_of_work)
            return Eigen::Vector3d::Zero().eval();  // the transform gives way to the Jacobian: nothing more spent
          const Eigen::Vector2d s = rotation(-psi) * Eigen::Vector2d(x(0), x(1));
          BrushSteady::Stats stats;
          const BrushForces f = steady.evaluate(s, x(2), chi_gamma * x(2), (1.0 - chi_gamma) * x(2), tolerance, &stats,
                                                std::min(BrushSteady::kMaxWork, std::max(share, 1L)));
          work += stats.work;
          short_of_work = short_of_work || ((f.flags & brush_flags::kAccuracyNotMet) && 2 * stats.work >= share);
          exists = exists && !(f.flags & brush_flags::kNoSteadyStateTilt);
          const Eigen::Vector2d F = rotation(psi) * Eigen::Vector2d(f.F_x, f.F_y);
          return Eigen::Vector3d(F.x(), F.y(), f.M_z);
        },
        0.0, true);
  };
  ForceCovariance guess;
  guess.covariance = J * Sigma * J.transpose();
  // (not below 1e-4 of mu F_z: a spread smaller than 2e-3 is then known to about 1e-4, which no user of a force's
  // uncertainty resolves, and eq. 4b's solver spends up to 10x longer at 1e-6)
  const auto tolerance = [](double spread) { return std::clamp(0.05 * spread, kCovarianceFloor, 1e-2); };
  const double first = tolerance(guess.spread(p));
  Unscented<N, 3> u = transform(first);
  out.evaluations = u.evaluations;
  out.covariance = u.covariance;
  const double second = tolerance(out.spread(p));
  share = (max_work - work) / points;
  if (first > 4.0 * second && !short_of_work && work <= max_work / 2)
  {
    u = transform(second);
    out.evaluations += u.evaluations;
    out.covariance = u.covariance;
  }
  out.method = CovarianceMethod::Unscented;
  out.smooth = u.curvature <= ForceCovariance::kSmooth;
  out.work = work;
  if (short_of_work)
  {
    // The budget could not buy the sigma points: the linear model's Jacobian (eqs. 61-62 and the friction circle),
    // no standard deviation beyond what the friction circle allows (|F_t| <= mu F_z, |M_z| <= a mu F_z), which a
    // linearisation over a wide spread would pass.
    const double limit = p.mu * p.F_z;
    const Eigen::Vector3d bound(limit, limit, p.a * limit);
    Eigen::Vector3d scale;
    for (int i = 0; i < 3; ++i)
    {
      const double sd = std::sqrt(std::max(0.0, guess.covariance(i, i)));
      scale(i) = sd > bound(i) ? bound(i) / sd : 1.0;
    }
    const Eigen::Matrix3d C = scale.asDiagonal() * guess.covariance * scale.asDiagonal();
    out.covariance = 0.5 * (C + C.transpose());  // symmetric to the last bit
    out.method = CovarianceMethod::Jacobian;
    out.smooth = false;
  }
  // with tilt the steady state ends where |R_gamma| reaches a (Fig. 2): near that edge the forces change without
  // bound, and a spread of phi_gamma that reaches it within three standard deviations is beyond the sigma points
  if (p.tilt && p.a * std::abs(chi_gamma) * (std::abs(phi) + 3.0 * std::sqrt(std::max(0.0, Sigma(2, 2)))) >= 1.0)
    out.smooth = false;
  if (!exists)
  {
    out.covariance.setZero();
    out.method = CovarianceMethod::None;
    out.defined = false;
  }
  return out;
}
}  // namespace

double ForceCovariance::spread(const BrushParameters& p) const
{
  const double limit = p.mu * p.F_z;
  if (!(limit > 0.0))
    return 0.0;
  const Eigen::Vector3d d = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  return std::max({ d.x(), d.y(), d.z() / p.a }) / limit;
}

ForceCovariance propagateSlipCovariance(BrushModelKind kind, const BrushParameters& p, const Eigen::Vector2d& sigma,
                                        double phi, double chi_gamma, const Eigen::Matrix3d& Sigma, long max_work)
{
  return propagate<3>(kind, p, sigma, phi, chi_gamma, Sigma, max_work);
}

ForceCovariance propagateSlipCovariance(BrushModelKind kind, const BrushParameters& p, const Eigen::Vector2d& sigma,
                                        double phi, double chi_gamma, const Eigen::Matrix4d& Sigma, long max_work)
{
  return propagateWithTurn(kind, p, sigma, phi, chi_gamma, Sigma, max_work);
}

}  // namespace sphere_contact_estimator
