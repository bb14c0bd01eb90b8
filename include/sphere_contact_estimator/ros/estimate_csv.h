#pragma once

// STL
#include <ostream>
#include <string>
#include <vector>

// Package
#include "sphere_contact_estimator/ContactEstimate.h"

namespace sphere_contact_estimator
{
/// One CSV row per ContactEstimate (bag_analyze --csv; scripts/plot_analysis.py reads it). Every number of
/// the message, flattened, with t = stamp - the first stamp.
class EstimateCsv
{
public:
  /// Writes the header line, after `preamble`'s lines each as a comment ("# ..."): what made the estimates.
  explicit EstimateCsv(std::ostream& out, const std::vector<std::string>& preamble = {});
  void write(const ContactEstimate& estimate);

private:
  std::ostream& out_;
  bool have_start_ = false;
  ros::Time start_;
};

}  // namespace sphere_contact_estimator
