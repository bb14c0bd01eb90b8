#include "sphere_contact_estimator/ros/bag_batch.h"

// STL
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace sphere_contact_estimator
{
namespace fs = std::filesystem;

std::vector<std::string> expandBagInputs(const std::vector<std::string>& inputs)
{
  std::vector<std::string> bags;
  for (const std::string& in : inputs)
  {
    std::error_code ec;
    if (fs::is_directory(in, ec))
    {
      std::vector<std::string> found;
      for (const fs::directory_entry& e : fs::directory_iterator(in, ec))
        if (e.is_regular_file(ec) && e.path().extension() == ".bag")
          found.push_back(e.path().string());
      if (found.empty())
        throw std::runtime_error("no .bag files in the directory " + in);
      std::sort(found.begin(), found.end());
      bags.insert(bags.end(), found.begin(), found.end());
    }
    else if (fs::exists(in, ec))
      bags.push_back(in);
    else
      throw std::runtime_error("no such bag or directory: " + in);
  }
  return bags;
}

std::vector<BagJob> makeBagJobs(const std::vector<std::string>& bags, const std::string& output_dir,
                                const std::string& csv_dir)
{
  std::vector<BagJob> jobs;
  std::map<std::string, std::string> seen;
  for (const std::string& bag : bags)
  {
    BagJob j;
    j.input = bag;
    j.name = fs::path(bag).stem().string();
    const auto [it, fresh] = seen.emplace(j.name, bag);
    if (!fresh)
      throw std::runtime_error("two bags are named " + j.name + " (" + it->second + " and " + bag +
                               "): their outputs would overwrite each other; analyse them in separate calls");
    if (!output_dir.empty())
      j.output = (fs::path(output_dir) / (j.name + "_analysis.bag")).string();
    if (!csv_dir.empty())
      j.csv = (fs::path(csv_dir) / (j.name + ".csv")).string();
    jobs.push_back(j);
  }
  return jobs;
}

std::vector<BagJobResult> analyzeBags(const std::vector<BagJob>& jobs, const BagAnalysisOptions& common, int threads,
                                      const std::function<void(double)>& progress)
{
  std::vector<BagJobResult> results(jobs.size());
  // each bag's share of the work: its size
  std::vector<double> weight(jobs.size(), 1.0);
  double total = 0.0;
  for (std::size_t i = 0; i < jobs.size(); ++i)
  {
    std::error_code ec;
    const auto size = fs::file_size(jobs[i].input, ec);
    weight[i] = ec ? 1.0 : std::max(1.0, static_cast<double>(size));
    total += weight[i];
  }
  std::vector<double> done(jobs.size(), 0.0);  // fraction of each bag, guarded by lock
  std::mutex lock;
  const auto report = [&](std::size_t i, double fraction) {
    if (!progress)
      return;
    std::lock_guard<std::mutex> guard(lock);
    done[i] = fraction;
    double sum = 0.0;
    for (std::size_t k = 0; k < done.size(); ++k)
      sum += weight[k] * done[k];
    progress(total > 0.0 ? std::min(1.0, sum / total) : 1.0);
  };
  std::atomic<std::size_t> next{ 0 };
  const auto work = [&]() {
    for (std::size_t i = next++; i < jobs.size(); i = next++)
    {
      BagJobResult& r = results[i];
      r.job = jobs[i];
      BagAnalysisOptions o = common;
      o.input = jobs[i].input;
      o.output = jobs[i].output;
      o.csv = jobs[i].csv;
      const auto start = std::chrono::steady_clock::now();
      try
      {
        r.analysis = analyzeBag(o, [&](double f) { report(i, f); });
        r.ok = true;
      }
      catch (const std::exception& e)  // a bad bag is reported by name, and the others go on
      {
        r.error = e.what();
      }
      r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      report(i, 1.0);
    }
  };
  const int n = std::max(1, std::min<int>(threads, static_cast<int>(jobs.size())));
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t)
    pool.emplace_back(work);
  work();
  for (std::thread& t : pool)
    t.join();
  return results;
}

