// contact_eval as a user runs it: JSON on stdout that matches the core, and clear failures.

// STL
#include <cstdio>
#include <random>
#include <string>

// nlohmann
#include <nlohmann/json.hpp>

// GTest
#include <gtest/gtest.h>

// Package
#include "../command_outcome.h"
#include "../core/cylinder_test_support.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_exact.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_expansion.h"

namespace sphere_contact_estimator
{
namespace
{
using test::Outcome;

Outcome contactEval(const std::string& args)
{
  return test::runCommand(std::string(CONTACT_EVAL_PATH) + " " + args);
}

const std::string kPaper = "cylinder --radius 0.1 --mass-per-length 250 --stiffness 1e7 --damping 5e5 "
                           "--surface-density 100 ";

// the paper's set, with contact_eval's default g
CylinderParameters paper()
{
  return test::paperParameters(9.81);
}

TEST(ContactEval, SpeedPrintsOneObjectThatMatchesTheCore)
{
  const Outcome r = contactEval(kPaper + "--speed 0.7");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_object());
  for (const char* key : { "h", "xi_plus", "xi_minus", "F_R", "torque", "mu_roll", "regime", "valid", "warnings", "v" })
    EXPECT_TRUE(j.contains(key)) << key;
  const CylinderState s = CylinderExact(paper()).solve(0.7);
  EXPECT_DOUBLE_EQ(j["h"].get<double>(), s.h);
  EXPECT_DOUBLE_EQ(j["xi_plus"].get<double>(), s.xi_plus);
  EXPECT_DOUBLE_EQ(j["xi_minus"].get<double>(), s.xi_minus);
  EXPECT_DOUBLE_EQ(j["F_R"].get<double>(), s.F_R);
  EXPECT_DOUBLE_EQ(j["torque"].get<double>(), s.torque);
  EXPECT_DOUBLE_EQ(j["mu_roll"].get<double>(), s.mu_roll);
  EXPECT_EQ(j["regime"], "contact_patch");
  EXPECT_EQ(j["valid"], true);
  EXPECT_TRUE(j["warnings"].empty());
  EXPECT_EQ(j["model"], "exact");
}

TEST(ContactEval, LengthGivesTotals)
{
  const auto one = nlohmann::json::parse(contactEval(kPaper + "--speed 0.7").out);
  const auto three = nlohmann::json::parse(contactEval(kPaper + "--speed 0.7 --length 3").out);
  EXPECT_DOUBLE_EQ(three["F_R"].get<double>(), 3.0 * one["F_R"].get<double>());
  EXPECT_DOUBLE_EQ(three["torque"].get<double>(), 3.0 * one["torque"].get<double>());
  EXPECT_DOUBLE_EQ(three["F_R_per_length"].get<double>(), one["F_R"].get<double>());
  EXPECT_DOUBLE_EQ(three["mu_roll"].get<double>(), one["mu_roll"].get<double>());
  EXPECT_DOUBLE_EQ(three["h"].get<double>(), one["h"].get<double>());
}

TEST(ContactEval, SweepPrintsAnArrayAcrossRegimes)
{
  const Outcome r = contactEval(kPaper + "--sweep 0 60 61 --g 9.81");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 61u);
  EXPECT_EQ(j.front()["regime"], "static");
  EXPECT_EQ(j.back()["regime"], "point_contact");
  EXPECT_EQ(j.back()["valid"], false);
  EXPECT_FALSE(j.back()["warnings"].empty());
  for (std::size_t i = 0; i < j.size(); ++i)
  {
    EXPECT_DOUBLE_EQ(j[i]["v"].get<double>(), static_cast<double>(i));
    for (const char* key : { "h", "xi_plus", "xi_minus", "F_R", "torque", "mu_roll" })
      EXPECT_TRUE(j[i][key].is_number()) << key << " at " << i;
  }
}

TEST(ContactEval, ModelsAndPeak)
{
  const auto e = nlohmann::json::parse(contactEval(kPaper + "--speed 0.1 --model expansion").out);
  EXPECT_EQ(e["model"], "expansion");
  EXPECT_DOUBLE_EQ(e["mu_roll"].get<double>(), CylinderExpansion(paper()).solve(0.1).mu_roll);
  const auto t = nlohmann::json::parse(contactEval(kPaper + "--speed 0.1 --model table").out);
  EXPECT_EQ(t["model"], "table");
  EXPECT_NEAR(t["mu_roll"].get<double>(), CylinderExact(paper()).solve(0.1).mu_roll, t["mu_roll_error"].get<double>());
  const auto peak = nlohmann::json::parse(contactEval(kPaper + "--peak --model expansion").out);
  EXPECT_NEAR(peak["v"].get<double>(), peak["v_star"].get<double>(), 1e-6 * peak["v_star"].get<double>());
}

