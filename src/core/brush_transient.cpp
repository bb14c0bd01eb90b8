#include "sphere_contact_estimator/core/brush_transient.h"

// STL
#include <algorithm>
#include <cmath>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "sphere_contact_estimator/core/friction_cap.h"

namespace sphere_contact_estimator
{
namespace
{
constexpr double kMaxAngle = 0.1;  // rad per substep, for every rotation

Eigen::Matrix2d rotation(double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

// Integral over [0, t] of the rotation R(rate tau): [[S, -C], [C, S]] with S = sin(rate t)/rate and
// C = (1 - cos(rate t))/rate, by series where rate t is small.
Eigen::Matrix2d rotationIntegral(double rate, double t)
{
  const double x = rate * t;
  double S, C;
  if (std::abs(x) < 1e-3)
  {
    S = t * (1.0 - x * x / 6.0);
    C = t * x * 0.5 * (1.0 - x * x / 12.0);
  }
  else
  {
    S = std::sin(x) / rate;
    C = (1.0 - std::cos(x)) / rate;
  }
  return (Eigen::Matrix2d() << S, -C, C, S).finished();
}

// -V_s - A_omega_z x: the drive of the bristle ODE and the rigid sliding direction (time domain).
Eigen::Vector2d drive(const ContactKinematics& k, const Eigen::Vector2d& x)
{
  return { -k.V_s.x() + k.omega_z * x.y(), -k.V_s.y() - k.omega_z * x.x() };
}
}  // namespace

BrushTransient::BrushTransient(const BrushParameters& parameters) : BrushModel(parameters)
{
  allocate();
}

bool BrushTransient::setParameters(const BrushParameters& parameters)
{
  parameters.validate();
  const bool lattice_changes = parameters.a != p_.a || parameters.resolution != p_.resolution;
  p_ = parameters;
  if (lattice_changes)
    allocate();
  return lattice_changes;
}

void BrushTransient::rotateFrame(double alpha)
{
  const Eigen::Matrix2d Q = rotation(-alpha);  // components in axes turned by alpha
  R_ = Q * R_;
  o_ = Q * o_;
  for (Eigen::Vector2d& u : u_)
    u = Q * u;
  recentre();
}

void BrushTransient::allocate()
{
  const int n = p_.resolution;
  h_ = 2.0 * p_.a / n;
  w_ = n + 6;  // the patch plus a margin: points shifted into the window are outside the patch
  c0_ = 0.5 * (w_ - 1);
  u_.resize(static_cast<std::size_t>(w_) * w_);
  inside_.resize(u_.size());
  sliding_.resize(u_.size());
  u_scratch_.resize(u_.size());
  inside_scratch_.resize(u_.size());
  sliding_scratch_.resize(u_.size());
  reset();
}

void BrushTransient::reset()
{
  R_.setIdentity();
  o_.setZero();
  std::fill(u_.begin(), u_.end(), Eigen::Vector2d::Zero());
  std::fill(sliding_.begin(), sliding_.end(), 0);
  const double a2 = p_.a * p_.a;
  for (int j = 0; j < w_; ++j)
    for (int i = 0; i < w_; ++i)
      inside_[index(i, j)] = position(i, j).squaredNorm() < a2;
}

BrushForces BrushTransient::update(const ContactKinematics& kin, double dt)
{
  checkInput(kin, dt);
  BrushForces f;
  if (dt > 0.0)
  {
    const double omega_gamma = p_.tilt ? kin.omegaGamma() : 0.0;
    const double travel = (kin.V_r.norm() + std::abs(omega_gamma) * (p_.a + h_)) * dt;
    double angle = std::abs(omega_gamma) * dt;
    if (p_.tilt)
      angle = std::max(angle, std::abs(kin.psi_dot) * dt);
    const double wanted = std::ceil(std::max({ 1.0, travel / (0.5 * h_), angle / kMaxAngle }));
    int n = kMaxSubsteps;
    if (wanted <= kMaxSubsteps)
      n = static_cast<int>(wanted);
    else
      f.flags |= brush_flags::kSubstepsTruncated;
    for (int s = 0; s < n; ++s)
      substep(kin, dt / n);
  }
  const BrushForces g = forces();
  f.F_x = g.F_x;
  f.F_y = g.F_y;
  f.M_z = g.M_z;
  f.sliding_fraction = g.sliding_fraction;
  f.max_utilisation = g.max_utilisation;
  return f;
}

void BrushTransient::substep(const ContactKinematics& kin, double dt)
{
  // Rigid motion of the bristle roots over dt (eq. 31): dx/dt = -V_r - A_omega_gamma x with
  // A_omega_gamma = -chi_gamma A_omega_z (after eq. 31), i.e. the roots turn with the sphere at rate
  // +omega_gamma. Exactly: x' = R(omega_gamma dt) x - Int_0^dt R(omega_gamma tau) dtau V_r.
  const double rate = p_.tilt ? kin.omegaGamma() : 0.0;
  const Eigen::Matrix2d Q = rotation(rate * dt);
  const Eigen::Matrix2d R_old = R_;
  const Eigen::Vector2d o_old = o_;
  R_ = Q * R_;
  o_ = Q * o_ - rotationIntegral(rate, dt) * kin.V_r;

  // Bristle ODE du/dt = w(x) - [A_psi_dot u]: exact rotation at rate -psi_dot of the coupling, drive at
  // the midpoint of the time spent inside the patch.
  const double spin = p_.tilt ? -kin.psi_dot : 0.0;
  const double a2 = p_.a * p_.a;
  const FrictionCap cap(p_);
  for (int j = 0; j < w_; ++j)
  {
    for (int i = 0; i < w_; ++i)
    {
      const std::size_t p = index(i, j);
      const Eigen::Vector2d l((i - c0_) * h_, (j - c0_) * h_);
      const Eigen::Vector2d x1 = o_ + R_ * l;
      const double g1 = x1.squaredNorm() - a2;
      if (g1 >= 0.0)
      {
        u_[p].setZero();  // outside the patch: undeformed (it re-enters under eq. 8)
        inside_[p] = sliding_[p] = 0;
        continue;
      }
      const Eigen::Vector2d x0 = o_old + R_old * l;
      double share = 1.0;  // part of the substep spent inside
      if (!inside_[p])
      {
        const double g0 = x0.squaredNorm() - a2;
        share = g0 > 0.0 ? -g1 / (g0 - g1) : 1.0;
        u_[p].setZero();
      }
      const double t = share * dt;
      const Eigen::Vector2d x_mid = x1 + 0.5 * share * (x0 - x1);
      Eigen::Vector2d& u = u_[p];
      if (spin != 0.0)
        u = rotation(spin * t) * u + rotationIntegral(spin, t) * drive(kin, x_mid);
      else
        u += t * drive(kin, x_mid);
      const FrictionCap::Result r = cap.apply(u, x1, drive(kin, x1));
      inside_[p] = 1;
      sliding_[p] = r.sliding;
    }
  }
  recentre();
}

void BrushTransient::recentre()
{
  // The patch centre in lattice coordinates, in spacings from the window centre.
  const Eigen::Vector2d l = -R_.transpose() * o_ / h_;
  const int di = static_cast<int>(std::lround(l.x())), dj = static_cast<int>(std::lround(l.y()));
  if (di == 0 && dj == 0)
    return;
  // New index (i, j) holds old (i + di, j + dj); points shifted in from outside the window lie outside
  // the patch (the margin), so they start undeformed.
  for (int j = 0; j < w_; ++j)
    for (int i = 0; i < w_; ++i)
    {
      const std::size_t p = index(i, j);
      const int si = i + di, sj = j + dj;
      const bool kept = si >= 0 && sj >= 0 && si < w_ && sj < w_;
      u_scratch_[p] = kept ? u_[index(si, sj)] : Eigen::Vector2d::Zero();
      inside_scratch_[p] = kept ? inside_[index(si, sj)] : 0;
      sliding_scratch_[p] = kept ? sliding_[index(si, sj)] : 0;
    }
  u_.swap(u_scratch_);
  inside_.swap(inside_scratch_);
  sliding_.swap(sliding_scratch_);
  o_ += R_ * Eigen::Vector2d(di * h_, dj * h_);
}

BrushForces BrushTransient::forces() const
{
  BrushForces f;
  Eigen::Vector2d F = Eigen::Vector2d::Zero();
  double M_z = 0.0, utilisation = 0.0, load = 0.0;
  int count = 0, sliding = 0;
  const FrictionCap cap(p_);
  forEachBristle([&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool slides) {
    ++count;
    sliding += slides;
    F += u;
    M_z += x.x() * u.y() - x.y() * u.x();
    const double q_z = cap.qz(x.squaredNorm());
    load += q_z;
    const double bound = p_.mu * q_z / p_.k;
    utilisation = std::max(utilisation, slides ? 1.0 : (bound > 0.0 ? u.norm() / bound : 0.0));
  });
  if (count == 0)
    return f;
  // Cell weight normalised so that the lattice sum of q_z is F_z: every bristle obeys |q| <= mu q_z, so
  // |F_t| <= mu F_z then holds exactly. Without load, the patch area over the bristle count.
  const double dA = load > 0.0 ? p_.F_z / load : boost::math::double_constants::pi * p_.a * p_.a / count;
  f.F_x = p_.k * F.x() * dA;
  f.F_y = p_.k * F.y() * dA;
  f.M_z = p_.k * M_z * dA;
  f.sliding_fraction = static_cast<double>(sliding) / count;
  f.max_utilisation = utilisation;
  return f;
}

}  // namespace sphere_contact_estimator
