#include "cli/brush_commands.h"

// STL
#include <cmath>
#include <ostream>
#include <stdexcept>

// nlohmann
#include <nlohmann/json.hpp>

// Package
#include "cli/json_output.h"
#include "sphere_contact_estimator/core/brush/brush_auto.h"
#include "sphere_contact_estimator/core/brush/brush_model.h"
#include "sphere_contact_estimator/core/brush/brush_steady.h"
#include "sphere_contact_estimator/core/brush/brush_transient.h"
#include "sphere_contact_estimator/core/brush/contact_kinematics.h"
#include "sphere_contact_estimator/core/brush/force_covariance.h"
#include "sphere_contact_estimator/core/estimator/paper_frame.h"

namespace sphere_contact_estimator::cli
{
namespace
{
void requireFinite(double x, const char* flag)
{
  if (!std::isfinite(x))
    throw std::invalid_argument(std::string(flag) + " must be finite");
}

nlohmann::ordered_json vectorOrNull(const std::optional<Eigen::Vector2d>& v, bool ros)
{
  if (!v || !v->allFinite())
    return nullptr;
  const Eigen::Vector2d w = ros ? paper_frame::toRos(*v) : *v;
  return { w.x(), w.y() };
}

// --frame: the paper's (SAE: x forward, y right, z down), in which the models work, or REP 103's (x forward, y left,
// z up) as on the node's topics; the two differ by half a turn about x (paper_frame.h, docs/conventions.md)
void addFrameOption(CLI::App* sub, std::string& frame)
{
  sub->add_option("--frame", frame,
                  "frame of the inputs and outputs: paper (SAE: x forward, y right, z down; the papers' signs) or ros "
                  "(REP 103: x forward, y left, z up; the node's topics): a lateral component, a spin and a yaw moment "
                  "change sign between them")
      ->check(CLI::IsMember({ "paper", "ros" }))
      ->capture_default_str();
}

const char* frameName(bool ros) { return ros ? "ros (REP 103: x forward, y left, z up)" : "paper (SAE: x forward, y right, z down)"; }
}  // namespace

CLI::App* addSlipsCommand(CLI::App& app, SlipsOptions& o)
{
  CLI::App* sub = app.add_subcommand(
      "slips", "Slips and spins of a spherical wheel from its kinematics (Romano et al. eqs. 2, 12, 13, 36, 42), "
               "paper frame (SAE, z down) unless --frame ros.");
  sub->add_option("--omega", o.omega, "WX WY WZ: angular velocity of the sphere [rad/s]")->expected(3)->required();
  sub->add_option("--vc", o.vc, "VX VY: velocity of the contact-patch centre [m/s]")->expected(2)->required();
  sub->add_option("--rolling-radius", o.rolling_radius, "rolling radius R_r [m]")->required();
  CLI::Option* turn = sub->add_option("--turn-rate", o.turn_rate, "turning speed psi_dot of the contact frame [rad/s] (default 0)");
  CLI::Option* tilt = sub->add_option("--tilt-ratio", o.tilt_ratio, "tilt ratio chi_gamma = omega_gamma / omega_z");
  turn->excludes(tilt);
  sub->add_option("--standstill-speed", o.standstill_speed, "rolling speed below which slips are undefined [m/s]")
      ->capture_default_str();
  addFrameOption(sub, o.frame);
  return sub;
}

void runSlipsCommand(const SlipsOptions& o, std::ostream& out)
{
  for (double x : o.omega)
    requireFinite(x, "--omega");
  for (double x : o.vc)
    requireFinite(x, "--vc");
  if (!(std::isfinite(o.rolling_radius) && o.rolling_radius > 0.0))
    throw std::invalid_argument("--rolling-radius must be finite and > 0 [m]");
  if (!(std::isfinite(o.standstill_speed) && o.standstill_speed > 0.0))
    throw std::invalid_argument("--standstill-speed must be finite and > 0 [m/s]");
  // the models work in the paper frame; ros inputs are turned into it and the outputs back
  const bool ros = o.frame == "ros";
  const Eigen::Vector3d omega_in(o.omega[0], o.omega[1], o.omega[2]);
  const Eigen::Vector2d vc_in(o.vc[0], o.vc[1]);
  const Eigen::Vector3d omega = ros ? paper_frame::fromRos(omega_in) : omega_in;
  const Eigen::Vector2d vc = ros ? paper_frame::fromRos(vc_in) : vc_in;
  // (+ 0: a flipped zero prints as 0, not -0)
  const auto vec = [ros](const Eigen::Vector2d& v) -> Eigen::Vector2d { return (ros ? paper_frame::toRos(v) : v) + Eigen::Vector2d::Zero(); };
  const auto z = [ros](double x) { return (ros ? paper_frame::zToRos(x) : x) + 0.0; };
  ContactKinematics kin;
  if (o.tilt_ratio)
  {
    requireFinite(*o.tilt_ratio, "--tilt-ratio");
    kin = ContactKinematics::fromWheelWithTiltRatio(omega, vc, o.rolling_radius, *o.tilt_ratio);
  }
  else
  {
    requireFinite(o.turn_rate.value_or(0.0), "--turn-rate");
    const double turn = o.turn_rate.value_or(0.0);
    kin = ContactKinematics::fromWheel(omega, vc, o.rolling_radius, ros ? paper_frame::zFromRos(turn) : turn);
  }
  const Slips s = computeSlips(kin, o.standstill_speed);
  const auto slip = [&s](double x) { return s.defined ? number(x) : nlohmann::ordered_json(nullptr); };
  nlohmann::ordered_json j;
  j["frame"] = frameName(ros);
  j["V_r"] = s.V_r;
  j["V_r_x"] = vec(kin.V_r).x();
  j["V_r_y"] = vec(kin.V_r).y();
  j["V_s_x"] = vec(kin.V_s).x();
  j["V_s_y"] = vec(kin.V_s).y();
  j["sigma_x"] = slip(vec(s.sigma).x());
  j["sigma_y"] = slip(vec(s.sigma).y());
  j["phi"] = slip(z(s.phi));
  j["phi_gamma"] = slip(z(s.phi_gamma));
  j["phi_psi"] = slip(z(s.phi_psi));
  j["chi_gamma"] = s.chi_gamma ? number(*s.chi_gamma) : nlohmann::ordered_json(nullptr);
  j["chi_psi"] = s.chi_psi ? number(*s.chi_psi) : nlohmann::ordered_json(nullptr);
  j["epsilon_x"] = slip(s.epsilon.x());
  j["epsilon_y"] = slip(s.epsilon.y());
  j["omega_gamma"] = z(kin.omegaGamma());
  j["psi_dot"] = z(kin.psi_dot);
  j["tilting_centre"] = vectorOrNull(s.tilting_centre, ros);
  j["turning_centre"] = vectorOrNull(s.turning_centre, ros);
  j["valid"] = s.defined;
  nlohmann::ordered_json warnings = nlohmann::ordered_json::array();
  if (!s.defined)
    warnings.push_back("rolling speed V_r below the standstill speed: the slips of eq. 12 divide by V_r and are "
                       "undefined (null); only the transient brush model describes the contact");
  if (!s.chi_gamma)
    warnings.push_back("omega_z = 0: the tilt and turn ratios are undefined (null)");
  j["warnings"] = warnings;
  out << j.dump(2) << '\n';
}

CLI::App* addBrushCommand(CLI::App& app, BrushOptions& o)
{
  CLI::App* sub = app.add_subcommand(
      "brush", "Forces and moment of the brush model of a spherical wheel (Romano et al.) at constant slips, paper "
               "frame (epsilon = (0, 1)) unless --frame ros.");
  BrushParameters& p = o.parameters;
  sub->add_option("--model", o.model, "linear | steady | transient | auto")->capture_default_str();
  sub->add_option("--accuracy-target", p.accuracy_target,
                  "steady: the error bound it integrates to; auto: the cheapest model whose error estimate is below it "
                  "(a fraction of mu F_z, covering F_x, F_y and M_z / a)")
      ->capture_default_str();
  sub->add_option("--sigma-x", o.sigma_x, "longitudinal slip sigma_x")->required();
  sub->add_option("--sigma-y", o.sigma_y, "lateral slip sigma_y")->required();
  sub->add_option("--phi", o.phi, "spin phi [1/m]")->required();
  sub->add_option("--tilt-ratio", o.tilt_ratio, "tilt ratio chi_gamma: phi_gamma = chi_gamma phi (with --tilt)")
      ->capture_default_str();
  sub->add_flag("--tilt", p.tilt, "Sect. 4 kinematics: circular bristle paths about the tilting centre and the turn "
                                  "coupling chi_psi A_phi u (eq. 32)");
  CLI::Option* a = sub->add_option("--patch-radius", o.patch_radius, "contact-patch radius a [m]");
  CLI::Option* e = sub->add_option("--contact-modulus", o.contact_modulus,
                                   "effective modulus E* [Pa]: a from Hertz, (3 F_z R / (4 E*))^(1/3)");
  sub->add_option("--sphere-radius", o.sphere_radius, "sphere radius R for Hertz [m]");
  a->excludes(e);
  sub->add_option("--stiffness", p.k, "bristle stiffness k [N/m^3]")->required();
  sub->add_option("--load", p.F_z, "vertical load F_z [N]")->required();
  sub->add_option("--friction", p.mu, "friction coefficient mu")->required();
  sub->add_option("--resolution", p.resolution, "transient (and auto's transient): lattice spacings across the patch")
      ->capture_default_str();
  sub->add_option("--pressure", o.pressure, "parabolic | hertzian | uniform")->capture_default_str();
  sub->add_option("--sliding-law", o.sliding_law,
                  "coulomb: eq. (4b), a sliding bristle's stress opposes its tip's full sliding velocity | rigid: "
                  "Sect. 6's approximation along the rigid sliding velocity (the paper's Fig. 4)")
      ->capture_default_str();
  sub->add_option("--distance", o.distance,
                  "transient: distance travelled from undeformed at constant slips [m] (default 4a: steady state)");
  sub->add_option("--covariance", o.covariance,
                  "CXX CXY CXPHI CYY CYPHI CPHIPHI: the covariance of (sigma_x, sigma_y, phi) [-, -, 1/m; 1/m^2]; adds "
                  "the covariance of (F_x, F_y, M_z) and the method used")
      ->expected(6);
  addFrameOption(sub, o.frame);
  return sub;
}

void runBrushCommand(const BrushOptions& o, std::ostream& out)
{
  const auto kind = parseBrushModelKind(o.model);
  if (!kind)
    throw std::invalid_argument("unknown --model '" + o.model + "': use linear, steady, transient or auto");
  for (const auto& [x, flag] : { std::pair{ o.sigma_x, "--sigma-x" }, { o.sigma_y, "--sigma-y" }, { o.phi, "--phi" },
                                 { o.tilt_ratio, "--tilt-ratio" } })
    requireFinite(x, flag);
  for (double x : o.covariance)
    requireFinite(x, "--covariance");
  BrushParameters p = o.parameters;
  if (const auto pressure = parsePressureDistribution(o.pressure))
    p.pressure = *pressure;
  else
    throw std::invalid_argument("unknown --pressure '" + o.pressure + "': use parabolic, hertzian or uniform");
  if (const auto law = parseSlidingLaw(o.sliding_law))
    p.sliding_law = *law;
  else
    throw std::invalid_argument("unknown --sliding-law '" + o.sliding_law + "': use coulomb or rigid");
  if (o.patch_radius)
    p.a = *o.patch_radius;
  else if (o.contact_modulus)
  {
    if (!o.sphere_radius)
      throw std::invalid_argument("--contact-modulus needs --sphere-radius");
    p.a = contactRadiusHertz(p.F_z, *o.sphere_radius, *o.contact_modulus);
  }
  else
    throw std::invalid_argument("give --patch-radius, or --contact-modulus with --sphere-radius");
  p.validate();

  // the models work in the paper frame: a ros sigma_y and phi change sign on the way in, F_y and M_z on the way out
  const bool ros = o.frame == "ros";
  const double flip = ros ? -1.0 : 1.0;
  const Eigen::Vector2d sigma(o.sigma_x, flip * o.sigma_y);
  const double phi = flip * o.phi;
  const double phi_gamma = o.tilt_ratio * phi, phi_psi = phi - phi_gamma;
  const bool inner_disc = p.tilt && std::abs(phi_gamma) * p.a > 1.0;  // |R_gamma| < a
  BrushModelKind ran = *kind;
  std::vector<std::string> notes;
  if (ran == BrushModelKind::Steady && inner_disc)
  {
    ran = BrushModelKind::Transient;
    notes.emplace_back("no steady state for |R_gamma| < a (Fig. 2): fell back to the transient model");
  }
  const double distance = o.distance.value_or(inner_disc ? 40.0 * p.a : 4.0 * p.a);
  if (!(std::isfinite(distance) && distance >= 0.0 && distance <= 1e4 * p.a))
    throw std::invalid_argument("--distance must be finite, >= 0 and at most 1e4 patch radii [m]");

  const std::unique_ptr<BrushModel> model = makeBrushModel(ran, p);
  // Constant slips at a rolling speed of 1 m/s along +x: the state after a distance s is the state after
  // s seconds (eqs. 12-13 make it independent of the speed).
  const ContactKinematics kin = ContactKinematics::fromSlips(sigma, phi, o.tilt_ratio, 1.0);
  const bool advances = ran == BrushModelKind::Transient || ran == BrushModelKind::Auto;
  const BrushForces f = model->update(kin, advances ? distance : 0.0);

  nlohmann::ordered_json j;
  j["frame"] = frameName(ros);
  j["model"] = toString(ran);
  j["sliding_law"] = ran == BrushModelKind::Linear ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(toString(p.sliding_law));
  if (ran == BrushModelKind::Auto)
  {
    j["model_used"] = toString(model->lastModel());
    j["resolution_used"] = model->lastResolution();
  }
  j["Fx"] = number(f.F_x);
  j["Fy"] = number(flip * f.F_y + 0.0);
  j["Mz"] = number(flip * f.M_z + 0.0);
  j["sliding_fraction"] = number(f.sliding_fraction);
  j["max_utilisation"] = number(f.max_utilisation);
  j["error_estimate"] = number(f.error_estimate);
  j["valid"] = f.valid();
  nlohmann::ordered_json warnings = notes;
  for (const std::string& w : brush_flags::describe(f.flags))
    warnings.push_back(w);
  j["warnings"] = warnings;
  j["patch_radius"] = p.a;
  j["tilt"] = p.tilt;
  j["phi_gamma"] = flip * phi_gamma + 0.0;
  j["phi_psi"] = flip * phi_psi + 0.0;
  if (ran == BrushModelKind::Steady || ran == BrushModelKind::Auto)
    j["accuracy_target"] = p.accuracy_target;
  if (ran == BrushModelKind::Transient || ran == BrushModelKind::Auto)
    j["resolution"] = p.resolution;
  if (advances)
    j["distance"] = distance;
  if (!o.covariance.empty())
  {
    // the forces' uncertainty from the slips', by the model's own propagation (force_covariance.h)
    Eigen::Matrix3d S;
    S << o.covariance[0], o.covariance[1], o.covariance[2],  //
        o.covariance[1], o.covariance[3], o.covariance[4],  //
        o.covariance[2], o.covariance[4], o.covariance[5];
    if (const char* problem = covarianceProblem<3>(S))
      throw std::invalid_argument(std::string("--covariance is ") + problem + ": give the upper triangle of a covariance "
                                  "of (sigma_x, sigma_y, phi), CXX CXY CXPHI CYY CYPHI CPHIPHI");
    // (sigma_y, phi) and (F_y, M_z) change sign together between the frames: D S D with D = diag(1, -1, -1)
    const Eigen::Matrix3d D = Eigen::Vector3d(1.0, flip, flip).asDiagonal();
    const ForceCovariance c = propagateSlipCovariance(ran == BrushModelKind::Linear ? BrushModelKind::Linear : BrushModelKind::Steady,
                                                      p, sigma, phi, o.tilt_ratio, Eigen::Matrix3d(D * S * D));
    if (c.defined)
    {
      nlohmann::ordered_json flat = nlohmann::ordered_json::array();
      const Eigen::Matrix3d C = D * c.covariance * D;
      for (int i = 0; i < 9; ++i)
        flat.push_back(number(C(i / 3, i % 3)));
      j["covariance"] = flat;
      j["std"] = { number(std::sqrt(C(0, 0))), number(std::sqrt(C(1, 1))), number(std::sqrt(C(2, 2))) };
    }
    else
      j["covariance"] = nullptr;
    j["covariance_method"] = toString(c.method);
    j["covariance_smooth"] = c.smooth;
    if (!c.smooth)
      j["warnings"].push_back("the forces kink or jump within the inputs' spread (the onset of sliding, the friction "
                              "limit): the covariance is only approximate");
    if (!c.defined)
      j["warnings"].push_back("no covariance: the steady state does not exist over the inputs' spread (|R_gamma| < a)");
  }
  out << j.dump(2) << '\n';
}

}  // namespace sphere_contact_estimator::cli