namespace
{
// The numbers of one row of the summary.
struct Row
{
  std::string bag, status;
  double odometry = 0, estimates = 0, skipped = 0, bag_seconds = 0, wall_seconds = 0, distance = 0, rr_energy = 0,
         brush_energy = 0, duration = 0, sliding_any = 0, sliding_mostly = 0, peak_force = 0, peak_utilisation = 0,
         peak_moment = 0, peak_rr = 0;
  std::array<double, 4> models{};  // estimates per brush model that ran: off, linear, steady, transient
};

Row rowOf(const BagJobResult& r)
{
  Row w;
  w.bag = r.job.name;
  w.status = r.ok ? "ok" : "failed";
  w.wall_seconds = r.wall_seconds;
  if (!r.ok)
    return w;
  const BagAnalysisResult& a = r.analysis;
  const RunSummary& s = a.summary;
  w.odometry = static_cast<double>(a.odometry);
  w.estimates = static_cast<double>(a.estimates);
  w.skipped = static_cast<double>(a.no_orientation + a.rejected);
  w.bag_seconds = a.bag_seconds;
  w.distance = s.distance();
  w.rr_energy = s.rollingResistanceEnergy();
  w.brush_energy = s.brushEnergy();
  w.duration = s.duration();
  w.sliding_any = s.slidingShareAny();
  w.sliding_mostly = s.slidingShareMostly();
  w.peak_force = s.peakForce();
  w.peak_utilisation = s.peakUtilisation();
  w.peak_moment = s.peakMoment();
  w.peak_rr = s.peakRollingResistance();
  for (int k = 0; k < 4; ++k)
    w.models[k] = static_cast<double>(s.brushModelsUsed()[k]);
  return w;
}

Row totalOf(const std::vector<BagJobResult>& results, double set_wall_seconds)
{
  Row t;
  t.bag = "total";
  int ok = 0;
  for (const BagJobResult& r : results)
  {
    if (!r.ok)
      continue;
    ++ok;
    const Row w = rowOf(r);
    t.odometry += w.odometry;
    t.estimates += w.estimates;
    t.skipped += w.skipped;
    t.bag_seconds += w.bag_seconds;
    t.distance += w.distance;
    t.rr_energy += w.rr_energy;
    t.brush_energy += w.brush_energy;
    t.sliding_any += w.sliding_any * w.duration;  // weighted by time, divided below
    t.sliding_mostly += w.sliding_mostly * w.duration;
    t.duration += w.duration;
    t.peak_force = std::max(t.peak_force, w.peak_force);
    t.peak_utilisation = std::max(t.peak_utilisation, w.peak_utilisation);
    t.peak_moment = std::max(t.peak_moment, w.peak_moment);
    t.peak_rr = std::max(t.peak_rr, w.peak_rr);
    for (int k = 0; k < 4; ++k)
      t.models[k] += w.models[k];
  }
  if (t.duration > 0.0)
  {
    t.sliding_any /= t.duration;
    t.sliding_mostly /= t.duration;
  }
  t.wall_seconds = set_wall_seconds;
  t.status = std::to_string(ok) + " of " + std::to_string(results.size()) + " ok";
  return t;
}

double share(const Row& w, int k)
{
  const double n = w.models[0] + w.models[1] + w.models[2] + w.models[3];
  return n > 0.0 ? w.models[k] / n : 0.0;
}

std::string csvText(const std::string& s)
{
  if (s.find_first_of(",\"\n") == std::string::npos)
    return s;
  std::string q = "\"";
  for (char c : s)
    q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
}  // namespace

void writeBatchSummaryCsv(std::ostream& out, const std::vector<BagJobResult>& results, double set_wall_seconds)
{
  out << "bag,status,odometry,estimates,skipped,bag_seconds,wall_seconds,odometry_per_second,distance,"
         "rolling_resistance_energy,brush_energy,sliding_share,mostly_sliding_share,peak_force,peak_utilisation,"
         "peak_moment,peak_rolling_resistance,linear_share,steady_share,transient_share,error\n";
  const auto line = [&](const Row& w, const std::string& error) {
    char buffer[1024];
    std::snprintf(buffer, sizeof(buffer),
                  "%.0f,%.0f,%.0f,%.6g,%.6g,%.0f,%.6g,%.6g,%.6g,%.4g,%.4g,%.6g,%.4g,%.6g,%.6g,%.4g,%.4g,%.4g,", w.odometry,
                  w.estimates, w.skipped, w.bag_seconds, w.wall_seconds,
                  w.wall_seconds > 0.0 ? w.odometry / w.wall_seconds : 0.0, w.distance, w.rr_energy, w.brush_energy,
                  w.sliding_any, w.sliding_mostly, w.peak_force, w.peak_utilisation, w.peak_moment, w.peak_rr,
                  share(w, 1), share(w, 2), share(w, 3));
    out << csvText(w.bag) << ',' << csvText(w.status) << ',' << buffer << csvText(error) << '\n';
  };
  for (const BagJobResult& r : results)
    line(rowOf(r), r.error);
  line(totalOf(results, set_wall_seconds), "");
}

std::string batchSummaryTable(const std::vector<BagJobResult>& results, double set_wall_seconds)
{
  std::string text;
  char buffer[512];
  std::snprintf(buffer, sizeof(buffer), "%-24s %-10s %9s %8s %9s %9s %9s %7s %7s %8s %6s %5s %5s %5s %9s\n", "bag",
                "status", "odometry", "bag [s]", "dist [m]", "E_rr [J]", "E_br [J]", "slide", ">50%", "peak F", "util",
                "lin", "std", "trn", "msgs/s");
  text += buffer;
  const auto line = [&](const Row& w) {
    std::snprintf(buffer, sizeof(buffer),
                  "%-24.24s %-10.10s %9.0f %8.2f %9.3f %9.4g %9.4g %6.1f%% %6.1f%% %8.4g %6.3f %4.0f%% %4.0f%% %4.0f%% %9.0f\n",
                  w.bag.c_str(), w.status.c_str(), w.odometry, w.bag_seconds, w.distance, w.rr_energy, w.brush_energy,
                  100.0 * w.sliding_any, 100.0 * w.sliding_mostly, w.peak_force, w.peak_utilisation,
                  100.0 * share(w, 1), 100.0 * share(w, 2), 100.0 * share(w, 3),
                  w.wall_seconds > 0.0 ? w.odometry / w.wall_seconds : 0.0);
    text += buffer;
  };
  for (const BagJobResult& r : results)
    line(rowOf(r));
  line(totalOf(results, set_wall_seconds));
  for (const BagJobResult& r : results)
    if (!r.ok)
      text += "  " + r.job.name + " (" + r.job.input + "): " + r.error + "\n";
  return text;
}

}  // namespace sphere_contact_estimator
