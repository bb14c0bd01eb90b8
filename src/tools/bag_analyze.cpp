// bag_analyze: recorded runs through the contact estimator, offline and as fast as the machine allows.
// Reads a bag, runs the node's own estimator class (OdometryEstimator) with a parameter file and model,
// writes an output bag with the node's topics beside the input's, and a CSV for scripts/plot_analysis.py;
// ends with a summary of the run. Several bags (or directories of them) are analysed in parallel, one output bag and
// CSV each in the --output and --csv folders, with a combined summary (summary.csv in the --csv folder and a table).
// Errors: a message on stderr and exit status 2 (CLI11's for usage); with several bags, a bag that cannot be analysed
// is named and skipped, the others finish, and the status is 1.
//
//   bag_analyze --input run.bag --output run_analysis.bag --csv run.csv [--params my.yaml] [--brush-model auto]
//   bag_analyze --input A.bag B.bag DIR/ --output OUTDIR --csv OUTDIR [--jobs N]

// STL
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>

// POSIX
#include <unistd.h>

// CLI11
#include <CLI/CLI.hpp>

// ROS
#include <ros/time.h>

// Package
#include "sphere_contact_estimator/ros/bag_analyzer.h"
#include "sphere_contact_estimator/ros/bag_batch.h"
#include "sphere_contact_estimator/ros/config_file.h"

namespace
{
namespace sce = sphere_contact_estimator;

/// A progress bar on stderr, redrawn at most ten times a second.
class ProgressBar
{
public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

  void operator()(double fraction)
  {
    if (!enabled_)
      return;
    const auto now = std::chrono::steady_clock::now();
    if (fraction < 1.0 && now - last_ < std::chrono::milliseconds(100))
      return;
    last_ = now;
    const int width = 40, filled = static_cast<int>(fraction * width + 0.5);
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r[%s%s] %5.1f %%  %.1f s", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), 100.0 * fraction, elapsed);
    if (fraction >= 1.0)
      std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

private:
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
};
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{ "bag_analyze: replay a bag through the contact estimator offline (the node's estimator class); "
                "writes the node's topics to an output bag and a CSV, and prints a summary of the run" };
  sce::BagAnalysisOptions options;
  std::string params;
  std::vector<std::string> sets;
  std::string brush_model, sliding_law, rr_model, progress = "auto";
  bool estimates_only = false, as_set = false;
  std::vector<std::string> inputs;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  app.add_option("--input,-i", inputs, "bag to read; or several bags and directories of bags (*.bag), analysed in "
                                       "parallel")->required()->expected(1, -1);
  app.add_option("--output,-o", options.output, "bag to write: the estimate topics and the input topics (several "
                                                "inputs: the folder for each <name>_analysis.bag)");
  app.add_option("--csv", options.csv, "CSV of every estimate (scripts/plot_analysis.py plots it; several inputs: the "
                                       "folder for each <name>.csv and summary.csv)");
  app.add_flag("--set-of-bags", as_set, "treat the input as a set even when it is one bag: --output and --csv name "
                                        "folders, and summary.csv is written (scripts that shard a list of bags)");
  app.add_option("--jobs,-j", jobs, "bags analysed at once, each on its own core (default: all cores)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--params,-p", params,
                 "parameter file in the node's format (default: the package's config/contact_estimator.yaml, "
                 "as contact_estimator.launch loads it)");
  app.add_option("--set", sets, "NAME=VALUE: one parameter, after the file (repeatable)");
  // (the three models' names are cfg/ContactEstimator.cfg's enums, checked where they are set: setParameter)
  app.add_option("--brush-model", brush_model, "brush model, overriding the file: off, linear, steady, transient, auto");
  app.add_option("--sliding-law", sliding_law, "sliding law of the brush models, overriding the file: coulomb (eq. 4b) "
                                               "or rigid (Sect. 6's approximation, as the paper's Fig. 4)");
  app.add_option("--rolling-resistance-model", rr_model, "rolling-resistance model, overriding the file: off, exact, "
                                                          "expansion, table");
  app.add_option("--odom-topic", options.odom_topic, "nav_msgs/Odometry topic (default: the bag's only one)");
  app.add_option("--topics", options.topics, "input topics to copy into the output (default: all)");
  app.add_flag("--estimates-only", estimates_only, "copy no input topic into the output");
  app.add_option("--start,-s", options.start, "start this many seconds after the bag's first message")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--end,-e", options.end, "end this many seconds after the bag's first message")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--progress", progress, "progress bar on stderr: auto (when it is a terminal), always, never")
      ->check(CLI::IsMember({ "auto", "always", "never" }));
  CLI11_PARSE(app, argc, argv);
  options.copy_input = !estimates_only;
  if (options.output.empty() && options.csv.empty())
    std::cerr << "bag_analyze: note: neither --output nor --csv given: only the summary\n";

