// The calibration's accuracy over seeds (issue 23), printed as JSON for scripts/benchmark_report.py: synthetic runs of
// a robot with known parameters (src/scenario/calibration_run.h: the bundled calibration manoeuvre, the forces from the
// node's auto model, the demo's odometry noise, 0.05 m/s^2 on the IMU), each fitted from the parameter file's values
// (k 2e8, mu 0.8; truth 1.5e8 and 0.6) as calibrate does: the fitted values, their standard deviations, whether the
// residuals flagged a mismatch, the fit's time. Then the time of a 60-s run at 100 Hz, runs with a bias on the IMU and
// with another pressure distribution than the fit assumes (the mismatch must be flagged), and robots drawn at random
// over the envelope a user reaches (mass, k, mu, patch radius, IMU and odometry noise), fitted from the same file
// values: there the file's mu may lie far from the truth and a run may give mu only as a bound, and every interval
// and bound must still hold the truth. And runs fitted with the floor's damping too (from twice the truth, 1e5).
//
//   calibration_accuracy [--seeds 100] [--floors 100] [--robots 100] > calibration.json      (progress on stderr)

// STL
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <random>
#include <string>
#include <vector>

// nlohmann
#include <nlohmann/json.hpp>

// Package
#include "sphere_contact_estimator/core/calibration/contact_fit.h"
#include "calibration_run.h"

namespace sce = sphere_contact_estimator;
using nlohmann::json;

