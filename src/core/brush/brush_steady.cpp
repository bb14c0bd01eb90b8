#include "sphere_contact_estimator/core/brush/brush_steady.h"

// STL
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

// Boost
#include <boost/math/constants/constants.hpp>

// The brush library's private rooms
#include "bristle_path.h"
#include "patch_integral.h"
#include "rolling_frame.h"

namespace sphere_contact_estimator
{
namespace
{
using boost::math::double_constants::pi;
}  // namespace

BrushSteady::BrushSteady(const BrushParameters& parameters) : BrushSlipModel(parameters)
{
}

void BrushSteady::prepareRules() { preparePatchRules(); }

BrushForces BrushSteady::evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi) const
{
  return solve(sigma, phi, phi_gamma, phi_psi, p_.accuracy_target, nullptr, nullptr, std::min(kMaxWork, work_budget_));
}

BrushForces BrushSteady::evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                                  double tolerance, Stats* stats, long max_work, CoulombStepper stepper) const
{
  if (!(std::isfinite(tolerance) && tolerance > 0.0 && tolerance <= 1.0))
  {
    std::ostringstream msg;
    msg << "steady brush model: tolerance " << tolerance << " must be in (0, 1] (a fraction of mu F_z)";
    throw std::invalid_argument(msg.str());
  }
  if (!(max_work > 0))
    throw std::invalid_argument("steady brush model: the work budget must be positive");
  return solve(sigma, phi, phi_gamma, phi_psi, tolerance, nullptr, stats, max_work, stepper);
}

BrushForces BrushSteady::evaluate(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                                  const Visitor& visit) const
{
  return solve(sigma, phi, phi_gamma, phi_psi, p_.accuracy_target, &visit);
}

bool BrushSteady::field(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi, BristleField& f) const
{
  return makeBristleField(p_, { sigma.x(), sigma.y() }, phi, phi_gamma, phi_psi, f);
}

BrushForces BrushSteady::solve(const Eigen::Vector2d& sigma, double phi, double phi_gamma, double phi_psi,
                               double tolerance, const Visitor* visit, Stats* stats, long max_work,
                               CoulombStepper stepper) const
{
  BrushForces out;
  if (p_.tilt && std::abs(phi_gamma) * p_.a > 1.0)
  {
    out.flags |= brush_flags::kNoSteadyStateTilt;  // |R_gamma| < a: Assumption 4.1 fails
    return out;
  }
  BristleField f;
  if (!field(sigma, phi, phi_gamma, phi_psi, f))
    return out;  // mu F_z = 0: no force, exactly
  const double c = peakFactor(p_.pressure);
  const double scale = c / pi;  // dimensionless integrals -> fractions of mu F_z
  // two thirds of the budget for the tolerance asked; if that runs out before the structure was even located (a
  // tolerance far tighter than the point allows, or a small budget), a looser one in the rest gives the best answer
  // the budget can: the work stays within it (but for the path under way when it ran out)
  const long first = tolerance < 1e-2 ? max_work - max_work / 3 : max_work;
  PatchIntegral I = integratePatch(f, tolerance / scale, first, stepper);
  if (!I.converged && I.error > 100.0 * tolerance / scale && tolerance < 1e-2 && max_work - I.work > 0)
  {
    const PatchIntegral looser = integratePatch(f, 100.0 * tolerance / scale, max_work - I.work, stepper);
    if (looser.error < I.error)
    {
      const long work = I.work;
      I = looser;
      I.work += work;
      I.converged = I.error <= tolerance / scale;  // against the tolerance asked for, not the looser one
    }
  }
  if (stats)
  {
    stats->paths = I.paths;
    stats->work = I.work;
  }
  out.work = I.work;
  const double muFz = p_.mu * p_.F_z;
  out.F_x = muFz * scale * I.force.real();
  out.F_y = muFz * scale * I.force.imag();
  out.M_z = muFz * p_.a * scale * I.moment;
  // Every bristle obeys |q| <= mu q_z, so the exact |F_t| <= mu F_z; a quadrature error may put the answer
  // outside that circle (by at most the error estimate, in full sliding). The circle is convex and holds the
  // exact answer, so the nearest point on it is never further from the exact answer than this one.
  const double norm = std::hypot(out.F_x, out.F_y);
  if (norm > muFz)
  {
    out.F_x *= muFz / norm;
    out.F_y *= muFz / norm;
  }
  out.sliding_fraction = std::clamp(I.sliding_area / pi, 0.0, 1.0);
  out.max_utilisation = std::sqrt(std::min(1.0, I.utilisation2));
  out.error_estimate = scale * I.error;
  if (!I.converged)
    out.flags |= brush_flags::kAccuracyNotMet;
  if (visit)
  {
    const double beta_a = deflectionUnit(p_);  // [m]
    for (int j = 0; j < kVisitPaths; ++j)
    {
      const double theta = -0.5 * pi + (j + 0.5) * pi / kVisitPaths;
      const BristlePath path = BristlePath::across(f, theta);
      const PathIntegrals solved = solvePath(f, path, 1e-6, true);
      for (int i = 0; i < kVisitPoints; ++i)
      {
        const double tau = (i + 0.5) * path.length / kVisitPoints;
        bool slides = false;
        const std::complex<double> u = deflectionAt(f, path, solved, tau, &slides);
        const std::complex<double> z = path.position(tau);
        (*visit)(Eigen::Vector2d(p_.a * z.real(), p_.a * z.imag()), Eigen::Vector2d(beta_a * u.real(), beta_a * u.imag()),
                 slides);
      }
    }
  }
  return out;
}

void BrushSteady::visitBristles(const BristleVisitor& visit) const
{
  visitBristles(last_, visit);
}

void BrushSteady::visitBristles(const Slips& s, const BristleVisitor& visit) const
{
  if (!s.defined)
    return;
  const RollingFrame frame(s.epsilon);
  evaluate(frame.toRolling(s.sigma), s.phi, s.phi_gamma, s.phi_psi,
           [&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool sliding) {
             visit(frame.toPatch(x), frame.toPatch(u), sliding);
           });
}

}  // namespace sphere_contact_estimator
