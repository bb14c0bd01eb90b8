#include "cli/cylinder_command.h"

// STL
#include <cmath>
#include <memory>
#include <ostream>
#include <stdexcept>

// Package
#include "cli/json_output.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_peak.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_spread.h"

namespace sphere_contact_estimator::cli
{
CLI::App* addCylinderCommand(CLI::App& app, CylinderOptions& o)
{
  CLI::App* sub = app.add_subcommand(
      "cylinder", "Rolling resistance of a hard cylinder on a viscous plane (Poeschel, Schwager, Brilliantov). "
                  "Forces and torque are totals over --length; *_per_length fields are the paper's values.");
  CylinderParameters& p = o.parameters;
  sub->add_option("--radius", p.R, "cylinder radius R [m]")->required();
  sub->add_option("--mass-per-length", p.M, "cylinder mass per unit length M [kg/m]")->required();
  sub->add_option("--stiffness", p.k, "surface stiffness k [N/m^3]")->required();
  sub->add_option("--damping", p.gamma, "surface damping gamma [kg/(m^2 s)]")->required();
  sub->add_option("--surface-density", p.m, "surface mass density m [kg/m^2]")->required();
  sub->add_option("--g", p.g, "gravitational acceleration [m/s^2]")->capture_default_str();
  sub->add_option("--length", p.L, "effective length L for totals [m]")->capture_default_str();
  sub->add_option("--model", o.model, "exact | expansion | table")->capture_default_str();
  CLI::Option* speed = sub->add_option("--speed", o.speed, "rolling speed v [m/s]")->expected(1);
  CLI::Option* sweep = sub->add_option("--sweep", o.sweep, "VMIN VMAX N: N evenly spaced speeds [m/s]")->expected(3);
  CLI::Option* peak = sub->add_flag("--peak", o.peak, "print the maximum of mu_roll over v and where it is");
  speed->excludes(sweep)->excludes(peak);
  sweep->excludes(peak);
  sub->add_flag("--log", o.log_sweep, "space the --sweep speeds geometrically (VMIN > 0)");
  sub->add_option("--speed-std", o.speed_std,
                  "standard deviation of the speed [m/s]: adds F_R_std, F_R_per_length_std and mu_roll_std (unscented "
                  "transform through the model)");
  sub->add_option("--table-size", o.table_size, "number of tabulated speeds (--model table)")->capture_default_str();
  sub->add_option("--table-vmax", o.table_v_max, "upper end of the table [m/s]; 0 = up to the critical speed")
      ->capture_default_str();
  return sub;
}

namespace
{
std::vector<double> speeds(const CylinderOptions& o)
{
  if (o.speed.size() == 1)
    return o.speed;
  if (o.sweep.size() != 3)
    throw std::invalid_argument("give one of --speed v, --sweep VMIN VMAX N or --peak");
  const double lo = o.sweep[0], hi = o.sweep[1], n_real = o.sweep[2];
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo >= 0.0 && hi >= lo))
    throw std::invalid_argument("--sweep needs 0 <= VMIN <= VMAX, both finite [m/s]");
  if (!(n_real >= 1.0 && n_real <= 1.0e7 && n_real == std::floor(n_real)))
    throw std::invalid_argument("--sweep N must be a whole number between 1 and 1e7");
  if (o.log_sweep && !(lo > 0.0))
    throw std::invalid_argument("--log needs VMIN > 0");
  const auto n = static_cast<std::size_t>(n_real);
  std::vector<double> v(n, lo);
  for (std::size_t i = 1; i < n; ++i)
  {
    const double t = static_cast<double>(i) / static_cast<double>(n - 1);
    v[i] = o.log_sweep ? lo * std::pow(hi / lo, t) : lo + (hi - lo) * t;
  }
  if (n > 1)
    v.back() = hi;
  return v;
}
}  // namespace

void runCylinderCommand(const CylinderOptions& o, std::ostream& out)
{
  const auto kind = parseCylinderModelKind(o.model);
  if (!kind)
    throw std::invalid_argument("unknown --model '" + o.model + "': use exact, expansion or table");
  const std::vector<double> v = o.peak ? std::vector<double>{} : speeds(o);
  std::unique_ptr<CylinderModel> model;
  if (*kind == CylinderModelKind::Table)
    model = std::make_unique<CylinderTable>(o.parameters, o.table_size, o.table_v_max);
  else
    model = makeCylinderModel(*kind, o.parameters);

  // the state at v, with the spread of F_R and mu_roll when the speed is uncertain
  const auto state = [&](double x) {
    nlohmann::ordered_json j = toJson(model->solve(x), *model);
    if (o.speed_std)
    {
      const CylinderSpread s = cylinderSpread(*model, x, *o.speed_std);
      const double L = model->parameters().L;
      j["speed_std"] = *o.speed_std;
      j["F_R_std"] = number(L * std::sqrt(s.F_R_variance));
      j["F_R_per_length_std"] = number(std::sqrt(s.F_R_variance));
      j["mu_roll_std"] = number(std::sqrt(s.mu_roll_variance));
      j["spread_method"] = toString(s.method);
    }
    return j;
  };
  if (o.speed_std && !(std::isfinite(*o.speed_std) && *o.speed_std >= 0.0))
    throw std::invalid_argument("--speed-std must be finite and >= 0 [m/s]");
  if (o.peak)
  {
    const std::optional<CylinderPeak> found = findPeak(*model);
    if (!found)
      throw std::invalid_argument("no maximum of mu_roll: without damping (gamma = 0) there is no resistance peak");
    out << state(found->v).dump(2) << '\n';
    return;
  }
  if (o.speed.size() == 1)
  {
    out << state(v.front()).dump(2) << '\n';
    return;
  }
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (double x : v)
    all.push_back(state(x));
  out << all.dump(2) << '\n';
}

}  // namespace sphere_contact_estimator::cli
