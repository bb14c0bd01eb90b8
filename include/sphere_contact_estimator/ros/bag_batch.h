#pragma once

// STL
#include <functional>
#include <ostream>
#include <string>
#include <vector>

// Package
#include "sphere_contact_estimator/ros/bag_analyzer.h"

namespace sphere_contact_estimator
{
/// One bag of a set: where it is read from and where its analysis goes (empty: not written).
struct BagJob
{
  std::string name;  ///< the bag's file name without .bag: the row in the summary and the outputs' stem
  std::string input, output, csv;
};

/// What became of one bag of the set.
struct BagJobResult
{
  BagJob job;
  bool ok = false;
  std::string error;          ///< why not, for people
  BagAnalysisResult analysis;  ///< when ok
  double wall_seconds = 0.0;
};

/// The bags named by files and directories (every *.bag in a directory, not recursing, in name order). Throws
/// std::runtime_error for a path that does not exist or a directory without bags.
std::vector<std::string> expandBagInputs(const std::vector<std::string>& inputs);

/// Jobs for the bags: each gives <name>_analysis.bag in output_dir and <name>.csv in csv_dir (an empty directory:
/// none). Throws std::runtime_error when two bags share a name (their outputs would overwrite each other).
std::vector<BagJob> makeBagJobs(const std::vector<std::string>& bags, const std::string& output_dir,
                                const std::string& csv_dir);

/// Analyses every job's bag with the same options (analyzeBag; `common`'s input, output and csv are each job's),
/// `threads` bags at a time, each on its own thread with its own estimator. A bag that cannot be analysed is reported
/// in its result and the others go on. progress(fraction) over the whole set, weighted by the bags' sizes, from
/// one thread at a time.
std::vector<BagJobResult> analyzeBags(const std::vector<BagJob>& jobs, const BagAnalysisOptions& common, int threads,
                                      const std::function<void(double)>& progress = {});

/// The combined summary, one row per bag and a row of totals (counts, time, distance and energies summed; the
/// sliding shares weighted by time and the models' by estimates; peaks the largest; wall time the set's own):
/// as CSV (`wall_seconds` of the totals is `set_wall_seconds`) and as a table for people.
void writeBatchSummaryCsv(std::ostream& out, const std::vector<BagJobResult>& results, double set_wall_seconds);
std::string batchSummaryTable(const std::vector<BagJobResult>& results, double set_wall_seconds);

}  // namespace sphere_contact_estimator
