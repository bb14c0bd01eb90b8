#include "sphere_contact_estimator/ros/estimate_csv.h"

// STL
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sphere_contact_estimator
{
EstimateCsv::EstimateCsv(std::ostream& out) : out_(out)
{
  out_ << "stamp,t,rolling_speed,heading,turn_rate,sliding_velocity_x,sliding_velocity_y,slips_defined,slip_x,slip_y,"
          "spin,spin_tilt,spin_turn,tilt_ratio,patch_radius,load,friction,brush_model,brush_model_used,"
          "brush_resolution,brush_fx,brush_fy,brush_mz,sliding_fraction,max_utilisation,brush_error_estimate,brush_flags,"
          "brush_valid,"
          "brush_power,rr_model,rr_speed,rr_h,rr_xi_plus,rr_xi_minus,rr_force,rr_torque,rr_mu_roll,rr_regime,"
          "rr_flags,rr_valid,rr_power,valid,flags,compute_time,covariance_status,brush_covariance_method,brush_fx_std,"
          "brush_fy_std,brush_mz_std,rr_force_std,brush_accuracy_target\n";
}

void EstimateCsv::write(const ContactEstimate& e)
{
  const double stamp = e.header.stamp.toSec();
  if (!have_start_)
  {
    have_start_ = true;
    start_ = stamp;
  }
  const RollingResistance& r = e.rolling_resistance;
  // %.10g: ten significant digits, more than any model's accuracy; the stamp to the nanosecond
  char line[2048];
  std::snprintf(line, sizeof(line),
                "%.9f,%.9f,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%d,"
                "%d,%.10g,%.10g,%.10g,%.10g,%.10g,%.4g,%u,%d,%.10g,%d,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%u,%d,"
                "%.10g,%d,%u,%.4g",
                stamp, stamp - start_, e.rolling_speed, e.heading, e.turn_rate, e.sliding_velocity.x,
                e.sliding_velocity.y, e.slips_defined ? 1 : 0, e.slip.x, e.slip.y, e.spin, e.spin_tilt, e.spin_turn,
                e.tilt_ratio, e.patch_radius, e.load, e.friction, e.brush_model, e.brush_model_used, e.brush_resolution,
                e.brush_force.x, e.brush_force.y, e.brush_moment, e.sliding_fraction, e.max_utilisation,
                e.brush_error_estimate, e.brush_flags,
                e.brush_valid ? 1 : 0, e.brush_power, r.model, r.speed, r.h, r.xi_plus, r.xi_minus, r.force, r.torque,
                r.mu_roll, r.regime, r.flags, r.valid ? 1 : 0, e.rolling_resistance_power, e.valid ? 1 : 0, e.flags,
                e.compute_time);
  out_ << line;
  // the standard deviations from the odometry's covariance; empty where unknown
  const bool brush = e.brush_covariance_method != ContactEstimate::COVARIANCE_METHOD_NONE;
  const bool rr = e.rolling_resistance_force_variance >= 0.0;
  char std_fields[256];
  std::snprintf(std_fields, sizeof(std_fields), ",%d,%d", e.covariance_status, e.brush_covariance_method);
  out_ << std_fields;
  for (int i : { 0, 4, 8 })
  {
    out_ << ',';
    if (brush)
    {
      std::snprintf(std_fields, sizeof(std_fields), "%.6g", std::sqrt(std::max(0.0, e.brush_covariance[i])));
      out_ << std_fields;
    }
  }
  out_ << ',';
  if (rr)
  {
    std::snprintf(std_fields, sizeof(std_fields), "%.6g", std::sqrt(e.rolling_resistance_force_variance));
    out_ << std_fields;
  }
  std::snprintf(std_fields, sizeof(std_fields), ",%.6g\n", e.brush_accuracy_target);
  out_ << std_fields;
}

}  // namespace sphere_contact_estimator
