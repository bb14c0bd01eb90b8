#pragma once

// STL
#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

// CLI11
#include <CLI/CLI.hpp>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_parameters.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

namespace sphere_contact_estimator::cli
{
/// What `contact_eval cylinder` was asked for.
struct CylinderOptions
{
  CylinderParameters parameters;
  std::vector<double> speed;  ///< --speed v (zero or one value)
  std::vector<double> sweep;  ///< --sweep VMIN VMAX N (zero or three values)
  bool log_sweep = false;     ///< geometric instead of even spacing
  bool peak = false;          ///< --peak: the model's maximum of mu_roll over v
  std::string model = "exact";
  std::size_t table_size = CylinderTable::kDefaultSize;
  double table_v_max = 0.0;
  std::optional<double> speed_std;  ///< --speed-std S: the speed's standard deviation [m/s]
};

/// Registers the `cylinder` subcommand and its flags on app.
CLI::App* addCylinderCommand(CLI::App& app, CylinderOptions& options);

/// Runs it: one JSON object (--speed) or an array of them (--sweep) on out. Throws
/// std::invalid_argument with a message for the user on bad input.
void runCylinderCommand(const CylinderOptions& options, std::ostream& out);

}  // namespace sphere_contact_estimator::cli
