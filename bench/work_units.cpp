// How long a counted unit of work takes (BrushForces::work): the work budget (work_budget, 10^5 units by default)
// stands for about 1 ms only while no unit costs much more than 10 ns. Over seeded random robots of the stream sweep's
// envelope (scripts/stream_sweep.py: patch radius 4-50 mm, k 3e7-1e9 N/m^3, 1-40 kg, mu 0.3-1.2, any pressure) and
// random noisy histories at 30, 100 or 1000 Hz (rolling at 0.1-2 m/s with slips |sigma_x| <= 0.3, |sigma_y| <= 0.2
// and spin |a phi| <= 1.5, the last quarter parked), each model that counts its work (steady, transient at a random
// resolution of 16-64, auto) under each sliding law, without and with tilt, within the default budget: every message's
// time (the fastest of three replays of the same history, each on a fresh model) over its counted work. Reported per
// model, law and tilt: the heavy messages' (a fifth of the budget or more, where the budget binds) time per unit,
// its worst case and where, and the slowest message.
//
// Usage: work_units [SEED [ROBOTS]]  (JSON on stdout; a timing, so run it on a quiet core: scripts/benchmark.sh)

// STL
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

// nlohmann
#include <nlohmann/json.hpp>

// Package
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "whole_number.h"

namespace
{
namespace sce = sphere_contact_estimator;
using sce::bench::wholeNumber;
using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr long kBudget = 100000;        // config/contact_estimator.yaml's work_budget
constexpr double kHeavyShare = 0.2;     // of the budget: the messages where the budget binds
constexpr int kMessages = 40;           // a history's messages, the last quarter parked
constexpr int kReplays = 3;

struct Robot
{
  sce::BrushParameters p;
  double rate = 100.0, speed = 1.0, noise = 0.0, a_phi = 0.0;
  Eigen::Vector2d sigma = Eigen::Vector2d::Zero();
  int resolution = 32;
  unsigned history_seed = 0;
};

double logUniform(std::mt19937_64& rng, double lo, double hi)
{
  std::uniform_real_distribution<double> u(std::log(lo), std::log(hi));
  return std::exp(u(rng));
}

Robot drawRobot(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Robot r;
  r.p.a = logUniform(rng, 0.004, 0.05);
  r.p.k = logUniform(rng, 3e7, 1e9);
  r.p.F_z = 9.81 * logUniform(rng, 1.0, 40.0);
  r.p.mu = 0.3 + 0.9 * u(rng);
  const int pressure = std::min(2, static_cast<int>(3.0 * u(rng)));
  r.p.pressure = pressure == 0   ? sce::PressureDistribution::Parabolic
                 : pressure == 1 ? sce::PressureDistribution::Hertzian
                                 : sce::PressureDistribution::Uniform;
  const double rates[] = { 30.0, 100.0, 100.0, 1000.0 };
  r.rate = rates[std::min(3, static_cast<int>(4.0 * u(rng)))];
  r.speed = 0.1 + 1.9 * u(rng);
  r.sigma = Eigen::Vector2d(0.6 * u(rng) - 0.3, 0.4 * u(rng) - 0.2);
  r.a_phi = 3.0 * u(rng) - 1.5;
  r.noise = logUniform(rng, 1e-3, 3e-2);
  const int resolutions[] = { 16, 32, 64 };
  r.resolution = resolutions[std::min(2, static_cast<int>(3.0 * u(rng)))];
  r.history_seed = static_cast<unsigned>(rng());
  return r;
}

// The history's messages (the same for every model and replay): rolling with noise on the slips and the spin, then
// parked (creeping at the noise's scale, spinning at the noise's).
std::vector<sce::ContactKinematics> history(const Robot& r)
{
  std::mt19937_64 rng(r.history_seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<sce::ContactKinematics> out;
  for (int i = 0; i < kMessages; ++i)
  {
    if (i >= 3 * kMessages / 4)
    {
      sce::ContactKinematics k;
      k.V_r = 0.01 * Eigen::Vector2d(g(rng), g(rng));
      k.V_s = r.noise * Eigen::Vector2d(g(rng), g(rng));
      k.omega_z = r.noise * g(rng) / r.p.a;
      k.psi_dot = 0.1 * k.omega_z;
      out.push_back(k);
      continue;
    }
    double phi = (r.a_phi + r.noise * g(rng)) / r.p.a;
    if (r.p.tilt && std::abs(0.9 * phi) * r.p.a > 0.9)
      phi = std::copysign(1.0 / r.p.a, phi);  // within the tilted model's reach, |R_gamma| > a
    const Eigen::Vector2d sigma = r.sigma + r.noise * Eigen::Vector2d(g(rng), g(rng));
    out.push_back(sce::ContactKinematics::fromSlips(sigma, phi, 0.9, r.speed));
  }
  return out;
}

std::unique_ptr<sce::BrushModel> makeModel(const std::string& kind, const Robot& r)
{
  std::unique_ptr<sce::BrushModel> m;
  if (kind == "steady")
    m = std::make_unique<sce::BrushSteady>(r.p);
  else if (kind == "transient")
  {
    sce::BrushParameters p = r.p;
    p.resolution = r.resolution;
    m = std::make_unique<sce::BrushTransient>(p);
  }
  else
    m = std::make_unique<sce::BrushAuto>(r.p);
  m->setWorkBudget(kBudget);
  return m;
}

struct Message
{
  long work = 0;
  double seconds = INFINITY;
};

// every message's counted work and its fastest time over the replays
std::vector<Message> replay(const std::string& kind, const Robot& r)
{
  const std::vector<sce::ContactKinematics> steps = history(r);
  std::vector<Message> out(steps.size());
  const double dt = 1.0 / r.rate;
  for (int k = 0; k < kReplays; ++k)
  {
    std::unique_ptr<sce::BrushModel> m = makeModel(kind, r);
    for (std::size_t i = 0; i < steps.size(); ++i)
    {
      const auto t0 = Clock::now();
      const sce::BrushForces f = m->update(steps[i], dt);
      const double s = std::chrono::duration<double>(Clock::now() - t0).count();
      out[i].seconds = std::min(out[i].seconds, s);
      out[i].work = f.work;
    }
  }
  return out;
}

Json robotJson(const Robot& r)
{
  return { { "a", r.p.a },           { "k", r.p.k },
           { "F_z", r.p.F_z },       { "mu", r.p.mu },
           { "pressure", sce::toString(r.p.pressure) },
           { "rate", r.rate },       { "speed", r.speed },
           { "sigma", { r.sigma.x(), r.sigma.y() } },
           { "a_phi", r.a_phi },     { "noise", r.noise },
           { "resolution", r.resolution } };
}

double quantile(std::vector<double> v, double q)
{
  if (v.empty())
    return NAN;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  const std::optional<long> seed = args.size() > 0 ? wholeNumber(args[0], 0, 4294967295L) : std::optional<long>(1);
  const std::optional<long> robots = args.size() > 1 ? wholeNumber(args[1], 1, 100000) : std::optional<long>(40);
  if (args.size() > 2 || !seed || !robots)
  {
    std::cerr << "usage: work_units [SEED [ROBOTS]]  (JSON on stdout)\n";
    return 2;
  }
  sce::BrushSteady::prepareRules();
  Json out;
  out["budget"] = kBudget;
  out["seed"] = *seed;
  out["robots"] = *robots;
  for (const sce::SlidingLaw law : { sce::SlidingLaw::Coulomb, sce::SlidingLaw::Rigid })
    for (const bool tilt : { false, true })
      for (const std::string kind : { "steady", "transient", "auto" })
      {
        std::mt19937_64 rng(static_cast<unsigned>(*seed));  // the same robots for every model, law and tilt
        std::vector<double> per_unit;
        Json worst, slowest;
        double worst_ns = 0.0, slowest_s = 0.0;
        long messages = 0;
        for (long i = 0; i < *robots; ++i)
        {
          Robot r = drawRobot(rng);
          r.p.sliding_law = law;
          r.p.tilt = tilt;
          const std::vector<Message> ms = replay(kind, r);
          for (std::size_t j = 0; j < ms.size(); ++j)
          {
            ++messages;
            const Message& m = ms[j];
            const Json where = { { "robot", i }, { "message", j }, { "work", m.work }, { "us", 1e6 * m.seconds },
                                 { "parameters", robotJson(r) } };
            if (m.seconds > slowest_s)
              slowest_s = m.seconds, slowest = where;
            if (m.work < kHeavyShare * kBudget)
              continue;
            const double ns = 1e9 * m.seconds / static_cast<double>(m.work);
            per_unit.push_back(ns);
            if (ns > worst_ns)
              worst_ns = ns, worst = where;
          }
        }
        Json& o = out["models"][std::string(sce::toString(law)) + (tilt ? ", tilt" : "")][kind];
        o["messages"] = messages;
        o["heavy"] = per_unit.size();
        o["ns_per_unit"] = { { "p50", quantile(per_unit, 0.5) }, { "p99", quantile(per_unit, 0.99) },
                             { "max", worst_ns } };
        o["worst"] = worst;
        o["slowest"] = slowest;
        std::cerr << sce::toString(law) << (tilt ? ", tilt, " : ", ") << kind << ": " << per_unit.size()
                  << " heavy messages, ns/unit p50 " << quantile(per_unit, 0.5) << " max " << worst_ns
                  << "; slowest " << 1e6 * slowest_s << " us\n";
      }
  std::cout << out.dump(1) << "\n";
  return 0;
}
