// calibrate: the contact's parameters from recorded runs. Reads the odometry the node reads and an IMU at the sphere's
// centre from one or more bags, fits the brush's bristle stiffness and friction (ContactFit: errors in the inputs,
// Ceres Solver), writes a parameter file the node loads, a report (a CSV of every message and its figures) and a
// summary on the terminal. Errors: a message on stderr and exit status 2.
//
//   calibrate --input run.bag [more.bag DIR/] --params robot.yaml --output fitted.yaml [--report DIR]

// STL
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

// CLI11
#include <CLI/CLI.hpp>

// ROS
#include <ros/package.h>
#include <ros/time.h>

// Package
#include "sphere_contact_estimator/core/calibration/contact_fit.h"
#include "sphere_contact_estimator/ros/bag_batch.h"
#include "sphere_contact_estimator/ros/calibration_recording.h"
#include "sphere_contact_estimator/ros/config_file.h"
#include "sphere_contact_estimator/ros/config_report.h"
#include "sphere_contact_estimator/ros/config_settings.h"

namespace
{
namespace sce = sphere_contact_estimator;

std::string format(const char* f, double v)
{
  char text[64];
  std::snprintf(text, sizeof text, f, v);
  return text;
}

// What the run covered and how the fit went, as the YAML's header and the terminal's summary share it.
std::string coverage(const sce::FitResult& r, const sce::CalibrationRecording& rec)
{
  std::ostringstream s;
  s << r.used << " of " << r.samples << " odometry messages in the fit; speeds " << format("%.2f", r.speed_min) << "-"
    << format("%.2f", r.speed_max) << " m/s, slips up to " << format("%.3g", r.slip_max) << ", up to "
    << format("%.0f", 100.0 * r.sliding_max) << " % of the patch sliding; IMU " << format("%.0f", rec.imu_rate)
    << " Hz on " << rec.imu_topic << ", noise " << format("%.3g", rec.imu_noise) << " m/s^2 (" << rec.imu_noise_source
    << ")";
  return s.str();
}

std::string quality(const sce::FitResult& r)
{
  return "reduced chi-square " + format("%.2f", r.reduced_chi2) + " (1: residuals as the IMU's noise), " +
         (r.converged ? "converged" : "NOT converged") + " after " + std::to_string(r.iterations) + " iterations";
}

// Where the fit's residuals say the run is not the model's: their spread beyond the noise, or a mean off zero.
std::vector<std::string> mismatches(const sce::FitResult& r)
{
  std::vector<std::string> out;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  int n = 0;
  for (std::size_t i = 0; i < r.residuals.size(); ++i)
    if (r.used_mask[i] && r.residuals[i].allFinite())
    {
      mean += r.residuals[i];
      ++n;
    }
  if (n > 0)
    mean /= n;
  // the reduced chi-square of a run of the model stays within a few sqrt(2 / dof) of 1 (100 synthetic runs: 0.92-1.06);
  // a rolling radius off by 0.5 % gave 1.38, an IMU bias of 0.2 m/s^2 1.29-1.37
  const double chi2_limit = std::max(1.2, 1.0 + 5.0 * std::sqrt(2.0 / std::max(1, 2 * r.used)));
  if (r.reduced_chi2 > chi2_limit)
    out.push_back("the reduced chi-square is " + format("%.2f", r.reduced_chi2) + " (runs of the model stay below " +
                  format("%.2f", chi2_limit) + "): the run is not the model's (a rolling radius off by half a per cent "
                  "gives 1.4; another pressure distribution, an IMU bias, a floor that gives, bumps) or the IMU is "
                  "noisier than declared (--imu-noise); see residuals.png");
  if (r.mismatch())
    out.push_back("the residuals run in streaks (lag-1 autocorrelation " + format("%.2f", r.residual_autocorrelation.maxCoeff()) +
                  "; runs of the model stay below " + format("%.2f", sce::FitResult::mismatchThreshold(r.used)) +
                  "): the run is not the model's (another pressure distribution, an IMU bias, a floor that gives) or "
                  "the IMU's noise is filtered; see residuals.png, and do not trust these values");
  if (n > 0 && mean.norm() > 5.0 / std::sqrt(static_cast<double>(n)) && mean.norm() > 0.1)
    out.push_back("the residuals' mean is (" + format("%.2f", mean.x()) + ", " + format("%.2f", mean.y()) +
                  ") standard deviations, far from zero: a bias on the IMU, or its frame off the robot's");
  return out;
}

// Gaps in the recording, named by topic: messages without an IMU sample near them, and odometry that restarted the
// estimator (a gap or a time jump). Both are left out of the fit and counted; these say where they come from.
std::vector<std::string> gaps(const sce::FitResult& r, const sce::CalibrationRecording& rec, double max_imu_gap)
{
  std::vector<std::string> out;
  const int no_imu = r.rejected[static_cast<int>(sce::Rejection::NoImu)];
  if (no_imu > 0)
    out.push_back(std::to_string(no_imu) + " odometry messages (" +
                  format("%.1f", 100.0 * no_imu / std::max(1, r.samples)) + " %) have no IMU sample on " +
                  rec.imu_topic + " within " + format("%.0f", 1e3 * max_imu_gap) +
                  " ms of them: gaps in the IMU's recording; they are left out");
  const int resets = r.rejected[static_cast<int>(sce::Rejection::Reset)];
  if (resets > 0)
    out.push_back(std::to_string(resets) + " gap(s) or time jump(s) in " + rec.odom_topic +
                  ": the estimator starts afresh after each (the message there is left out)");
  return out;
}

// Everything the summary and the file's header warn of: a run that is not the model's, and gaps in the recording.
std::vector<std::string> warnings(const sce::FitResult& r, const sce::CalibrationRecording& rec, double max_imu_gap)
{
  std::vector<std::string> out = mismatches(r);
  for (std::string& w : gaps(r, rec, max_imu_gap))
    out.push_back(std::move(w));
  return out;
}

// Where the floor's damping is fitted, what its other two parameters are.
constexpr const char* kFloorHeld =
    "NOT determined (held): at the run's speeds the data determine only surface_damping / surface_stiffness";

std::string valueComment(const sce::FittedValue& v)
{
  if (!v.fitted)
    return "";
  if (v.determined)
    return "fitted: sd " + format("%.3g", v.sd) + ", 95 % [" + format("%.4g", v.low) + ", " + format("%.4g", v.high) +
           "], start " + format("%.4g", v.start) + (v.note.empty() ? "" : "; " + v.note);
  if (v.lower_bound > 0.0)
    return "NOT determined by the data (" + v.note + "): >= " + format("%.3g", v.lower_bound) +
           "; this value is the one the others were fitted with";
  return "NOT determined by the data (" + v.note + ", sd " + format("%.3g", v.sd) + "); the parameter file's value kept";
}

void writeReportCsv(const std::string& path, const sce::CalibrationRecording& rec, const sce::FitResult& r,
                    const std::string& header)
{
  std::ofstream out(path);
  if (!out)
    throw std::runtime_error("cannot write " + path);
  std::istringstream lines(header);
  for (std::string line; std::getline(lines, line);)
    out << "# " << line << "\n";
  out << "t,used,rejection,speed,slip_x,slip_y,spin,sliding,measured_x,measured_y,predicted_x,predicted_y,force_sd,"
         "residual_x,residual_y\n";
  const auto num = [](double v) { return std::isfinite(v) ? format("%.9g", v) : std::string("nan"); };
  double offset = 0.0;
  for (std::size_t i = 0; i < rec.samples.size(); ++i)
  {
    if (i > 0 && rec.bag[i] != rec.bag[i - 1])
      offset = rec.samples[i].input.stamp - rec.time[i];  // runs one after the other on one time axis
    const sce::CalibrationSample& s = rec.samples[i];
    const sce::Prediction& p = r.fitted;
    out << num(rec.time[i] + offset) << "," << int(r.used_mask[i]) << ","
        << (r.used_mask[i] ? "" : sce::toString(r.rejection[i])) << "," << num(p.speed[i]) << "," << num(p.slip[i].x())
        << "," << num(p.slip[i].y()) << "," << num(p.spin[i]) << "," << num(p.sliding[i]) << ","
        << num(s.has_force ? s.force.x() : NAN) << "," << num(s.has_force ? s.force.y() : NAN) << ","
        << num(p.force[i].x()) << "," << num(p.force[i].y()) << "," << num(s.force_sd) << "," << num(r.residuals[i].x())
        << "," << num(r.residuals[i].y()) << "\n";
  }
}

// The report's figures: scripts/plot_calibration.py beside this executable (installed) or in the package's source.
void drawReport(const std::string& csv, const std::string& dir)
{
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    candidates.push_back(self.parent_path() / "plot_calibration.py");
  const std::string share = ros::package::getPath("sphere_contact_estimator");
  if (!share.empty())
    candidates.push_back(fs::path(share) / "scripts" / "plot_calibration.py");
  for (const fs::path& script : candidates)
    if (fs::exists(script))
    {
      const std::string command = "/usr/bin/python3 '" + script.string() + "' '" + csv + "' '" + dir + "' > /dev/null";
      if (std::system(command.c_str()) != 0)
        std::cerr << "calibrate: warning: the figures could not be drawn (" << command << ")\n";
      return;
    }
  std::cerr << "calibrate: warning: scripts/plot_calibration.py not found: the report has its CSV only\n";
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{ "calibrate: the brush's bristle stiffness and friction, and the floor's damping, from recorded runs "
                "(odometry and an IMU at the sphere's centre); writes a parameter file the node loads, a report and a "
                "summary" };
  std::vector<std::string> inputs, sets, fit = { "bristle_stiffness", "friction" };
  std::string params, output, report;
  sce::CalibrationReadOptions read;
  app.add_option("--input,-i", inputs, "bags, and folders of bags (*.bag), read in order")->required();
  app.add_option("--params,-p", params,
                 "the robot's parameter file in the node's format (default: the package's config/contact_estimator.yaml)");
  app.add_option("--set", sets, "NAME=VALUE: one parameter, after the file (repeatable)");
  app.add_option("--output,-o", output, "the fitted parameter file (the node's format, with a header)")->required();
  app.add_option("--report,-r", report, "folder for the report: calibration.csv and its figures");
  app.add_option("--odom-topic", read.odom_topic, "nav_msgs/Odometry topic (default: the bag's only one)");
  app.add_option("--imu-topic", read.imu_topic, "sensor_msgs/Imu topic, at the sphere's centre (default: the bag's only one)");
  app.add_option("--imu-noise", read.imu_noise,
                 "the IMU's noise, sd of its acceleration on each axis [m/s^2] (default: the messages' covariance, else "
                 "estimated from the run)")
      ->check(CLI::PositiveNumber);
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  app.add_option("--jobs,-j", jobs, "threads for the fit (default: all cores; the values agree to rounding across counts)")
      ->check(CLI::PositiveNumber);
  app.add_option("--fit", fit,
                 "the parameters to fit; add surface_damping for the floor (its relaxation time), from a run the fit of "
                 "the other two shows to be the model's (docs/calibration.md)")->delimiter(',')->check(CLI::IsMember({ "bristle_stiffness", "friction", "surface_damping" }));
  CLI11_PARSE(app, argc, argv);

  try
  {
    ros::Time::init();
    const auto started = std::chrono::steady_clock::now();
    if (params.empty())
      params = sce::defaultParameterFile();
    sce::applyParameterFile(read.config, params);
    sce::applyParameterSets(read.config, sets);
    const std::vector<std::string> bags = sce::expandBagInputs(inputs);
    if (bags.empty())
      throw std::runtime_error("no bag among the inputs");
    const sce::CalibrationRecording rec = sce::readCalibrationBags(bags, read);
    const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const sce::EstimatorSettings settings = sce::settingsFromConfig(read.config);
    sce::FitOptions options;
    options.threads = jobs;
    for (int j = 0; j < static_cast<int>(sce::FitParameter::Count); ++j)
      options.fit[j] = std::find(fit.begin(), fit.end(), sce::parameterName(static_cast<sce::FitParameter>(j))) != fit.end();
    const sce::FitResult r = sce::fitContact(rec.samples, settings, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    // the parameter file: the robot's, with the determined values, and a header that says where they came from
    sce::ContactEstimatorConfig fitted = read.config;
    for (const sce::FittedValue& v : r.values)
      if (v.fitted)
      {
        sce::setParameter(fitted, sce::parameterName(v.parameter), format("%.6g", sce::parameterValue(r.settings, v.parameter)));
      }
    std::string header = "Fitted by calibrate from " + std::to_string(bags.size()) + " bag(s):\n";
    for (const std::string& b : bags)
      header += "  " + b + "\n";
    header += "starting from " + params + "\n" + coverage(r, rec) + "\n" + quality(r) + "\n";
    for (const std::string& w : warnings(r, rec, read.max_imu_gap))
      header += "WARNING: " + w + "\n";
    {
      std::ofstream out(output);
      if (!out)
        throw std::runtime_error("cannot write " + output);
      std::istringstream lines(header);
      for (std::string line; std::getline(lines, line);)
        out << "# " << line << "\n";
      out << "# Load it as the node's parameter file: roslaunch sphere_contact_estimator contact_estimator.launch "
             "config:=" << std::filesystem::absolute(output).string() << "\n\n";
      const bool floor = r.values[static_cast<int>(sce::FitParameter::SurfaceDamping)].fitted;
      out << sce::parameterFileText(fitted, [&](const std::string& name) {
        for (const sce::FittedValue& v : r.values)
          if (name == sce::parameterName(v.parameter))
            return valueComment(v);
        if (floor && (name == "surface_stiffness" || name == "surface_density"))
          return std::string(kFloorHeld);
        return std::string();
      });
    }
    if (!report.empty())
    {
      std::filesystem::create_directories(report);
      const std::string csv = report + "/calibration.csv";
      writeReportCsv(csv, rec, r, header);
      drawReport(csv, report);
    }

    // the summary
    std::printf("calibrate: %zu bag(s), %s\n", bags.size(), coverage(r, rec).c_str());
    std::string rejected;
    for (int i = 0; i < static_cast<int>(sce::Rejection::Count); ++i)
      if (r.rejected[i] > 0)
        rejected += (rejected.empty() ? "" : ", ") + std::to_string(r.rejected[i]) + " " +
                    sce::toString(static_cast<sce::Rejection>(i));
    std::printf("  not in the fit: %s\n", rejected.empty() ? "none" : rejected.c_str());
    if (rec.imu_without_orientation > 0)
      std::printf("  IMU messages without an orientation (none in the message, none in tf): %llu, unused\n",
                  static_cast<unsigned long long>(rec.imu_without_orientation));
    std::printf("  %-18s %12s %12s %12s %27s  %s\n", "parameter", "start", "fitted", "sd", "95 % interval", "");
    for (const sce::FittedValue& v : r.values)
    {
      if (!v.fitted)
        continue;
      const std::string interval = "[" + format("%.4g", v.low) + ", " + format("%.4g", v.high) + "]";
      if (v.determined)
        std::printf("  %-18s %12.4g %12.5g %12.3g %27s  determined%s\n", sce::parameterName(v.parameter), v.start,
                    v.value, v.sd, interval.c_str(), v.note.empty() ? "" : (" " + v.note).c_str());
      else
        std::printf("  %-18s %12.4g %12s %12s %27s  %s\n", sce::parameterName(v.parameter), v.start,
                    v.lower_bound > 0.0 ? (">= " + format("%.3g", v.lower_bound)).c_str() : "-", "-", "-",
                    v.note.c_str());
    }
    {
      // the correlations of the fitted parameters, in the order of r.values where fitted
      std::vector<const char*> names;
      for (sce::FitParameter p : r.correlated)
        names.push_back(sce::parameterName(p));
      std::string pairs;
      for (int a = 0; a < r.correlation.rows() && a < static_cast<int>(names.size()); ++a)
        for (int b = a + 1; b < r.correlation.cols() && b < static_cast<int>(names.size()); ++b)
          pairs += std::string(pairs.empty() ? "" : ", ") + names[a] + "/" + names[b] + " " + format("%.2f", r.correlation(a, b));
      if (!pairs.empty())
        std::printf("  correlations: %s\n", pairs.c_str());
    }
    if (r.values[static_cast<int>(sce::FitParameter::SurfaceDamping)].fitted)
      std::printf("  surface_stiffness and surface_density: %s\n", kFloorHeld);
    {
      // what the data determine is k a^3 (the slip stiffness), with a held at the parameter file's
      const sce::FittedValue& k = r.values[static_cast<int>(sce::FitParameter::BristleStiffness)];
      const double a = settings.brushParameters().a, a3 = a * a * a;
      if (k.fitted && k.determined)
        std::printf("  with a = %.4g m held: k a^3 = %.4g N, 95 %% [%.4g, %.4g] (slip stiffness C_sigma = 8/3 k a^3 = "
                    "%.4g N, any pressure)\n", a, k.value * a3, k.low * a3, k.high * a3, 8.0 / 3.0 * k.value * a3);
    }
    std::printf("  fit: %s, %.1f s (%.1f s reading the bags, %d thread(s) fitting)\n", quality(r).c_str(), seconds,
                read_seconds, jobs);
    for (const std::string& w : warnings(r, rec, read.max_imu_gap))
      std::printf("  WARNING: %s\n", w.c_str());
    std::printf("  parameter file: %s%s\n", output.c_str(), report.empty() ? "" : ("; report: " + report).c_str());
    return 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "calibrate: error: " << e.what() << "\n";
    return 2;
  }
}
