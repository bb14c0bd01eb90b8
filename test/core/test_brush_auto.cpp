// The auto brush model: the linear model's bound, staying within its target at random operating points and
// covering its error over random histories, the exact steady state after a long step, continuity, the
// transient model's resolution, and its cost.

// STL
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

// GTest
#include <gtest/gtest.h>

// Boost
#include <boost/math/constants/constants.hpp>

// Package
#include "brush_test_support.h"
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "scenario.h"

namespace sphere_contact_estimator
{
namespace
{
using test::figure4Parameters;
using test::forceDistance;

// Seeded random operating points over the envelope (a = 0.01-0.08 m, F_z = 20-5000 N, mu = 0.2-1.2,
// k = 10^6.5-10^9 N/m^3, |sigma_x| <= 0.3, |sigma_y| <= 0.1, |a phi| <= 1), all pressures, tilt and no tilt.
struct Point
{
  BrushParameters p;
  Eigen::Vector2d sigma;
  double phi, chi;
};

Point draw(std::mt19937_64& rng, int i, double scale)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Point q;
  q.p.a = 0.01 + 0.07 * u(rng);
  q.p.F_z = std::exp(std::log(20.0) + std::log(250.0) * u(rng));
  q.p.mu = 0.2 + u(rng);
  q.p.k = std::pow(10.0, 6.5 + 2.5 * u(rng));
  q.p.pressure = static_cast<PressureDistribution>(i % 3);
  q.p.tilt = (i / 3) % 2;
  q.sigma = scale * Eigen::Vector2d(0.3 * (2.0 * u(rng) - 1.0), 0.1 * (2.0 * u(rng) - 1.0));
  q.phi = scale * (2.0 * u(rng) - 1.0) / q.p.a;
  q.chi = -0.5 + 2.0 * u(rng);
  if (q.p.tilt && std::abs(q.chi * q.phi) * q.p.a > 1.0)
    q.chi = 0.9;
  return q;
}

TEST(BrushAuto, LinearErrorBoundHolds)
{
  // The bound of the linear model against the exact steady model, over random slips and spins from 1e-4 of the
  // envelope to all of it, the three pressures, tilt and no tilt; only where it could be chosen (<= 0.1).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  int checked = 0;
  for (int i = 0; i < 900; ++i)
  {
    const Point q = draw(rng, i, std::pow(10.0, -4.0 * u(rng)));
    const double pg = q.chi * q.phi, pp = q.phi - pg;
    const double bound = BrushLinear::errorBound(q.p, q.sigma, q.phi, pg, pp);
    if (bound > 0.1)
      continue;
    const double actual = forceDistance(BrushSteady(q.p).evaluate(q.sigma, q.phi, pg, pp, 1e-3 * bound + 1e-10),
                                        BrushLinear(q.p).evaluate(q.sigma, q.phi), q.p);
    ++checked;
    worst = std::max(worst, actual / bound);
    EXPECT_LE(actual, bound * (1.0 + 1e-3) + 1e-10) << "point " << i << " pressure " << toString(q.p.pressure)
                                                      << " tilt " << q.p.tilt;
  }
  std::printf("linear bound: %d points, largest error / bound %.3f\n", checked, worst);
  EXPECT_GT(checked, 300);
  EXPECT_GT(worst, 0.5);  // and it is not loose: pure slip follows the derived 0.35 s^2
}

TEST(BrushAuto, WithinItsTargetAtRandomPoints)
{
  // Held inputs, as a robot rolling at 1 m/s with 100 Hz odometry: auto's answer against the exact steady state,
  // at targets 0.1 %, 1 % and 5 %. bench/brush_accuracy does the same on 1000 points per target.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double target : { 1e-3, 1e-2, 5e-2 })
  {
    double worst = 0.0;
    for (int i = 0; i < 90; ++i)
    {
      Point q = draw(rng, i, std::pow(10.0, -2.0 * u(rng)));
      q.p.accuracy_target = target;
      BrushAuto model(q.p);
      const ContactKinematics k = ContactKinematics::fromSlips(q.sigma, q.phi, q.chi, 1.0);
      BrushForces f;
      for (int step = 0; step < 5; ++step)
        f = model.update(k, 0.01);
      // the reference to 1e-6 (eq. 4b's solver spends its reference budget before 1e-8 at some tilted points)
      const BrushForces ref = BrushSteady(q.p).evaluate(q.sigma, q.phi, q.chi * q.phi, (1 - q.chi) * q.phi, 1e-6,
                                                        nullptr, BrushSteady::kReferenceWork);
      ASSERT_FALSE(ref.flags & brush_flags::kAccuracyNotMet) << "point " << i;
      const double error = forceDistance(f, ref, q.p);
      worst = std::max(worst, error / target);
      EXPECT_LE(error, target + ref.error_estimate) << "target " << target << " point " << i << " ran " << toString(model.lastModel());
      EXPECT_LE(error, f.error_estimate + ref.error_estimate) << "target " << target << " point " << i;
      EXPECT_NE(model.lastModel(), BrushModelKind::Transient);  // constant inputs: a steady state
    }
    std::printf("auto at target %.0e: largest error %.2f of the target over 90 points\n", target, worst);
  }
}

TEST(BrushAuto, ALongStepAtHeldInputsEndsInTheSteadyState)
{
  // Whatever came before (here: spinning in place, in the transient model), a step that rolls further than the
  // longest path through the patch at held inputs leaves every bristle in the steady state of these inputs.
  BrushParameters p = figure4Parameters();
  p.accuracy_target = 1e-3;
  BrushAuto model(p);
  ContactKinematics spin;
  spin.omega_z = 3.0;
  spin.psi_dot = 3.0;
  model.update(spin, 0.2);
  ASSERT_EQ(model.lastModel(), BrushModelKind::Transient);
  const ContactKinematics k = ContactKinematics::fromSlips({ 0.05, 0.02 }, 3.33, 1.0, 1.0);
  const BrushForces f = model.update(k, 2.0 * p.a / 1.0);  // V_r dt = 2a
  EXPECT_NE(model.lastModel(), BrushModelKind::Transient);
  const BrushForces ref = BrushSteady(p).evaluate({ 0.05, 0.02 }, 3.33, 0.0, 0.0, 1e-9);
  // the answer carries the decaying difference from the transient model's last one, within the estimate
  EXPECT_LE(forceDistance(f, ref, p), f.error_estimate + 1e-12);
  BrushForces g;
  for (int i = 0; i < 10; ++i)
    g = model.update(k, 2.0 * p.a);
  EXPECT_LE(forceDistance(g, ref, p), 1e-3);
}

// The demo manoeuvre as contact kinematics in the paper frame (contact frame along the heading).
std::vector<ContactKinematics> demo(double dt, double R)
{
  std::vector<ContactKinematics> out;
  for (const ScenarioSample& s : Scenario(Scenario::defaultSegments(), R).sample(dt))
  {
    const Eigen::Vector3d omega(s.omega_body.x(), -s.omega_body.y(), -s.omega_body.z());  // ROS -> paper
    const Eigen::Vector2d V_C(s.velocity_body.x(), -s.velocity_body.y());
    const double yaw_rate = Scenario::defaultSegments()[s.segment].yaw_rate;
    out.push_back(ContactKinematics::fromWheel(omega, V_C, R, -yaw_rate));
  }
  return out;
}

TEST(BrushAuto, AlongTheDemoManoeuvre)
{
  // A 5 kg robot of 0.1 m radius (config/contact_estimator.yaml), the manoeuvre of launch/demo.launch at
  // 100 Hz. Reference: the transient model at resolution 128. Auto stays within its target (plus the
  // reference's own error), never jumps, and costs less than always running the transient model.
  BrushParameters p;
  p.a = 0.01;
  p.k = 2e8;
  p.F_z = 49.05;
  p.mu = 0.8;
  p.standstill_speed = 0.05;
  p.accuracy_target = 0.02;
  BrushAuto model(p);
  BrushParameters r = p;
  r.resolution = 128;
  BrushTransient reference(r);
  double worst = 0.0, worst_jump = 0.0, transient_cost = 0.0, estimate_misses = 0;
  BrushForces previous, previous_ref;
  const std::vector<ContactKinematics> ks = demo(0.01, 0.1);
  int transient_updates = 0, finest = 0;
  for (std::size_t i = 0; i < ks.size(); ++i)
  {
    const BrushForces f = model.update(ks[i], i ? 0.01 : 0.0);
    const BrushForces g = reference.update(ks[i], i ? 0.01 : 0.0);
    const double error = forceDistance(f, g, p);
    worst = std::max(worst, error);
    estimate_misses += error > f.error_estimate + g.error_estimate;
    if (i > 0)
      worst_jump = std::max(worst_jump, forceDistance(f, previous, p) - forceDistance(g, previous_ref, p));
    previous = f;
    previous_ref = g;
    transient_updates += model.lastModel() == BrushModelKind::Transient;
    finest = std::max(finest, model.transientResolution());
  }
  // always the transient model, at the finest resolution auto's own transient model took for the target
  const int n = finest;
  for (const ContactKinematics& k : ks)
    transient_cost += BrushAuto::transientStepCost(n) * std::max(1.0, std::ceil(k.V_r.norm() * 0.01 / (p.a / n)));
  std::printf("demo manoeuvre: max error %.3g of mu F_z (target %.3g), largest jump beyond the reference's %.3g, "
              "transient in %d of %zu updates (resolution %d at the end, %d the finest), cost %.3g of always-transient at the finest, "
              "estimate short %g times\n",
              worst, p.accuracy_target, worst_jump, transient_updates, ks.size(), model.transientResolution(), finest,
              model.cost() / transient_cost, estimate_misses);
  EXPECT_LE(worst, p.accuracy_target + 0.005);  // the reference at resolution 128 is itself ~0.2 % off
  // the estimate with the reference's covers every message (the lag of a sliding state after the slip's step at the end
  // of the acceleration once fell 1.5e-5 short, weighed by the linear theory's kernel: SteadyLag's comment)
  EXPECT_EQ(estimate_misses, 0);
  EXPECT_LT(worst_jump, p.accuracy_target);
  EXPECT_GT(transient_updates, 0);             // standstill and braking need it
  EXPECT_LT(transient_updates, static_cast<int>(ks.size()));
  EXPECT_LT(model.cost(), 0.5 * transient_cost);
}

TEST(BrushAuto, EstimateCoversRandomHistories)
{
  // Seeded random operating points over the envelope (as draw(), slips and spins scaled by 1e-2 to 1), each a
  // history of 40 messages after a long first step (which leaves both models in the steady state): noise on the
  // slips and spins (1e-3 to 1e-1), a ramp between two operating points, steps between them every 10 messages,
  // or a robot accelerating from 0.06 to 1.56 m/s at a held sliding velocity (the slips fall as 1 / V_r);
  // 0.03-2.5 patch radii rolled per message. Auto at 1 % against the transient model at resolution 64 (whose
  // own estimate is added): its estimate covers the error at 99 % of the points, never by less than half, and
  // no point is over the target without the flag.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  int checked = 0, short_count = 0, unflagged_over = 0;
  double worst = 0.0;
  for (int h = 0; h < 48; ++h)
  {
    BrushParameters p = test::drawEnvelopeParameters(rng, h);
    p.standstill_speed = 0.05;
    p.accuracy_target = 0.01;
    p.resolution = 16;
    const int kind = (h / 6) % 4;
    const double scale = std::pow(10.0, -2.0 * u(rng));
    const Eigen::Vector2d s0 = scale * Eigen::Vector2d(0.3 * (2.0 * u(rng) - 1.0), 0.1 * (2.0 * u(rng) - 1.0));
    const Eigen::Vector2d s1 = scale * Eigen::Vector2d(0.3 * (2.0 * u(rng) - 1.0), 0.1 * (2.0 * u(rng) - 1.0));
    const double a_phi0 = scale * (2.0 * u(rng) - 1.0), a_phi1 = scale * (2.0 * u(rng) - 1.0);
    const double noise = std::pow(10.0, -3.0 + 2.0 * u(rng));
    const double step = std::pow(10.0, -1.5 + 1.9 * u(rng));  // V_r dt / a
    const double chi = -0.5 + 2.0 * u(rng);
    BrushAuto model(p);
    BrushParameters fine = p;
    fine.resolution = 64;
    BrushTransient reference(fine);
    for (int m = 0; m < 40; ++m)
    {
      const double t = m / 39.0;
      Eigen::Vector2d sigma;
      double a_phi, V = 1.0;
      if (kind == 0)
      {
        sigma = s0 + noise * Eigen::Vector2d(g(rng), 0.3 * g(rng));
        a_phi = a_phi0 + noise * g(rng);
      }
      else if (kind == 1)
      {
        sigma = s0 + t * (s1 - s0);
        a_phi = a_phi0 + t * (a_phi1 - a_phi0);
      }
      else if (kind == 2)
      {
        const bool second = (m / 10) % 2;
        sigma = second ? s1 : s0;
        a_phi = second ? a_phi1 : a_phi0;
      }
      else
      {
        V = 0.06 + 1.5 * t;
        sigma = s0 * (0.3 / V);
        a_phi = a_phi0;
      }
      double phi = a_phi / p.a;
      if (p.tilt && std::abs(chi * phi) * p.a > 0.9)
        phi = std::copysign(0.9 / (std::abs(chi) * p.a), phi);
      const ContactKinematics k = ContactKinematics::fromSlips(sigma, phi, chi, V);
      const double dt = m == 0 ? 8.0 * p.a / V : step * p.a / (kind == 3 ? 1.0 : V);
      const BrushForces f = model.update(k, dt), r = reference.update(k, dt);
      if (m < 5)
        continue;
      const double error = forceDistance(f, r, p);
      const double ratio = error / (f.error_estimate + r.error_estimate + 1e-300);
      ++checked;
      short_count += ratio > 1.0;
      worst = std::max(worst, ratio);
      unflagged_over += error > p.accuracy_target + r.error_estimate && !(f.flags & brush_flags::kAccuracyNotMet);
    }
  }
  RecordProperty("worst_error_over_estimate", std::to_string(worst));
  EXPECT_LE(short_count, checked / 100) << "worst error / estimate " << worst;
  EXPECT_LE(worst, 2.0);
  EXPECT_EQ(unflagged_over, 0);
}

TEST(BrushAuto, AWarmStartAfterTheFrameTurnedRollsAlongThePhysicalDirection)
{
  // The estimator turns the patch frame where the rolling direction jumps (ContactEstimator: more than 0.5 rad between
  // messages, or rolling again after standstill): the lattice, the lag and the carried forces turn with it, and so must
  // the last rolling inputs, which a warm start into the transient model rolls. Fig. 4's robot at 16 settles in the
  // steady family, then the slips jump: the same history expressed in axes turned by a quarter or half a turn before
  // the jump (the lattice's axes then lie along the motion in both) answers the same forces, turned, to rounding.
  // Unturned, the warm start rolled the old direction's coordinates in the new axes, a state turned by the angle:
  // 0.13-0.18 of mu F_z apart.
  BrushParameters p = figure4Parameters();
  p.resolution = 16;
  p.accuracy_target = 1e-2;
  const double V = 1.0, dt = 0.002;
  const auto slips = [&](int i, int jump) {
    return ContactKinematics::fromSlips(i < jump ? Eigen::Vector2d(0.05, 0.02) : Eigen::Vector2d(-0.1, 0.25), 3.33,
                                        1.0, V);
  };
  // at held inputs it answers from the steady family from the first message; 3.6 transits on, no lattice rolls beside
  // it: the jump enters the transient model from a warm start (asserted below)
  const int jump = 180;
  for (double alpha : { 0.5 * boost::math::double_constants::pi, boost::math::double_constants::pi })
  {
    const double c = std::cos(alpha), s = std::sin(alpha);
    const auto turned = [&](const Eigen::Vector2d& v) {
      return Eigen::Vector2d(c * v.x() + s * v.y(), -s * v.x() + c * v.y());
    };
    BrushAuto model(p), in_turned_axes(p);
    double worst = 0.0;
    for (int i = 0; i <= jump + 20; ++i)
    {
      if (i == jump)
        in_turned_axes.rotateFrame(alpha);
      ContactKinematics k = slips(i, jump), k_turned = k;
      if (i >= jump)
      {
        k_turned.V_r = turned(k.V_r);
        k_turned.V_s = turned(k.V_s);
      }
      const BrushForces f = model.update(k, dt), g = in_turned_axes.update(k_turned, dt);
      if (i < jump)
      {
        ASSERT_NE(model.lastModel(), BrushModelKind::Transient) << "message " << i << ": no warm start at the jump";
        continue;
      }
      if (i == jump)
      {
        ASSERT_EQ(model.lastModel(), BrushModelKind::Transient);
      }
      BrushForces f_turned = f;
      const Eigen::Vector2d F = turned(Eigen::Vector2d(f.F_x, f.F_y));
      f_turned.F_x = F.x();
      f_turned.F_y = F.y();
      const double distance = forceDistance(f_turned, g, p);
      worst = std::max(worst, distance);
      EXPECT_LE(distance, 1e-6) << "turned by " << alpha << ", message " << i - jump << " after the jump";
    }
    std::printf("axes turned by %.3f rad before the jump: the two answers %.2e of mu F_z apart at most\n", alpha, worst);
  }
}

TEST(BrushAuto, StandstillTakesTheTransientModel)
{
  BrushAuto model(figure4Parameters());
  model.update(ContactKinematics::fromSlips({ 0.01, 0.0 }, 0.0, 1.0, 1.0), 0.01);
  ContactKinematics spin;
  spin.omega_z = 3.0;
  spin.psi_dot = 3.0;
  const BrushForces f = model.update(spin, 0.01);
  EXPECT_EQ(model.lastModel(), BrushModelKind::Transient);
  EXPECT_TRUE(f.valid());
  EXPECT_TRUE(std::isfinite(f.M_z));
  EXPECT_TRUE(std::isfinite(f.error_estimate));
}

TEST(BrushAuto, TheTransientResolutionGrowsUntilItsEstimateMeetsTheTarget)
{
  // Rolling with a lateral slip that changes within a patch length (no steady state holds: only the transient
  // model), at a tight target: the lattice doubles while the model's own estimate misses the target.
  BrushParameters p = figure4Parameters();
  p.resolution = 8;
  p.accuracy_target = 2e-3;
  BrushAuto model(p);
  const double V = 1.0, dt = 0.002;  // 2 mm per step, a = 50 mm
  BrushForces f;
  int grew_at = -1;
  for (int i = 0; i < 400; ++i)
  {
    const double s = V * dt * i;
    const double sigma_y = 0.01 * std::sin(2.0 * M_PI * s / (1.5 * p.a));
    f = model.update(ContactKinematics::fromSlips({ 0.0, sigma_y }, 0.0, 1.0, V), dt);
    if (i >= 10)  // once the changes have made a lag
    {
      ASSERT_EQ(model.lastModel(), BrushModelKind::Transient) << "step " << i;
    }
    ASSERT_TRUE(f.valid());
    if (grew_at < 0 && model.transientResolution() > 8)
      grew_at = i;
  }
  EXPECT_GE(grew_at, 0);
  EXPECT_GT(model.transientResolution(), 8);
  EXPECT_TRUE(model.transientResolution() == BrushAuto::kMaxTransientResolution || f.error_estimate <= p.accuracy_target)
      << "resolution " << model.transientResolution() << " estimate " << f.error_estimate;
}

TEST(BrushAuto, AtStandstillAMissedTargetIsReportedAndTheFinerLatticeStartsWhenRolling)
{
  // Spinning in place nothing renews the bristles, so a finer lattice could not forget its start: the estimate
  // reports the miss, and the finer lattice starts once the robot rolls.
  BrushParameters p = figure4Parameters();
  p.resolution = 8;
  p.accuracy_target = 2e-3;
  BrushAuto model(p);
  ContactKinematics spin;
  spin.omega_z = 3.0;
  spin.psi_dot = 3.0;
  BrushForces f;
  for (int i = 0; i < 40; ++i)
    f = model.update(spin, 0.05);
  EXPECT_EQ(model.lastModel(), BrushModelKind::Transient);
  EXPECT_EQ(model.transientResolution(), 8);
  EXPECT_GT(f.error_estimate, p.accuracy_target);
  // rolling off with a spin that keeps changing: still the transient model, and once a lattice of twice the
  // resolution has rolled the longest path beside it (2a), that one
  const double V = 1.0, dt = 0.002;
  for (int i = 0; i < 80; ++i)
  {
    const ContactKinematics k = ContactKinematics::fromSlips({ 0.0, 0.0 }, 0.3 * std::sin(0.5 * i) / p.a, 1.0, V);
    model.update(k, dt);
    EXPECT_EQ(model.lastModel(), BrushModelKind::Transient) << "step " << i;
    if (V * dt * (i + 1) < 2.0 * p.a)
    {
      EXPECT_EQ(model.transientResolution(), 8) << "step " << i;
    }
  }
  EXPECT_GT(model.transientResolution(), 8);
}

TEST(BrushAuto, TheResolutionComesBackDownAndResetRestoresIt)
{
  // Driven hard at a tight target (the lattice grows), then rolled gently at a loose one: the estimate stays far below
  // the target and the lattice halves again, every other bristle kept; reset() restores the configured resolution.
  BrushParameters p = figure4Parameters();
  p.resolution = 16;
  p.accuracy_target = 2e-3;
  BrushAuto model(p);
  const double V = 1.0, dt = 0.002;
  for (int i = 0; i < 400; ++i)
  {
    const double sigma_y = 0.01 * std::sin(2.0 * M_PI * V * dt * i / (1.5 * p.a));
    model.update(ContactKinematics::fromSlips({ 0.0, sigma_y }, 0.0, 1.0, V), dt);
  }
  const int hard = model.transientResolution();
  ASSERT_GT(hard, 16);
  model.setInputSpread(1.0);  // below the noise: the target rises to a quarter of it (auto_noise_fraction)
  BrushForces f;
  int lowest = hard;
  for (int i = 0; i < 600; ++i)
  {
    const double sigma_y = 0.002 * std::sin(2.0 * M_PI * V * dt * i / (1.5 * p.a));
    f = model.update(ContactKinematics::fromSlips({ 0.0, sigma_y }, 0.0, 1.0, V), dt);
    ASSERT_EQ(model.lastModel(), BrushModelKind::Transient) << "step " << i;
    EXPECT_LE(f.error_estimate, model.lastTarget()) << "step " << i << " resolution " << model.transientResolution();
    lowest = std::min(lowest, model.transientResolution());
  }
  EXPECT_LT(lowest, hard);
  model.reset();
  EXPECT_EQ(model.transientResolution(), 16);
}

TEST(BrushAuto, ASwitchIntoTheTransientModelCarriesNoLag)
{
  // Leaving the steady family because the steady state no longer holds (the slips jump), auto enters the transient
  // model and carries the difference between the two models at the same state, decaying: the last answer against the
  // lattice's forces before the step, a warm start's or, within a transit of leaving the transient model, those of the
  // lattice that rolled on beside the steady answers. Carrying the steady model's answer at the new inputs instead put
  // that model's lag into the answer (sweep seed 5021 with tilt: 0.343 of mu F_z off where the lattice alone was
  // 0.039). Fig. 4's robot at 16, at slips (0.05, 0.02) in the steady family, then at a first jump in the transient
  // model until it leaves it again; 80 messages later (past the transit: a warm start) or 5 (within it) the slips jump
  // again: at that jump and after, the answer against a lattice at 128 that rolled throughout is within its estimate,
  // and at the jump nearer it than a fifth of the steady answer's lag there.
  BrushParameters p = figure4Parameters();
  p.resolution = 16;
  p.accuracy_target = 1e-2;
  BrushParameters fine = p;
  fine.resolution = 128;
  const double V = 1.0, dt = 0.002;  // 2 mm a message: the offset decays by e^{-0.4} = 0.67 over one
  const Eigen::Vector2d start(0.05, 0.02), between(0.12, 0.0);
  for (const Eigen::Vector2d& after : { Eigen::Vector2d(0.15, 0.02), Eigen::Vector2d(-0.1, 0.25) })
    for (const int after_leaving : { 80, 5 })
    {
      BrushAuto model(p);
      BrushTransient reference(fine);
      BrushSteady steady(p);
      int left = -1, jump = -1;
      bool entered = false;
      for (int i = 0; i < 2000 && (jump < 0 || i <= jump + 20); ++i)
      {
        const Eigen::Vector2d sigma = i < 100 ? start : jump < 0 || i < jump ? between : after;
        const ContactKinematics k = ContactKinematics::fromSlips(sigma, 3.33, 1.0, V);
        const BrushForces f = model.update(k, dt), r = reference.update(k, dt);
        entered = entered || (i >= 100 && model.lastModel() == BrushModelKind::Transient);
        if (entered && left < 0 && model.lastModel() != BrushModelKind::Transient)
        {
          left = i;
          jump = left + after_leaving;
        }
        if (jump < 0 || i < jump)
          continue;
        const double error = forceDistance(f, r, p);
        EXPECT_LE(error, f.error_estimate + r.error_estimate) << "message " << i - jump << " after the jump";
        if (i == jump)
        {
          ASSERT_EQ(model.lastModel(), BrushModelKind::Transient);
          const double lag = forceDistance(steady.update(k, dt), r, p);
          std::printf("slips (%.2f, %.2f), %d messages after leaving: at the jump %.4f of mu F_z off, the steady "
                      "answer's lag %.4f\n", after.x(), after.y(), after_leaving, error, lag);
          EXPECT_GT(lag, 2.0 * p.accuracy_target) << "the steady state held: nothing to test";
          EXPECT_LT(error, 0.2 * lag);
        }
      }
      ASSERT_GE(jump, 0) << "auto never left the transient model";
    }
}

TEST(BrushAuto, ReturningWithinATransitOfLeavingRollsOnWithoutAWarmStart)
{
  // On leaving the transient model for the steady family the lattice keeps rolling for a transit beside the steady
  // answers: a lag that comes back within it (on the manoeuvre's weave every visit to the steady family ended one
  // message later) returns to that lattice as it stands, not to a warm start that rolls 2.5 transits in one message. A
  // return after the transit starts warm, as before. Which one happened shows in the estimated cost (cost(): a warm start
  // adds 5 * resolution steps of the lattice, a message's roll one). Either way every answer is within its estimate of a
  // lattice eight times as fine that never left.
  BrushParameters p = figure4Parameters();
  p.resolution = 16;
  p.accuracy_target = 1e-2;
  BrushParameters fine = p;
  fine.resolution = 128;
  const double V = 1.0, dt = 0.002;  // 2 mm a message: a transit (2a) is 50 messages
  const auto slips = [V](int i, int jump) {
    const double held = 0.05 + 0.03 * std::sin(2.0 * M_PI * 100 / 40.0);
    const double sigma_x = i < 100 ? 0.05 + 0.03 * std::sin(2.0 * M_PI * i / 40.0) : (i < jump ? held : 0.15);
    return ContactKinematics::fromSlips({ sigma_x, 0.02 }, 3.33, 1.0, V);
  };
  for (int after : { 5, 80 })  // messages in the steady family before the slips jump: within the transit, past it
  {
    // where auto leaves the transient model at these held inputs
    int left = -1;
    {
      BrushAuto probe(p);
      for (int i = 0; i < 1000 && left < 0; ++i)
      {
        probe.update(slips(i, 100000), dt);
        if (i >= 100 && probe.lastModel() != BrushModelKind::Transient)
          left = i;
      }
    }
    ASSERT_GE(left, 100);
    const int jump = left + after;
    BrushAuto model(p);
    BrushTransient reference(fine);
    for (int i = 0; i <= jump; ++i)
    {
      const double before = model.cost();
      const BrushForces f = model.update(slips(i, jump), dt);
      const BrushForces r = reference.update(slips(i, jump), dt);
      if (i > left && i < jump)
      {
        ASSERT_NE(model.lastModel(), BrushModelKind::Transient) << "message " << i;
      }
      const double error =
          std::max({ std::abs(f.F_x - r.F_x), std::abs(f.F_y - r.F_y), std::abs(f.M_z - r.M_z) / p.a }) / (p.mu * p.F_z);
      if (i >= 150)  // (the reference started from an unloaded patch, auto from the steady state: both forgotten)
      {
        EXPECT_LE(error, f.error_estimate + r.error_estimate) << "after " << after << ", message " << i;
      }
      if (i == jump)
      {
        ASSERT_EQ(model.lastModel(), BrushModelKind::Transient) << "after " << after;
        const int n = model.transientResolution();
        const double warm = BrushAuto::transientStepCost(n) * 5.0 * n, spent = model.cost() - before;
        std::printf("back %d messages after leaving: the returning message's work %ld, estimated cost %.0f ns "
                    "(a warm start's %.0f)\n", after, f.work, spent, warm);
        if (after < 50)
          EXPECT_LT(spent, 0.2 * warm);
        else
          EXPECT_GE(spent, warm);
      }
    }
  }
}

TEST(BrushAuto, ANoiseThatFallsBetweenLagChecksKeepsTheTargetPositive)
{
  // In the transient model the lag of the steady state is checked every quarter radius of travel, not at every message;
  // between checks the last one's verdict stands. The target follows the inputs' noise: falling between two checks, it
  // left a verdict "steady" whose lag exceeded the new target, and on leaving the transient model there the steady
  // solver was asked for target - lag < 0 and threw (a random stream of the estimator's tests found it). Here slips that
  // swing keep the lag between the two targets, and the noise falls at each message in turn of a window around the
  // leaving (without the check against the current target: the solver threw for 7 of these 20 histories). Every update
  // answers, finite, flagged wherever it misses the target.
  BrushParameters p = figure4Parameters();
  p.resolution = 16;
  p.accuracy_target = 1e-3;
  p.auto_noise_fraction = 0.25;
  const double V = 1.0, dt = 0.002;
  int transient = 0;
  for (int fall = 110; fall < 130; ++fall)
  {
    BrushAuto model(p);
    model.setInputSpread(0.2);  // the target a quarter of it, 5 % of mu F_z
    for (int i = 0; i < 200; ++i)
    {
      if (i == fall)
        model.setInputSpread(0.0);  // back to accuracy_target
      const double sigma_x = 0.1 + 0.02 * std::sin(2.0 * M_PI * i / 60.0);
      BrushForces f;
      ASSERT_NO_THROW(f = model.update(ContactKinematics::fromSlips({ sigma_x, 0.02 }, 3.33, 1.0, V), dt))
          << "noise falling at message " << fall << ", message " << i;
      ASSERT_TRUE(std::isfinite(f.F_x) && std::isfinite(f.F_y) && std::isfinite(f.M_z) && std::isfinite(f.error_estimate));
      if (f.error_estimate > model.lastTarget())
      {
        EXPECT_TRUE(f.flags & brush_flags::kAccuracyNotMet) << "noise falling at message " << fall << ", message " << i;
      }
      transient += model.lastModel() == BrushModelKind::Transient;
    }
  }
  EXPECT_GT(transient, 0);
}

TEST(BrushAuto, TheLagOnLeavingTheTransientModelHoldsTheNoiseBetweenChecks)
{
  // In the transient model the lag is checked every quarter radius of travel; a check takes the inputs' net change
  // since the last one, not the noise's excursions between, which the bristles remember. Leaving with that lag, the
  // steady family's estimate fell short of its error (scripts/stream_sweep.py seed 1062: a 5.4-mm patch at 1 kHz,
  // rolling at 0.8-1 m/s with 9 % slip and the odometry's noise, by 1.2x beyond the reference's own estimate). Such
  // streams here, auto at 1 % against the transient model at resolution 128 (its own estimate added): every answer of
  // the steady family within its estimate (58 of them). Before the lag was checked at every message once a check found
  // steady conditions, 7 of these 8 histories had answers short of it, by up to 1.24x (285 answers).
  BrushParameters p;
  p.a = 0.0054;
  p.F_z = 13.95 * 9.81;
  p.mu = 1.04;
  p.k = 1.03e8;
  p.pressure = PressureDistribution::Parabolic;
  p.sliding_law = SlidingLaw::Coulomb;
  p.standstill_speed = 0.05;
  p.accuracy_target = 0.01;
  p.resolution = 32;
  BrushParameters fine = p;
  fine.resolution = 128;
  const double dt = 1e-3;
  int steady_family = 0, short_count = 0, short_histories = 0;
  double worst = 0.0;
  for (int h = 0; h < 8; ++h)
  {
    const int short_before = short_count;
    std::mt19937_64 rng(1062 + h);
    std::normal_distribution<double> g(0.0, 1.0);
    BrushAuto model(p);
    BrushTransient reference(fine);
    for (int m = 0; m < 250; ++m)
    {
      const double V = 0.8 + 0.2 * m / 250.0;
      const Eigen::Vector2d sigma(0.09 + 0.015 * g(rng), 0.01 * g(rng));
      const double phi = 1.0 * g(rng);
      const ContactKinematics k = ContactKinematics::fromSlips(sigma, phi, 1.0, V);
      const double step = m == 0 ? 8.0 * p.a / V : dt;
      const BrushForces f = model.update(k, step), r = reference.update(k, step);
      if (m < 20 || model.lastModel() == BrushModelKind::Transient)
        continue;
      ++steady_family;
      const double ratio = forceDistance(f, r, p) / (f.error_estimate + r.error_estimate + 1e-300);
      short_count += ratio > 1.0;
      worst = std::max(worst, ratio);
    }
    short_histories += short_count > short_before;
  }
  RecordProperty("steady_family_answers", std::to_string(steady_family));
  RecordProperty("worst_error_over_estimate", std::to_string(worst));
  EXPECT_GT(steady_family, 20);
  EXPECT_EQ(short_count, 0) << "worst error / estimate " << worst << " over " << steady_family << " answers, "
                            << short_histories << " of the histories";
}

// One message of noisy odometry at 100 Hz (velocity_noise [m/s] on the speed and, over it, on the slips; 0.02 rad/s on
// the spin rate) through `model` within `budget`: its work within the budget, its estimate finite and flagged exactly
// where it is above the target. (noise: a standard normal kept across messages, as it draws its values in pairs)
BrushForces noisyMessage(BrushAuto& model, std::mt19937_64& rng, std::normal_distribution<double>& noise, long budget,
                         double velocity_noise, double V, const Eigen::Vector2d& sigma, double spin_rate)
{
  const double v = V + velocity_noise * noise(rng);
  model.setWorkBudget(budget);
  const BrushForces f = model.update(ContactKinematics::fromSlips({ sigma.x() + velocity_noise * noise(rng) / v,
                                                                    sigma.y() + velocity_noise * noise(rng) / v },
                                                                  (spin_rate + 0.02 * noise(rng)) / v, 1.0, v),
                                     0.01);
  EXPECT_LE(f.work, budget + BrushModel::kWorkGranularity);
  EXPECT_TRUE(std::isfinite(f.error_estimate));
  EXPECT_EQ(f.error_estimate > model.lastTarget(), (f.flags & brush_flags::kAccuracyNotMet) != 0);
  if (f.flags & brush_flags::kBudgetLimited)
  {
    EXPECT_TRUE(f.flags & brush_flags::kAccuracyNotMet) << "a met target is held back by nothing";
  }
  return f;
}

// The default robot (config/contact_estimator.yaml: a = 1 cm, 5 kg, mu 0.8, k = 2e8 N/m^3, resolution 32) at a target.
BrushParameters defaultRobot(double target)
{
  BrushParameters p;
  p.a = 0.01, p.F_z = 5.0 * 9.81, p.mu = 0.8, p.k = 2e8;
  p.resolution = 32;
  p.accuracy_target = target;
  return p;
}

// One message of its pivot as data/manoeuvre.bag's (0.3 m/s, lateral slip 0.08, the shell spinning at 12 rad/s, the
// demo's noise, 100 Hz) within `budget`.
BrushForces pivotMessage(BrushAuto& model, std::mt19937_64& rng, std::normal_distribution<double>& noise, long budget)
{
  return noisyMessage(model, rng, noise, budget, 0.005, 0.3, { 0.0, 0.08 }, 12.0);
}

TEST(BrushAuto, WhereTheBudgetHoldsAMissedTargetTheAnswerSaysSo)
{
  // The default robot (config/contact_estimator.yaml's a = 1 cm, 5 kg, mu 0.8, k = 2e8 N/m^3, resolution 32, a 1 %
  // target) pivoting as data/manoeuvre.bag does (0.3 m/s, lateral slip 0.08, the shell spinning at 12 rad/s, the
  // demo's noise, 100 Hz). Within the default budget (what the covariance leaves of 1e5) resolution 32 misses the
  // target at times, and 64, which would meet it, does not fit: those answers carry kBudgetLimited beside
  // kAccuracyNotMet (a larger work_budget lets auto refine). With a budget that fits 64 the same stream refines, meets
  // the target at those messages, and no answer says the budget held it.
  const BrushParameters p = defaultRobot(1e-2);
  std::vector<std::uint32_t> flags[2];
  int budget_limited[2] = {}, flagged[2] = {};
  const long budgets[2] = { 90000, 2000000 };
  for (int b = 0; b < 2; ++b)
  {
    BrushAuto model(p);
    std::mt19937_64 rng(404);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (int i = 0; i < 200; ++i)
    {
      const BrushForces f = pivotMessage(model, rng, noise, budgets[b]);
      flags[b].push_back(f.flags);
      budget_limited[b] += (f.flags & brush_flags::kBudgetLimited) != 0;
      flagged[b] += (f.flags & brush_flags::kAccuracyNotMet) != 0;
    }
  }
  int bought = 0;  // messages the budget held that the larger one answered within the target
  for (int i = 0; i < 200; ++i)
    bought += (flags[0][i] & brush_flags::kBudgetLimited) && !(flags[1][i] & brush_flags::kAccuracyNotMet);
  std::printf("pivot at 12 rad/s: budget 9e4: %d flagged, %d of them held by the budget; budget 2e6: %d flagged, %d "
              "held; the larger budget met the target at %d of the held ones\n",
              flagged[0], budget_limited[0], flagged[1], budget_limited[1], bought);
  EXPECT_GE(budget_limited[0], 10);
  EXPECT_EQ(budget_limited[1], 0);
  EXPECT_LT(flagged[1], flagged[0]);
  EXPECT_GE(bought, budget_limited[0] * 9 / 10);
}

TEST(BrushAuto, ALagCheckNeverCoarsensALatticeWhoseStepFits)
{
  // The default robot (config/contact_estimator.yaml: a = 1 cm, 5 kg, mu 0.8, k = 2e8 N/m^3, resolution 32, a budget of
  // 1e5 units) pivoting as data/manoeuvre.bag does (0.3 m/s, lateral slip 0.08, the shell spinning at 12 rad/s, the
  // demo's noise, 100 Hz) at a 0.1 % target, with what the covariance leaves of the budget. The lattice's step fits
  // (about 75 k units) but not beside a lag check at that target (up to 36 k): the check waits, and the lattice keeps
  // its resolution. (Before, the check took half of what was left; the lattice, coarsened to 8 and then refined to 16,
  // stayed there, since a finer one needs eight times its step.) Every update within its budget, every estimate
  // finite and flagged above the target.
  const BrushParameters p = defaultRobot(1e-3);
  BrushAuto model(p);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  int transient = 0, lowest = p.resolution;
  for (int i = 0; i < 200; ++i)
  {
    const BrushForces f = pivotMessage(model, rng, noise, 90000);
    ASSERT_TRUE(std::isfinite(f.error_estimate)) << "message " << i;
    if (model.lastModel() == BrushModelKind::Transient)
    {
      ++transient;
      lowest = std::min(lowest, model.lastResolution());
    }
  }
  std::printf("pivot at a 0.1 %% target: %d of 200 messages transient, lowest resolution %d\n", transient, lowest);
  EXPECT_GT(transient, 150);
  EXPECT_EQ(lowest, p.resolution);
}

TEST(BrushAuto, ALagCheckThatKeepsRunningOutOfRoomIsTriedEverLessOften)
{
  // The default robot pivoting as data/manoeuvre.bag does (0.3 m/s, lateral slip 0.08, the shell spinning at 12 rad/s,
  // the demo's noise, 100 Hz) at the default 1 % target, with what the covariance leaves of the default budget. Beside
  // the lattice's step (about 70 k units) a lag check cannot finish its steady evaluation (it needs more than the
  // 20-30 k left): each one spends what is left and gives no verdict. After such a check the next waits 4, 8 and then
  // 16 patch radii of rolling, not 2 every time. A check's message spends what the lattice left: the messages within a
  // granularity of the budget count them, 5 of the 590 here (34 when every check waited 2 radii; along the recording
  // the pivot's p99 work fell from 88 k units to 73 k).
  const BrushParameters p = defaultRobot(1e-2);
  BrushAuto model(p);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  const long budget = 90000;
  constexpr int kMessages = 600;  // 1.8 m: 90 transits
  int full = 0, transient = 0;
  for (int i = 0; i < kMessages; ++i)
  {
    const BrushForces f = pivotMessage(model, rng, noise, budget);
    transient += model.lastModel() == BrushModelKind::Transient;
    if (i >= 10)
      full += f.work > budget - BrushModel::kWorkGranularity;
  }
  std::printf("pivot at 1 %%: %d of %d messages transient, %d spent the budget\n", transient, kMessages, full);
  EXPECT_GT(transient, kMessages - 20);
  EXPECT_LE(full, 13);  // checks after 2, 6 and 14 radii, then every 16: at most 13 over the 180 radii rolled
}

TEST(BrushAuto, ALatticeTheBudgetCoarsenedComesBackOnceItFitsAgain)
{
  // A random robot of the stream sweep (seed 1253: a = 25 mm, 4.9 kg, mu 1.09, k = 3.2e8 N/m^3, parabolic; resolution
  // 32, a 1 % target, what the covariance leaves of the budget) weaving at 1 m/s with a lateral slip of 0.1 and the
  // shell spinning at 15.6 rad/s, where 32's step does not fit (the budget coarsens the lattice), then rolling straight
  // with 6 % slip, slowing from 1.9 to 0.5 m/s, where it does. The lattice comes back to 32 within the roll, and there
  // meets the target. (Before, a finer lattice needed eight times the coarse one's step: it stayed at 16.)
  BrushParameters p;
  p.a = 0.0254, p.F_z = 4.93 * 9.81, p.mu = 1.087, p.k = 3.2e8;
  p.resolution = 32;
  p.accuracy_target = 1e-2;
  BrushAuto model(p);
  std::mt19937_64 rng(1253);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto message = [&](double V, double sigma_x, double sigma_y, double spin_rate) {
    return noisyMessage(model, rng, noise, 81000, 0.01, V, { sigma_x, sigma_y }, spin_rate);
  };
  for (int i = 0; i < 150; ++i)
    message(1.0, 0.0, -0.1, -15.6);
  ASSERT_LT(model.transientResolution(), 32) << "the weave should not fit resolution 32 within the budget";
  int back = -1, at_32 = 0, met = 0;
  for (int i = 0; i < 100; ++i)
  {
    const BrushForces f = message(1.9 - 0.014 * i, 0.064, 0.0, 0.0);
    if (model.lastModel() == BrushModelKind::Transient && model.lastResolution() == 32)
    {
      back = back < 0 ? i : back;
      ++at_32;
      met += f.error_estimate <= model.lastTarget();
    }
  }
  std::printf("back at resolution 32 after %d messages of the roll; there at %d messages, %d within the target\n", back,
              at_32, met);
  ASSERT_GE(back, 0) << "the lattice did not come back to the configured resolution";
  EXPECT_LE(back, 20);
  EXPECT_EQ(met, at_32);
}

TEST(BrushAuto, WhereTheSteadySolverCannotFinishWithinTheBudgetTheTransientModelAnswers)
{
  // A random robot of the stream sweep with tilt (stream_sweep.py --set tilt=true, seed 5009: a = 48 mm, 2.4 kg,
  // mu 0.77, k = 9e7 N/m^3, Hertzian, eq. 4b, resolution 32, a 1 % target, what the covariance leaves of the budget)
  // weaving at 1.47 m/s at held inputs, 100 Hz. Its steady state needs about 2.2e5 units of the steady solver at any
  // target. Before, auto stayed in the steady family on lag checks that had run out of their room, and answered with
  // the budget's best steady answer at every message: F_y 0.02-3 N against 4.84, estimates of 4-14 mu F_z. Now, after
  // one such answer, the transient model answers; its warm start fits the budget at 8 only, and a lattice of 16 (whose
  // step, predicted as its own substeps over its own window, fits beside it) takes over after the longest arc. Every
  // answer within its estimate of the converged steady state (the state at held inputs); from two transits on within
  // 1 % of mu F_z.
  BrushParameters p;
  p.a = 0.04839, p.F_z = 23.855, p.mu = 0.76926, p.k = 9.045e7;
  p.pressure = PressureDistribution::Hertzian;
  p.tilt = true;
  p.resolution = 32;
  p.accuracy_target = 1e-2;
  const Eigen::Vector2d sigma(-0.0015, -0.0713);
  const double phi = -6.854, chi = 0.9634, V = 1.473;
  BrushSteady::Stats stats;
  const BrushForces exact = BrushSteady(p).evaluate(sigma, phi, chi * phi, (1.0 - chi) * phi, 1e-3, &stats);
  ASSERT_FALSE(exact.flags & brush_flags::kAccuracyNotMet);
  ASSERT_GT(stats.work, 100000) << "the steady state fits the budget: the case shows nothing";
  BrushAuto model(p);
  double worst_late = 0.0, worst_ratio = 0.0;
  int transient = 0;
  for (int i = 0; i < 40; ++i)
  {
    model.setWorkBudget(60000);
    const BrushForces f = model.update(ContactKinematics::fromSlips(sigma, phi, chi, V), i == 0 ? 0.0 : 0.01);
    EXPECT_LE(f.work, 60000 + BrushModel::kWorkGranularity);
    transient += model.lastModel() == BrushModelKind::Transient;
    const double e = forceDistance(f, exact, p);
    worst_ratio = std::max(worst_ratio, (e - exact.error_estimate) / f.error_estimate);
    if (i >= 15)
      worst_late = std::max(worst_late, e);  // two transits (the longest arc, about 2.2 a) after the first message
  }
  std::printf("budget-starved steady state: %d of 40 messages transient, at %d at the end; largest error after two "
              "transits %.3g; error / estimate at most %.3g\n",
              transient, model.lastResolution(), worst_late, worst_ratio);
  EXPECT_GE(transient, 39);
  EXPECT_GE(model.lastResolution(), 16);
  EXPECT_LE(worst_late, 0.01);
  EXPECT_LE(worst_ratio, 1.0);
}

TEST(BrushAuto, EveryUpdatesWorkStaysWithinItsBudget)
{
  // Random hostile histories (slips and spins over the envelope, jumps, standstill, spin in place, steps from 0.1 ms
  // to 0.5 s) at budgets from a few steady paths to plenty: each update's counted work within the budget (but for the
  // substep or path under way, kWorkGranularity), its estimate finite, flagged wherever it misses the target.
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int updates = 0, flagged = 0, held = 0;
  long worst_over = 0;
  for (long budget : { 6000L, 20000L, 100000L })
    for (int run = 0; run < 6; ++run)
    {
      BrushParameters p = test::drawEnvelopeParameters(rng, run);
      p.accuracy_target = std::pow(10.0, -1.0 - 2.0 * u(rng));
      BrushAuto model(p);
      for (int i = 0; i < 120; ++i)
      {
        ContactKinematics k;
        const double V = u(rng) < 0.15 ? 0.0 : 2.0 * u(rng);
        k.V_r = Eigen::Vector2d(V, 0.0);
        k.V_s = Eigen::Vector2d(0.5 * (2.0 * u(rng) - 1.0), 0.5 * (2.0 * u(rng) - 1.0)) * std::max(V, 0.1);
        k.omega_z = 20.0 * (2.0 * u(rng) - 1.0);
        k.psi_dot = p.tilt ? 0.3 * k.omega_z : k.omega_z;
        const double dt = std::pow(10.0, -4.0 + 3.7 * u(rng));
        model.setWorkBudget(budget);
        const BrushForces f = model.update(k, dt);
        ++updates;
        worst_over = std::max(worst_over, f.work - budget);
        EXPECT_LE(f.work, budget + BrushModel::kWorkGranularity) << "budget " << budget << " run " << run << " step " << i;
        EXPECT_TRUE(std::isfinite(f.error_estimate));
        if (f.error_estimate > model.lastTarget())
        {
          EXPECT_TRUE(f.flags & brush_flags::kAccuracyNotMet);
          ++flagged;
        }
        if (f.flags & brush_flags::kBudgetLimited)
        {
          EXPECT_TRUE(f.flags & brush_flags::kAccuracyNotMet) << "budget " << budget << " run " << run << " step " << i;
          ++held;
        }
      }
    }
  std::printf("work budget: %d updates, %d flagged (the target missed within the budget; %d of them held by it), "
              "largest overrun %ld\n",
              updates, flagged, held, worst_over);
  EXPECT_GT(held, 0);
}


TEST(BrushAuto, ASwitchFromASteadyAnswerThatMissedItsTargetCarriesNothingOfIt)
{
  // The pivot of stream sweep seed 1014 (a = 14.7 mm, 1.14 kg, mu 0.69, k = 6.9e7 N/m^3, uniform pressure, eq. 4b,
  // resolution 32; lateral slip 0.25 at 0.33 m/s, the shell spinning at 85 rad/m), 1 kHz with the demo's noise, at the
  // target the covariance raised it to there (0.25). Its steady state takes 3e5 units of the steady solver: within these
  // budgets the steady family answers once from a solve cut short (estimate about 3) and auto enters the transient
  // model, whose sliding bristles renew within a few messages at this spin. The switch used to carry the difference
  // between that cut-short answer, or one as short evaluated at the new inputs, and the lattice's, decaying over half a
  // patch radius (a hundred messages here): 0.25-0.34 of mu F_z off for the messages after it. From an answer that
  // missed its target nothing is carried: from the third transient answer on within 0.1 (measured 0.043 at most, against 0.12-0.36 carrying it).
  BrushParameters p;
  p.a = 0.0147083, p.F_z = 1.13735 * 9.81, p.mu = 0.686519, p.k = 6.94217e7;
  p.pressure = PressureDistribution::Uniform;
  p.resolution = 32;
  p.accuracy_target = 0.25;
  const Eigen::Vector2d sigma(-0.02, 0.25);
  const double phi = -85.0, V = 0.327;
  BrushSteady::Stats stats;
  const BrushForces exact = BrushSteady(p).evaluate(sigma, phi, phi, 0.0, 1e-4, &stats);
  ASSERT_FALSE(exact.flags & brush_flags::kAccuracyNotMet);
  for (const long budget : { 40000L, 80000L, 90000L })
  {
    ASSERT_GT(stats.work, 3 * budget) << "the steady state fits the budget: the case shows nothing";
    std::mt19937_64 rng(1);
    std::normal_distribution<double> noise;
    BrushAuto model(p);
    int transient = 0;
    double worst = 0.0;
    for (int i = 0; i < 20; ++i)
    {
      const double v = V + 0.01 * noise(rng);
      const double sx = sigma.x() + 0.01 * noise(rng) / v, sy = sigma.y() + 0.01 * noise(rng) / v;
      const double spin = (phi * V + 0.02 * noise(rng)) / v;
      model.setWorkBudget(budget);
      const BrushForces f = model.update(ContactKinematics::fromSlips({ sx, sy }, spin, 1.0, v), i == 0 ? 0.0 : 1e-3);
      if (model.lastModel() != BrushModelKind::Transient)
      {
        ASSERT_EQ(transient, 0) << "budget " << budget << ": back in the steady family at message " << i;
        continue;
      }
      if (++transient >= 3)
        worst = std::max(worst, forceDistance(f, exact, p));
    }
    std::printf("budget %ld: %d transient answers, from the third on at most %.4f of mu F_z off\n", budget, transient,
                worst);
    EXPECT_GE(transient, 5) << "budget " << budget;
    EXPECT_LT(worst, 0.1) << "budget " << budget;
  }
}

}  // namespace
}  // namespace sphere_contact_estimator