  try
  {
    ros::Time::init();
    if (params.empty())
      params = sce::defaultParameterFile();
    sce::applyParameterFile(options.config, params);
    sce::applyParameterSets(options.config, sets);
    for (const auto& [name, value] : { std::pair{ "brush_model", &brush_model }, { "sliding_law", &sliding_law },
                                       { "rolling_resistance_model", &rr_model } })
      if (!value->empty())
        sce::setParameter(options.config, name, *value);
    // what made the estimates, for the output's record
    options.config_source = "parameters " + params;
    for (const std::string& s : sets)
      options.config_source += ", --set " + s;
    for (const auto& [flag, value] : { std::pair{ "--brush-model", &brush_model }, { "--sliding-law", &sliding_law },
                                       { "--rolling-resistance-model", &rr_model } })
      if (!value->empty())
        options.config_source += std::string(", ") + flag + " " + *value;
    std::fprintf(stderr, "bag_analyze: %s\n", options.config_source.c_str());

    ProgressBar bar(progress == "always" || (progress == "auto" && isatty(STDERR_FILENO)));
    std::error_code ec;
    const bool batch = as_set || inputs.size() > 1 || std::filesystem::is_directory(inputs.front(), ec);
    if (batch)
    {
      // the set: one output bag and CSV per bag in the folders, the bags analysed in parallel, one progress bar
      const std::vector<std::string> bags = sce::expandBagInputs(inputs);
      for (const std::string* dir : { &options.output, &options.csv })
        if (!dir->empty() && !std::filesystem::is_directory(*dir) && !std::filesystem::create_directories(*dir, ec))
          throw std::runtime_error("cannot make the folder " + *dir + ": " + ec.message());
      const std::vector<sce::BagJob> set = sce::makeBagJobs(bags, options.output, options.csv);
      const auto start = std::chrono::steady_clock::now();
      const std::vector<sce::BagJobResult> results = sce::analyzeBags(set, options, jobs, [&bar](double f) { bar(f); });
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("bag_analyze: %zu bags, %d at a time, in %.3f s\n%s", results.size(), std::min<int>(jobs, results.size()),
                  wall, sce::batchSummaryTable(results, wall).c_str());
      if (!options.csv.empty())
      {
        const std::string path = (std::filesystem::path(options.csv) / "summary.csv").string();
        std::ofstream summary(path);
        sce::writeBatchSummaryCsv(summary, results, wall);
        if (!summary.flush())
          throw std::runtime_error("writing " + path + " failed");
        std::printf("  summary               %s\n", path.c_str());
      }
      int failed = 0;
      for (const sce::BagJobResult& r : results)
        for (const std::string& w : r.analysis.warnings)
          std::cerr << "bag_analyze: warning: " << r.job.input << ": " << w << '\n';
      for (const sce::BagJobResult& r : results)
        if (!r.ok)
        {
          ++failed;
          std::cerr << "bag_analyze: skipped " << r.job.input << ": " << r.error << '\n';
        }
      return failed ? 1 : 0;
    }
    options.input = inputs.front();
    if (!std::filesystem::is_regular_file(options.input, ec))
      throw std::runtime_error("no such bag: " + options.input);
    const auto start = std::chrono::steady_clock::now();
    const sce::BagAnalysisResult r = sce::analyzeBag(options, [&bar](double f) { bar(f); });
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const std::string& w : r.warnings)
      std::cerr << "bag_analyze: warning: " << w << '\n';

    std::printf("bag_analyze: %s, odometry on %s\n", options.input.c_str(), r.odom_topic.c_str());
    std::printf("  messages              %llu odometry, %llu estimates (%llu skipped: no orientation, %llu rejected), "
                "%llu copied\n",
                static_cast<unsigned long long>(r.odometry), static_cast<unsigned long long>(r.estimates),
                static_cast<unsigned long long>(r.no_orientation), static_cast<unsigned long long>(r.rejected),
                static_cast<unsigned long long>(r.copied));
    if (r.dropped + r.out_of_order + r.tf_stale > 0)
      std::printf("  odometry stream       %llu messages missing (gaps in header.seq), %llu stamps out of order (answered "
                  "without a reset), %llu with tf older than tf_max_age (odometry orientation)\n",
                  static_cast<unsigned long long>(r.dropped), static_cast<unsigned long long>(r.out_of_order),
                  static_cast<unsigned long long>(r.tf_stale));
    std::printf("  speed                 %.3f s of bag in %.3f s (%.0f x real time, %.0f odometry messages/s)\n",
                r.bag_seconds, wall, wall > 0.0 ? r.bag_seconds / wall : 0.0, wall > 0.0 ? r.odometry / wall : 0.0);
    for (const std::string& t : r.replaced_topics)
      std::printf("  replaced              %s from the input by this analysis\n", t.c_str());
    std::printf("%s", r.summary.report().c_str());
    if (!options.output.empty())
      std::printf("  output bag            %s\n", options.output.c_str());
    if (!options.csv.empty())
      std::printf("  csv                   %s\n", options.csv.c_str());
  }
  catch (const std::exception& e)
  {
    std::cerr << "bag_analyze: error: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