namespace
{
json fitRun(const sce::EstimatorSettings& t, const sce::CalibrationNoise& noise, double duration_scale,
            bool robot = false, bool floor = false)
{
  std::vector<sce::ScenarioSegment> segments = sce::calibrationSegments();
  for (auto& s : segments)
    s.duration *= duration_scale;
  const sce::Scenario scenario(segments, t.rolling_radius);
  std::vector<sce::CalibrationSample> samples;
  for (const sce::CalibrationMessage& m : sce::calibrationRun(scenario, t, 100.0, noise))
    samples.push_back(m.sample);
  // the file: the robot as its user knows it (mass, patch radius, the parabolic pressure), k and mu guessed
  sce::EstimatorSettings file = robot ? t : sce::calibrationTruth();
  file.bristle_stiffness = 2e8;
  file.friction = 0.8;
  if (floor)
    file.surface_damping = 2.0 * t.surface_damping;  // else the floor as it is: the rolling resistance given
  const auto start = std::chrono::steady_clock::now();
  sce::FitOptions options;
  options.fit[static_cast<int>(sce::FitParameter::SurfaceDamping)] = floor;
  const sce::FitResult r = sce::fitContact(samples, file, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const sce::FittedValue& k = r.values[static_cast<int>(sce::FitParameter::BristleStiffness)];
  const sce::FittedValue& mu = r.values[static_cast<int>(sce::FitParameter::Friction)];
  const sce::FittedValue& gamma = r.values[static_cast<int>(sce::FitParameter::SurfaceDamping)];
  return json{ { "seed", noise.seed },
               { "duration", scenario.duration() },
               { "messages", r.samples },
               { "used", r.used },
               { "k", k.value },
               { "k_sd", k.sd },
               { "k_low", k.low },
               { "k_high", k.high },
               { "k_determined", k.determined },
               { "mu", mu.value },
               { "mu_sd", mu.sd },
               { "mu_low", mu.low },
               { "mu_bound", mu.lower_bound },
               { "mu_determined", mu.determined },
               { "gamma", gamma.value },
               { "gamma_sd", gamma.sd },
               { "gamma_determined", gamma.determined },
               { "reduced_chi2", r.reduced_chi2 },
               { "autocorrelation", r.residual_autocorrelation.maxCoeff() },
               { "mismatch", r.mismatch() },
               { "converged", r.converged },
               { "seconds", seconds },
               { "truth", robot ? json{ { "k", t.bristle_stiffness },
                                         { "mu", t.friction },
                                         { "gamma", t.surface_damping },
                                         { "mass", t.robot_mass },
                                         { "a", t.patch_radius },
                                         { "imu_noise", noise.imu },
                                         { "odometry_noise_scale", noise.velocity / sce::CalibrationNoise{}.velocity } }
                                : json() } };
}
}  // namespace

int main(int argc, char** argv)
{
  int seeds = 100, robots = 100, floors = 100;
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--seeds") == 0)
      seeds = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--robots") == 0)
      robots = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--floors") == 0)
      floors = std::atoi(argv[i + 1]);
  const sce::EstimatorSettings t = sce::calibrationTruth();
  json out{ { "truth",
              { { "k", t.bristle_stiffness },
                { "mu", t.friction },
                { "gamma", t.surface_damping },
                { "mass", t.robot_mass } } },
            { "imu_noise", sce::CalibrationNoise{}.imu } };
  for (int s = 1; s <= seeds; ++s)
  {
    sce::CalibrationNoise noise;
    noise.seed = static_cast<std::uint64_t>(s);
    out["runs"].push_back(fitRun(t, noise, 1.0));
    std::cerr << "\rcalibration_accuracy: seed " << s << " of " << seeds << std::flush;
  }
  std::cerr << "\n";
  for (int s = 1; s <= 3; ++s)
  {
    sce::CalibrationNoise noise;
    noise.seed = 1000 + static_cast<std::uint64_t>(s);
    out["long"].push_back(fitRun(t, noise, 3.0));  // 58.5 s at 100 Hz
  }
  for (int s = 1; s <= 5; ++s)
  {
    sce::CalibrationNoise noise;
    noise.seed = 2000 + static_cast<std::uint64_t>(s);
    noise.imu_bias = Eigen::Vector2d(0.2, 0.0);
    out["imu_bias"].push_back(fitRun(t, noise, 1.0));
    sce::EstimatorSettings uniform = t;
    uniform.pressure = sce::PressureDistribution::Uniform;
    noise.imu_bias.setZero();
    out["uniform_pressure"].push_back(fitRun(uniform, noise, 1.0));
  }
  // the floor too (calibrate --fit bristle_stiffness,friction,surface_damping), from twice its damping
  for (int s = 1; s <= floors; ++s)
  {
    sce::CalibrationNoise noise;
    noise.seed = 4000 + static_cast<std::uint64_t>(s);
    out["floor"].push_back(fitRun(t, noise, 1.0, false, true));
    std::cerr << "\rcalibration_accuracy: floor " << s << " of " << floors << std::flush;
  }
  std::cerr << "\n";
  // robots at random over the envelope (seeded): a light or heavy robot, soft or stiff bristles, low or high friction,
  // small or large patch, a quiet or noisy IMU and odometry, a hard or soft floor
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < robots; ++i)
  {
    sce::EstimatorSettings r = t;
    r.robot_mass = 2.0 + 6.0 * u(rng);
    r.bristle_stiffness = std::pow(10.0, 7.7 + 1.0 * u(rng));
    r.friction = 0.3 + 0.7 * u(rng);
    r.patch_radius = 0.006 + 0.01 * u(rng);
    sce::CalibrationNoise noise;
    noise.seed = 3000 + static_cast<std::uint64_t>(i);
    noise.imu = 0.02 + 0.08 * u(rng);
    const double scale = 0.5 + 1.0 * u(rng);
    noise.velocity *= scale;
    noise.omega *= scale;
    r.surface_damping = std::pow(10.0, 4.0 + 2.0 * u(rng));  // a hard floor to a soft one (tau 1e-4 to 1e-2 s)
    out["robots"].push_back(fitRun(r, noise, 1.0, true));
    std::cerr << "\rcalibration_accuracy: robot " << i + 1 << " of " << robots << std::flush;
  }
  std::cerr << "\n";
  std::cout << out.dump(1) << "\n";
  return 0;
}
