// The node's core path allocates nothing per message (docs/node.md): every heap allocation of the process is counted
// while ContactEstimator::update runs, over odometry streams that reach what the node meets (the recorded manoeuvre's
// segments at 100 Hz and 1 kHz with the demo's noise and its covariance, every brush model and law, tilt, each
// rolling-resistance model; and a hostile stream of jumps, gaps, jittered and repeated stamps, standstill, bad numbers
// and huge slips), after one pass of the same stream has sized what is sized once.
// Every allocation is counted (test/support/allocation_count.h: operator new's, Eigen's, the C library's); not under
// the sanitizers, which own the allocator.

// STL
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

// Eigen
#include <Eigen/Geometry>

// GTest
#include <gtest/gtest.h>

// Package
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"
#include "allocation_count.h"
#include "manoeuvre.h"
#include "scenario.h"

namespace sphere_contact_estimator
{
namespace
{
using test::AllocationCount;

// The manoeuvre as odometry at `rate` with the demo's noise (0.005 m/s, 0.02 rad/s) and that covariance, in the ground
// frame, as the node hands it to the estimator.
std::vector<EstimatorInput> manoeuvreStream(double rate, unsigned seed)
{
  const double noise_v = test::kManoeuvreNoiseVelocity, noise_w = test::kManoeuvreNoiseOmega;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  TwistCovariance C = TwistCovariance::Zero();
  C(0, 0) = C(1, 1) = noise_v * noise_v;
  C(3, 3) = C(4, 4) = C(5, 5) = noise_w * noise_w;
  std::vector<EstimatorInput> stream;
  for (const ScenarioSample& s : Scenario(test::manoeuvreSegments(), 0.1).sample(1.0 / rate))
  {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EstimatorInput in;
    in.stamp = 100.0 + s.time;
    in.omega = R * (s.omega_body + noise_w * Eigen::Vector3d(g(rng), g(rng), g(rng)));
    in.v_contact = R * (s.velocity_body + noise_v * Eigen::Vector3d(g(rng), g(rng), 0.0));
    in.twist_covariance = rotateTwistCovariance(C, R);
    in.body_heading = s.yaw;
    stream.push_back(in);
  }
  return stream;
}

// What a faulty source sends: the manoeuvre at 1 kHz with stamps that jitter by +-0.5 ms, repeat, jump back by a
// second and forward past max_step; messages with NaN or infinite numbers, an invalid or unknown covariance; bursts
// of huge slips and spins; standstill between.
std::vector<EstimatorInput> hostileStream(unsigned seed)
{
  std::vector<EstimatorInput> stream = manoeuvreStream(1000.0, seed);
  std::mt19937_64 rng(seed + 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  double shift = 0.0;
  for (std::size_t i = 0; i < stream.size(); ++i)
  {
    EstimatorInput& in = stream[i];
    in.stamp += shift + (u(rng) - 0.5) * 1e-3;
    const double draw = u(rng);
    if (draw < 0.002)
      shift -= 1.0;  // a looping bag: time goes backwards
    else if (draw < 0.004)
      shift += 1.0;  // a gap past max_step
    else if (draw < 0.01 && i > 0)
      in.stamp = stream[i - 1].stamp;  // a repeated stamp
    else if (draw < 0.02)
      in.omega.x() = nan;
    else if (draw < 0.025)
      in.v_contact.y() = inf;
    else if (draw < 0.035)
      in.twist_covariance(0, 0) = -1.0;  // unknown
    else if (draw < 0.045)
      in.twist_covariance(0, 1) = 1.0;  // not symmetric: invalid
    else if (draw < 0.05)
      in.twist_covariance *= u(rng) < 0.5 ? 1e300 : 1e150;  // finite, but too large to carry through
    else if (draw < 0.06)
    {
      in.v_contact *= 30.0;  // a huge slip and spin
      in.omega.z() *= 50.0;
    }
    else if (draw < 0.08)
    {
      in.omega.head<2>().setZero();  // standstill, or the centre dragged while the shell does not turn
      in.v_contact *= u(rng);
    }
    // checked as the node checks it (OdometryEstimator): only an Ok one is handed on
    in.twist_covariance_status = checkTwistCovariance(in.twist_covariance);
    if (in.twist_covariance_status != CovarianceStatus::Ok)
      in.twist_covariance.setZero();
  }
  return stream;
}

// Runs the stream three times through one estimator and returns the allocations of the third pass, with the messages
// that allocated (and, given, how often that pass changed the transient lattice's resolution). The passes before size
// what is sized once: the first from a new estimator, the second from where the first left it (the gap between resets
// the bristles, not the frame), as the third does, so that the third repeats the second message by message and any
// allocation it makes is one per message. (With two passes, the second's lattice sizes could differ from the first's:
// with hold_within_noise the start's held motion arrives in the frame the last pass left, auto's choices drifted
// apart by 1e-3 of the work, and at one message the second pass sized a lattice the first never had.)
long warmPassAllocations(const EstimatorSettings& settings, const std::vector<EstimatorInput>& stream,
                         std::string& where, int* resolution_changes = nullptr)
{
  ContactEstimator e(settings);
  const double offset = stream.back().stamp - stream.front().stamp + 10.0;  // on, not back: no reset at the start
  EstimatorInput in;
  for (int pass = 0; pass < 2; ++pass)  // (uncounted)
    for (const EstimatorInput& message : stream)
    {
      in = message;
      in.stamp += pass * offset;
      e.update(in);
    }
  long total = 0;
  int last_resolution = 0;
  for (std::size_t i = 0; i < stream.size(); ++i)
  {
    in = stream[i];
    in.stamp += 2.0 * offset;
    long n;
    const ContactEstimateData* d;
    {
      const AllocationCount count;
      d = e.update(in);
      n = count.count();
    }
    if (resolution_changes && d && d->brush_resolution > 0)
    {
      *resolution_changes += last_resolution > 0 && d->brush_resolution != last_resolution;
      last_resolution = d->brush_resolution;
    }
    if (n > 0 && where.size() < 400)
      where += " message " + std::to_string(i) + ": " + std::to_string(n) + ";";
    total += n;
  }
  return total;
}

// In a process of its own (a death test's re-run of this binary, where nothing has built the solver's rules yet): the
// steady solver's first evaluation, counted, exits 0 where it allocated nothing.
int firstSteadyEvaluationAllocates(bool build_estimator_first)
{
  if (build_estimator_first)
    ContactEstimator estimator{ EstimatorSettings{} };
  const BrushSteady steady(EstimatorSettings{}.brushParameters());
  long allocations = 0;
  {
    AllocationCount count;
    steady.evaluate(Eigen::Vector2d(0.05, 0.01), 3.0, 0.0, 0.0);
    allocations = count.count();
  }
  std::exit(allocations == 0 ? 0 : 1);
}

TEST(HotPath, TheEstimatorBuildsTheSolversRulesBeforeTheFirstMessage)
{
  // The steady solver builds its quadrature rules on first use (about half a millisecond: the first covariance or steady
  // answer of a run took 0.6-1 ms, 2-3 times its work's worth). ContactEstimator builds them at construction, so that
  // the first message that needs them does not. Those that allocate (the Gauss-Legendre rules' storage) show here:
  // after the estimator's construction the solver's first evaluation allocates nothing, without it it does. (The rules
  // across the paths allocate nothing: callgrind shows them, the first steady message of data/manoeuvre.bag taking
  // 1.9 M instructions in ContactEstimator::update before, 1.08 M after, the next one 0.97 M.)
  SCE_REQUIRE_ALLOCATION_COUNT();
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(firstSteadyEvaluationAllocates(true), ::testing::ExitedWithCode(0), "");
  EXPECT_EXIT(firstSteadyEvaluationAllocates(false), ::testing::ExitedWithCode(1), "");
}

TEST(HotPath, TheDefaultSettingsAllocateNothingPerMessageAlongTheManoeuvre)
{
  SCE_REQUIRE_ALLOCATION_COUNT();
  for (double rate : { 100.0, 1000.0 })
  {
    std::string where;
    EXPECT_EQ(warmPassAllocations(EstimatorSettings(), manoeuvreStream(rate, 7), where), 0)
        << rate << " Hz:" << where;
  }
}

// Auto with a tight target, not raised to the noise, within `budget` from `resolution`: it refines and coarsens its
// lattice along the manoeuvre.
EstimatorSettings refining(long budget, int resolution = 32)
{
  EstimatorSettings s;
  s.resolution = resolution;
  s.accuracy_target = 0.001;
  s.auto_noise_fraction = 0.0;
  s.work_budget = budget;
  return s;
}

TEST(HotPath, AutoRefiningOftenAllocatesNothingPerMessage)
{
  // the budget to reach the target: auto refines and coarsens its lattice all along the manoeuvre (its finer lattices
  // in the storage of those it dropped)
  SCE_REQUIRE_ALLOCATION_COUNT();
  const EstimatorSettings s = refining(1000000);
  std::string where;
  int changes = 0;
  EXPECT_EQ(warmPassAllocations(s, manoeuvreStream(100.0, 9), where, &changes), 0) << where;
  EXPECT_GE(changes, 2) << "the lattice hardly changed its resolution: the test shows little";
  std::printf("%d changes of resolution in the counted pass\n", changes);
}

// One pass of the stream through a new estimator, counted from its first message: per message the allocations, the
// work and the transient model's resolution.
struct CountedMessage
{
  long allocations = 0, work = 0;
  int resolution = 0;
};
std::vector<CountedMessage> firstPass(const EstimatorSettings& settings, const std::vector<EstimatorInput>& stream)
{
  ContactEstimator e(settings);
  std::vector<CountedMessage> out;
  out.reserve(stream.size());
  for (const EstimatorInput& in : stream)
  {
    CountedMessage m;
    const ContactEstimateData* d;
    {
      const AllocationCount count;
      d = e.update(in);
      m.allocations = count.count();
    }
    if (d)
    {
      m.work = d->work;
      m.resolution = d->brush_resolution;
    }
    out.push_back(m);
  }
  return out;
}

TEST(HotPath, AutoRefinesToTwiceItsResolutionWithoutSizingStorageInAMessage)
{
  // Both of auto's lattices hold storage for twice the configured resolution from the start, so that even the first
  // refinement to it sizes nothing in a message (before, the message that started the finer lattice sized it: 1.0-1.2 ms
  // of fresh pages at 64, uncounted; and a switch into the transient model sized the resolution it asked for before
  // the budget cut it). A budget that affords 64 and not 128, a tight target: auto refines from 32 to 64 and back.
  SCE_REQUIRE_ALLOCATION_COUNT();
  const EstimatorSettings s = refining(150000);
  ASSERT_GT(BrushTransient::leastUpdateWork(128, false), s.work_budget);
  const std::vector<CountedMessage> pass = firstPass(s, manoeuvreStream(100.0, 9));
  std::string where;
  long total = 0;
  int at_64 = 0;
  for (std::size_t i = 1; i < pass.size(); ++i)  // (the first message sizes what is sized once)
  {
    total += pass[i].allocations;
    at_64 += pass[i].resolution == 64;
    if (pass[i].allocations > 0 && where.size() < 400)
      where += " message " + std::to_string(i) + ": " + std::to_string(pass[i].allocations) + ";";
  }
  EXPECT_EQ(total, 0) << where;
  EXPECT_GT(at_64, 0) << "auto never refined to 64: the test shows nothing";
}

TEST(HotPath, StorageALatticeGrowsInAMessageIsCountedAsWork)
{
  // Beyond twice the configured resolution a refinement sizes storage in the message that starts it: that message
  // counts it (BrushTransient::kGrowWork a point), within the budget. Configured 16, presized for 32: the lattice of 64
  // grows by points(64) - points(32) at least.
  SCE_REQUIRE_ALLOCATION_COUNT();
  const EstimatorSettings s = refining(1000000, 16);
  const std::vector<CountedMessage> pass = firstPass(s, manoeuvreStream(100.0, 9));
  const long growth = BrushTransient::growthWork(BrushTransient::points(64), BrushTransient::points(32));
  int growing = 0, at_64 = 0;
  for (std::size_t i = 1; i < pass.size(); ++i)
  {
    at_64 += pass[i].resolution >= 64;
    if (pass[i].allocations == 0)
      continue;
    ++growing;
    EXPECT_GE(pass[i].work, growth) << "message " << i << " allocated " << pass[i].allocations << " times";
    EXPECT_LE(pass[i].work, s.work_budget + BrushModel::kWorkGranularity) << "message " << i;
  }
  EXPECT_GT(at_64, 0) << "auto never refined to 64: the test shows nothing";
  EXPECT_GT(growing, 0) << "no message sized storage: the test shows nothing";
}

TEST(HotPath, EveryModelAllocatesNothingPerMessage)
{
  SCE_REQUIRE_ALLOCATION_COUNT();
  const std::vector<EstimatorInput> stream = manoeuvreStream(100.0, 8);
  for (BrushModelKind brush : { BrushModelKind::Off, BrushModelKind::Linear, BrushModelKind::Steady,
                                BrushModelKind::Transient, BrushModelKind::Auto })
    for (SlidingLaw law : { SlidingLaw::Coulomb, SlidingLaw::Rigid })
      for (bool tilt : { false, true })
      {
        EstimatorSettings s;
        s.brush_model = brush;
        s.sliding_law = law;
        s.tilt = tilt;
        s.resolution = 16;  // the transient model at its own resolution: kept short
        std::string where;
        EXPECT_EQ(warmPassAllocations(s, stream, where), 0)
            << "brush model " << static_cast<int>(brush) << ", law " << static_cast<int>(law) << ", tilt " << tilt
            << ":" << where;
      }
  // with tilt, a budget that cannot pay for every substep: the bristles that need them share it (coarser substeps,
  // their own arc maps)
  for (SlidingLaw law : { SlidingLaw::Coulomb, SlidingLaw::Rigid })
  {
    EstimatorSettings s;
    s.brush_model = BrushModelKind::Transient;
    s.sliding_law = law;
    s.tilt = true;
    s.resolution = 32;
    s.work_budget = 50000;
    std::string where;
    EXPECT_EQ(warmPassAllocations(s, stream, where), 0)
        << "tilt at 32 within a short budget, law " << static_cast<int>(law) << ":" << where;
  }
  for (CylinderModelKind cylinder : { CylinderModelKind::Off, CylinderModelKind::Exact, CylinderModelKind::Expansion,
                                      CylinderModelKind::Table })
    for (bool covariance : { false, true })
    {
      EstimatorSettings s;
      s.brush_model = BrushModelKind::Steady;
      s.rolling_resistance_model = cylinder;
      s.propagate_covariance = covariance;
      s.covariance_period = 0.0;  // every message
      std::string where;
      EXPECT_EQ(warmPassAllocations(s, stream, where), 0)
          << "rolling resistance " << static_cast<int>(cylinder) << ", covariance " << covariance << ":" << where;
    }
}

TEST(HotPath, AHostileStreamAllocatesNothingPerMessage)
{
  SCE_REQUIRE_ALLOCATION_COUNT();
  for (unsigned seed : { 11u, 12u })
  {
    std::string where;
    EXPECT_EQ(warmPassAllocations(EstimatorSettings(), hostileStream(seed), where), 0) << "seed " << seed << ":"
                                                                                          << where;
  }
}

}  // namespace
}  // namespace sphere_contact_estimator
