#include "cli/json_output.h"

// STL
#include <cmath>

namespace sphere_contact_estimator::cli
{
nlohmann::ordered_json number(double x)
{
  return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json toJson(const CylinderState& s, const CylinderModel& model)
{
  const double L = model.parameters().L;
  const CylinderScales& sc = model.scales();
  nlohmann::ordered_json j;
  j["v"] = s.v;
  j["model"] = toString(model.kind());
  j["regime"] = toString(s.regime);
  j["valid"] = s.valid();
  j["warnings"] = cylinder_flags::describe(s.flags);
  j["h"] = s.h;
  j["xi_plus"] = s.xi_plus;
  j["xi_minus"] = s.xi_minus;
  j["mu_roll"] = s.mu_roll;
  j["mu_roll_error"] = s.mu_roll_error;
  j["length"] = L;
  j["F_R"] = s.F_R * L;
  j["torque"] = s.torque * L;
  j["F_N"] = s.F_N * L;
  j["F_N_impact"] = s.F_N_impact * L;
  j["F_R_per_length"] = s.F_R;
  j["torque_per_length"] = s.torque;
  j["F_N_per_length"] = s.F_N;
  j["F_N_impact_per_length"] = s.F_N_impact;
  j["F_R_impact_per_length"] = s.F_R_impact;
  j["xi_plus_static"] = sc.xi0;
  j["h_static"] = sc.h0;
  j["lambda"] = sc.lambda;
  j["overdamped"] = sc.overdamped;
  j["v_critical"] = number(sc.v_critical);
  j["v_star"] = sc.v_star ? number(*sc.v_star) : nlohmann::ordered_json(nullptr);
  j["mu_star"] = sc.mu_star ? number(*sc.mu_star) : nlohmann::ordered_json(nullptr);
  return j;
}

}  // namespace sphere_contact_estimator::cli