TEST(ContactEval, BadInputFailsWithAMessage)
{
  const std::vector<std::string> bad{
    kPaper,                                              // no speed
    kPaper + "--speed -1",                               // negative speed
    kPaper + "--speed nan",                              // not a number
    kPaper + "--speed 1 --sweep 0 1 3",                  // both
    kPaper + "--sweep 0 1",                              // two values
    kPaper + "--sweep 1 0 3",                            // reversed
    kPaper + "--sweep 0 1 2.5",                          // fractional count
    kPaper + "--speed 1 --model fancy",                  // unknown model
    "cylinder --radius -0.1 --mass-per-length 250 --stiffness 1e7 --damping 5e5 --surface-density 100 --speed 1",
    "cylinder --radius 0.1 --mass-per-length 250 --stiffness 0 --damping 5e5 --surface-density 100 --speed 1",
    "cylinder --radius 0.1 --mass-per-length 250 --stiffness 1e7 --damping -5 --surface-density 100 --speed 1",
    "cylinder --radius 0.1 --mass-per-length 250 --stiffness 1e7 --damping 5e5 --speed 1",  // missing m
    "cylinder --radius abc --mass-per-length 250 --stiffness 1e7 --damping 5e5 --surface-density 100 --speed 1",
    "",                                                  // no subcommand
  };
  for (const std::string& args : bad)
  {
    const Outcome r = contactEval(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_FALSE(r.err.empty()) << args;
    EXPECT_TRUE(r.out.empty()) << args << " printed " << r.out;
  }
  const Outcome r = contactEval("cylinder --radius -0.1 --mass-per-length 250 --stiffness 1e7 --damping 5e5 "
                            "--surface-density 100 --speed 1");
  EXPECT_NE(r.err.find("radius (R)"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace sphere_contact_estimator

namespace sphere_contact_estimator
{
namespace
{
const std::string kFig4 = "--patch-radius 0.05 --stiffness 1.023e8 --load 3000 --friction 1 ";

TEST(ContactEvalSlips, PrintsEqs12And13)
{
  const Outcome r = contactEval("slips --omega 0 -10 2 --vc 1.1 -0.05 --rolling-radius 0.1 --turn-rate 0.5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : { "V_r", "sigma_x", "sigma_y", "phi", "phi_gamma", "phi_psi", "chi_gamma", "epsilon_x",
                           "epsilon_y", "valid", "warnings" })
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_NEAR(j["V_r"].get<double>(), 1.0, 1e-15);
  EXPECT_NEAR(j["sigma_x"].get<double>(), -0.1, 1e-12);
  EXPECT_NEAR(j["sigma_y"].get<double>(), 0.05, 1e-12);
  EXPECT_NEAR(j["phi"].get<double>(), -2.0, 1e-12);
  EXPECT_NEAR(j["phi_psi"].get<double>(), -0.5, 1e-12);
  EXPECT_NEAR(j["phi_gamma"].get<double>(), -1.5, 1e-12);
  EXPECT_NEAR(j["chi_gamma"].get<double>(), 0.75, 1e-12);
  EXPECT_NEAR(j["epsilon_y"].get<double>(), 1.0, 1e-15);
  EXPECT_EQ(j["valid"], true);
  // the tilt ratio instead of the turn rate
  const auto t = nlohmann::json::parse(contactEval("slips --omega 0 -10 2 --vc 1 0 --rolling-radius 0.1 --tilt-ratio 0.9").out);
  EXPECT_NEAR(t["phi_gamma"].get<double>(), -1.8, 1e-12);
}

TEST(ContactEvalSlips, StandstillGivesNullsNotInfinities)
{
  const Outcome r = contactEval("slips --omega 0 0 3 --vc 0.01 0 --rolling-radius 0.1");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["valid"], false);
  EXPECT_TRUE(j["sigma_x"].is_null());
  EXPECT_TRUE(j["phi"].is_null());
  EXPECT_FALSE(j["warnings"].empty());
}

TEST(ContactEvalSlips, FrameRosReadsAsTheTopicsDo)
{
  // forward rolling as it reads on a REP 103 topic: omega about +y left, V_C forward
  const Outcome r = contactEval("slips --omega 0 5.3333333333333333 0 --vc 0.8 0 --rolling-radius 0.15 --frame ros");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frame"].get<std::string>().rfind("ros", 0), 0u);
  EXPECT_NEAR(j["V_r_x"].get<double>(), 0.8, 1e-12);
  EXPECT_NEAR(j["sigma_x"].get<double>(), 0.0, 1e-12);
  EXPECT_TRUE(j["valid"].get<bool>());
  // against the estimator behind the node (ROS in, ROS out), at random rolling, sliding and spinning inputs whose
  // contact frame is the ground's (V_r along +x): the same slips, spins and sliding velocity
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 20; ++i)
  {
    const double R = 0.1, v = 0.5 + std::abs(u(rng)), w_z = 5.0 * u(rng);
    const Eigen::Vector3d omega(0.0, v / R, w_z);
    const Eigen::Vector2d vc(v + 0.2 * u(rng), 0.2 * u(rng));
    EstimatorSettings settings;
    settings.turn_rate_time_constant = 0.0;
    settings.tilt_ratio_source = TiltRatioSource::Fixed;
    settings.tilt_ratio = 0.7;
    ContactEstimator estimator(settings);
    EstimatorInput in;
    in.omega = omega;
    in.v_contact = Eigen::Vector3d(vc.x(), vc.y(), 0.0);
    const ContactEstimateData* d = estimator.update(in);
    ASSERT_TRUE(d);
    ASSERT_NEAR(d->heading, 0.0, 1e-12);
    char args[256];
    std::snprintf(args, sizeof args, "slips --omega %.17g %.17g %.17g --vc %.17g %.17g --rolling-radius %g --tilt-ratio 0.7 --frame ros",
                  omega.x(), omega.y(), omega.z(), vc.x(), vc.y(), R);
    const Outcome o = contactEval(args);
    ASSERT_EQ(o.status, 0) << o.err;
    const auto k = nlohmann::json::parse(o.out);
    EXPECT_NEAR(k["sigma_x"].get<double>(), d->slip.x(), 1e-12) << args;
    EXPECT_NEAR(k["sigma_y"].get<double>(), d->slip.y(), 1e-12) << args;
    EXPECT_NEAR(k["phi"].get<double>(), d->spin, 1e-9) << args;
    EXPECT_NEAR(k["phi_gamma"].get<double>(), d->spin_tilt, 1e-9) << args;
    EXPECT_NEAR(k["V_s_x"].get<double>(), d->sliding_velocity.x(), 1e-12) << args;
    EXPECT_NEAR(k["V_s_y"].get<double>(), d->sliding_velocity.y(), 1e-12) << args;
  }
}

TEST(ContactEvalBrush, FrameRosFlipsTheLateralSlipSpinForceAndMoment)
{
  // the same inputs in both frames: sigma_y and phi flip, and with them the covariance's (x, y) and (x, phi) terms
  const std::string common = "brush --model steady --sigma-x 0.05 --patch-radius 0.05 --stiffness 1.023e8 --load 3000 "
                             "--friction 1 ";
  const Outcome paper = contactEval(common + "--sigma-y 0.02 --phi 3.33 --covariance 1e-6 2e-7 1e-5 2e-6 3e-6 0.01");
  const Outcome ros = contactEval(common + "--sigma-y -0.02 --phi -3.33 --covariance 1e-6 -2e-7 -1e-5 2e-6 3e-6 0.01 --frame ros");
  ASSERT_EQ(paper.status, 0) << paper.err;
  ASSERT_EQ(ros.status, 0) << ros.err;
  const auto p = nlohmann::json::parse(paper.out), r = nlohmann::json::parse(ros.out);
  EXPECT_EQ(p["frame"].get<std::string>().rfind("paper", 0), 0u);
  EXPECT_EQ(r["frame"].get<std::string>().rfind("ros", 0), 0u);
  EXPECT_EQ(r["Fx"].get<double>(), p["Fx"].get<double>());
  EXPECT_EQ(r["Fy"].get<double>(), -p["Fy"].get<double>());
  EXPECT_EQ(r["Mz"].get<double>(), -p["Mz"].get<double>());
  EXPECT_NE(p["Fy"].get<double>(), 0.0);
  // the covariance of (F_x, F_y, M_z): D C D, D = diag(1, -1, -1)
  const double sign[9] = { 1, -1, -1, -1, 1, 1, -1, 1, 1 };
  for (int i = 0; i < 9; ++i)
    EXPECT_NEAR(r["covariance"][i].get<double>(), sign[i] * p["covariance"][i].get<double>(),
                1e-9 * std::abs(p["covariance"][i].get<double>()) + 1e-12) << i;
  EXPECT_NE(contactEval(common + "--sigma-y 0 --phi 0 --frame sae").status, 0);
}

TEST(ContactEvalBrush, ModelsAgreeWhereTheyShould)
{
  // small slips: the three models give the linear theory
  const std::string small = "--sigma-x 0.0001 --sigma-y 0.0002 --phi 0.002 " + kFig4 + "--resolution 64 ";
  const auto lin = nlohmann::json::parse(contactEval("brush --model linear " + small).out);
  const auto st = nlohmann::json::parse(contactEval("brush --model steady " + small).out);
  const auto tr = nlohmann::json::parse(contactEval("brush --model transient " + small).out);
  for (const char* key : { "Fx", "Fy", "Mz", "sliding_fraction", "max_utilisation", "error_estimate", "valid", "warnings" })
    EXPECT_TRUE(st.contains(key)) << key;
  for (const auto* j : { &st, &tr })
  {
    EXPECT_NEAR((*j)["Fx"].get<double>(), lin["Fx"].get<double>(), 0.01 * std::abs(lin["Fx"].get<double>()));
    EXPECT_NEAR((*j)["Fy"].get<double>(), lin["Fy"].get<double>(), 0.01 * std::abs(lin["Fy"].get<double>()));
  }
  // partial sliding, spin and tilt: transient at steady state against steady
  const std::string tilt = "--sigma-x 0.05 --sigma-y 0.02 --phi 3.33 --tilt --tilt-ratio 0.9 " + kFig4 + "--resolution 64 ";
  const auto a = nlohmann::json::parse(contactEval("brush --model steady " + tilt).out);
  const auto b = nlohmann::json::parse(contactEval("brush --model transient " + tilt).out);
  EXPECT_NEAR(a["Fx"].get<double>(), b["Fx"].get<double>(), 30.0);
  EXPECT_NEAR(a["Fy"].get<double>(), b["Fy"].get<double>(), 30.0);
  EXPECT_GT(a["sliding_fraction"].get<double>(), 0.1);
  EXPECT_LT(a["sliding_fraction"].get<double>(), 0.9);
  EXPECT_EQ(b["distance"].get<double>(), 0.2);  // 4a by default
}

TEST(ContactEvalBrush, AutoMeetsItsTargetAndSaysWhatRan)
{
  const std::string point = "--sigma-x 0.05 --sigma-y 0.02 --phi 3.33 " + kFig4;
  const auto reference = nlohmann::json::parse(contactEval("brush --model steady --accuracy-target 1e-9 " + point).out);
  for (double target : { 0.05, 0.01, 0.002 })
  {
    const Outcome r = contactEval("brush --model auto --accuracy-target " + std::to_string(target) + " " + point);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["model"], "auto");
    EXPECT_TRUE(j["model_used"] == "linear" || j["model_used"] == "steady") << j["model_used"];
    EXPECT_NEAR(j["Fx"].get<double>(), reference["Fx"].get<double>(), target * 3000.0) << target;
    EXPECT_NEAR(j["Fy"].get<double>(), reference["Fy"].get<double>(), target * 3000.0) << target;
  }
  // tiny slips: the linear model is exact enough
  const auto small = nlohmann::json::parse(contactEval("brush --model auto --sigma-x 0.0001 --sigma-y 0 --phi 0 " + kFig4).out);
  EXPECT_EQ(small["model_used"], "linear");
  EXPECT_NE(contactEval("brush --model auto --accuracy-target 0 --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4).status, 0);
}

TEST(ContactEvalBrush, SteadyToItsAccuracyTarget)
{
  // Issue 20's example point (Fig. 4's parameters, pure spin phi = 3.33 1/m): under eq. (4b) F_y = 1484.3835 N and
  // M_z = 36.41168 N m (converged by two independent solvers), at --accuracy-target 1e-4 within 1e-4 mu F_z, the
  // estimate saying so; under Sect. 6's rigid law the converged 996.56 N and 45.316 N m of the paper's Fig. 4
  const std::string spin = "--sigma-x 0 --sigma-y 0 --phi 3.33 " + kFig4;
  for (double target : { 1e-2, 1e-4 })
  {
    const Outcome r = contactEval("brush --model steady --accuracy-target " + std::to_string(target) + " " + spin);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["sliding_law"], "coulomb");
    EXPECT_NEAR(j["Fy"].get<double>(), 1484.38354, target * 3000.0);
    EXPECT_NEAR(j["Mz"].get<double>(), 36.411681, target * 3000.0 * 0.05);
    EXPECT_NEAR(j["Fx"].get<double>(), 0.0, target * 3000.0);
    EXPECT_LE(j["error_estimate"].get<double>(), target);
  }
  const auto rigid = nlohmann::json::parse(contactEval("brush --model steady --sliding-law rigid --accuracy-target 1e-4 " + spin).out);
  EXPECT_EQ(rigid["sliding_law"], "rigid");
  EXPECT_NEAR(rigid["Fy"].get<double>(), 996.560, 0.3);
  EXPECT_NEAR(rigid["Mz"].get<double>(), 45.316, 0.015);
  const auto linear = nlohmann::json::parse(contactEval("brush --model linear " + spin).out);
  EXPECT_TRUE(linear["sliding_law"].is_null());  // no sliding in eqs. 61-62

  // Issue 11's point (a small zone of re-adhering bristles around a spin pole in the patch) under the rigid law: at
  // --accuracy-target 1e-4 F_y is within 1e-4 mu F_z of the converged 4.79225233 N, and the estimate says so.
  const std::string point = "--sliding-law rigid --patch-radius 0.030132135540406 --load 721.6240066650845 --friction 0.8447950430510605 "
                            "--stiffness 195451215.1840554 --sigma-x -0.009505213968784471 "
                            "--sigma-y 0.004217246676809281 --phi -9.057291504918961 ";
  const double muFz = 0.8447950430510605 * 721.6240066650845;
  for (double target : { 1e-2, 1e-4 })
  {
    const Outcome r = contactEval("brush --model steady --accuracy-target " + std::to_string(target) + " " + point);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(j["Fy"].get<double>(), 4.79225233, target * muFz);
    EXPECT_NEAR(j["Fx"].get<double>(), -28.29525733, target * muFz);
    EXPECT_LE(j["error_estimate"].get<double>(), target);
    EXPECT_EQ(j["accuracy_target"].get<double>(), target);
    EXPECT_FALSE(j.contains("resolution"));  // the steady model has none
  }
}

TEST(ContactEvalBrush, InnerDiscFallsBackToTransient)
{
  const Outcome r = contactEval("brush --model steady --sigma-x 0 --sigma-y 0 --phi 40 --tilt " + kFig4);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"], "transient");
  EXPECT_FALSE(j["warnings"].empty());
  EXPECT_LE(std::hypot(j["Fx"].get<double>(), j["Fy"].get<double>()), 3000.0 * (1 + 1e-9));
}

TEST(ContactEvalBrush, HertzPatchRadius)
{
  // a = (3 F_z R / (4 E*))^(1/3)
  const auto j = nlohmann::json::parse(
      contactEval("brush --model linear --sigma-x 0 --sigma-y 0 --phi 0 --contact-modulus 1e7 --sphere-radius 0.2 "
                  "--stiffness 1e8 --load 3000 --friction 1").out);
  EXPECT_NEAR(j["patch_radius"].get<double>(), std::cbrt(3.0 * 3000 * 0.2 / (4.0 * 1e7)), 1e-15);
}

TEST(ContactEvalBrush, CovarianceOfTheForces)
{
  // the linear model: J Sigma J^T with eqs. 61-62 (C_sigma = 8/3 k a^3 on the Fig. 4 parameters); the steady model
  // by the unscented transform; a zero covariance exactly zero
  const std::string point = "--sigma-x 0.001 --sigma-y 0.0005 --phi 0.1 " + kFig4;
  const auto lin = nlohmann::json::parse(contactEval("brush --model linear " + point + "--covariance 1e-8 0 0 4e-8 0 0").out);
  ASSERT_TRUE(lin["covariance"].is_array());
  ASSERT_EQ(lin["covariance"].size(), 9u);
  EXPECT_EQ(lin["covariance_method"], "jacobian");
  const double C_sigma = 8.0 / 3.0 * 1.023e8 * 0.05 * 0.05 * 0.05;
  EXPECT_NEAR(lin["covariance"][0].get<double>(), C_sigma * C_sigma * 1e-8, 1e-9 * C_sigma * C_sigma * 1e-8);
  EXPECT_NEAR(lin["covariance"][4].get<double>(), C_sigma * C_sigma * 4e-8, 1e-9 * C_sigma * C_sigma * 4e-8);
  EXPECT_DOUBLE_EQ(lin["covariance"][1].get<double>(), 0.0);
  EXPECT_NEAR(lin["std"][0].get<double>(), C_sigma * 1e-4, 1e-9 * C_sigma);
  const auto st = nlohmann::json::parse(contactEval("brush --model steady " + point + "--covariance 1e-8 0 0 4e-8 0 0").out);
  EXPECT_EQ(st["covariance_method"], "unscented");
  EXPECT_NEAR(st["covariance"][0].get<double>(), lin["covariance"][0].get<double>(),
              0.05 * lin["covariance"][0].get<double>());  // adhesion: the two models agree
  const auto zero = nlohmann::json::parse(contactEval("brush --model steady " + point + "--covariance 0 0 0 0 0 0").out);
  EXPECT_EQ(zero["covariance_method"], "zero");
  for (const auto& x : zero["covariance"])
    EXPECT_EQ(x.get<double>(), 0.0);
}

TEST(ContactEval, SpeedStdGivesTheSpreadOfTheResistance)
{
  const auto j = nlohmann::json::parse(contactEval(kPaper + "--speed 0.7 --speed-std 0.01").out);
  EXPECT_EQ(j["spread_method"], "unscented");
  // small spread: the derivative times the speed's sd
  const CylinderExact model(paper());
  const double dF = (model.solve(0.7 + 1e-5).F_R - model.solve(0.7 - 1e-5).F_R) / 2e-5;
  EXPECT_NEAR(j["F_R_std"].get<double>(), std::abs(dF) * 0.01, 0.01 * std::abs(dF) * 0.01);
  EXPECT_GT(j["mu_roll_std"].get<double>(), 0.0);
  const auto zero = nlohmann::json::parse(contactEval(kPaper + "--speed 0.7 --speed-std 0").out);
  EXPECT_EQ(zero["F_R_std"].get<double>(), 0.0);
}

TEST(ContactEvalBrush, BadInputFailsWithAMessage)
{
  for (const std::string& args : std::vector<std::string>{
           "brush --model fancy --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4,
           "brush --sliding-law viscous --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4,
           "brush --sigma-x nan --sigma-y 0 --phi 0 " + kFig4,
           "brush --sigma-x 0 --sigma-y 0 --phi 0 --stiffness 1e8 --load 3000 --friction 1",  // no a
           "brush --sigma-x 0 --sigma-y 0 --phi 0 --patch-radius -1 --stiffness 1e8 --load 3000 --friction 1",
           "brush --sigma-x 0 --sigma-y 0 --phi 0 --patch-radius 0.05 --stiffness 1e8 --load 3000 --friction -1",
           "brush --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4 + "--resolution 1",
           "brush --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4 + "--model transient --distance -1",
           "brush --sigma-x 0 --sigma-y 0 --phi 0 --contact-modulus 1e7 --stiffness 1e8 --load 1 --friction 1",
           "slips --omega 0 0 --vc 0 0 --rolling-radius 0.1",
           "slips --omega 0 0 1 --vc 0 0 --rolling-radius 0",
           "slips --omega 0 0 1 --vc 0 inf --rolling-radius 0.1",
           "slips --omega 0 0 1 --vc 0 0 --rolling-radius 0.1 --turn-rate 1 --tilt-ratio 0.5",
           "brush --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4 + "--covariance 1e-6 0 0 -1e-6 0 1e-4",  // negative
           "brush --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4 + "--covariance 1e-6 5e-6 0 1e-6 0 1e-4",  // beyond +-1
           "brush --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4 + "--covariance 1e-6 nan 0 1e-6 0 1e-4",
           "brush --sigma-x 0 --sigma-y 0 --phi 0 " + kFig4 + "--covariance 1e-6 0 0",  // not six numbers
           kPaper + "--speed 0.5 --speed-std -0.1",
           kPaper + "--speed 0.5 --speed-std nan",
       })
  {
    const Outcome r = contactEval(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_FALSE(r.err.empty()) << args;
    EXPECT_TRUE(r.out.empty()) << args << " printed " << r.out;
  }
}

}  // namespace
}  // namespace sphere_contact_estimator
