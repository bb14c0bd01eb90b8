#pragma once

// STL
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

// CLI11
#include <CLI/CLI.hpp>

// Package
#include "sphere_contact_estimator/core/brush/brush_parameters.h"

namespace sphere_contact_estimator::cli
{
/// What `contact_eval slips` was asked for.
struct SlipsOptions
{
  std::vector<double> omega;  ///< WX WY WZ [rad/s], in `frame`
  std::vector<double> vc;     ///< VX VY [m/s], in `frame`
  double rolling_radius = 0.0;
  std::optional<double> turn_rate;
  std::optional<double> tilt_ratio;
  double standstill_speed = 1.0e-3;
  std::string frame = "paper";  ///< of the inputs and outputs: paper (SAE, z down) or ros (REP 103, z up)
};

/// What `contact_eval brush` was asked for.
struct BrushOptions
{
  std::string model = "steady";
  double sigma_x = 0.0, sigma_y = 0.0, phi = 0.0;
  double tilt_ratio = 1.0;
  std::optional<double> patch_radius, contact_modulus, sphere_radius;
  std::optional<double> distance;
  std::string pressure = "parabolic";
  std::string sliding_law = "coulomb";
  /// --covariance CXX CXY CXPHI CYY CYPHI CPHIPHI: the symmetric covariance of (sigma_x, sigma_y, phi), empty: none
  std::vector<double> covariance;
  std::string frame = "paper";  ///< of the slips, spin, forces and moment: paper (SAE, z down) or ros (REP 103, z up)
  BrushParameters parameters = accurate();

  /// The CLI favours accuracy over speed: resolution 64 (0.03 % of mu F_z for the steady model in
  /// partial sliding, 0.4 % for the transient one, on the Fig. 4 set).
  static BrushParameters accurate()
  {
    BrushParameters p;
    p.resolution = 64;
    return p;
  }
};

CLI::App* addSlipsCommand(CLI::App& app, SlipsOptions& options);
CLI::App* addBrushCommand(CLI::App& app, BrushOptions& options);

/// Run them; JSON on out. Throw std::invalid_argument with a message for the user on bad input.
void runSlipsCommand(const SlipsOptions& options, std::ostream& out);
void runBrushCommand(const BrushOptions& options, std::ostream& out);

}  // namespace sphere_contact_estimator::cli
