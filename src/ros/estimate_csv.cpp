#include "sphere_contact_estimator/ros/estimate_csv.h"

// STL
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>

namespace sphere_contact_estimator
{
EstimateCsv::EstimateCsv(std::ostream& out, const std::vector<std::string>& preamble) : out_(out)
{
  for (const std::string& line : preamble)
    out_ << "# " << line << '\n';
  out_ << "stamp,t,rolling_speed,heading,turn_rate,sliding_velocity_x,sliding_velocity_y,slips_defined,slip_x,slip_y,"
          "spin,spin_tilt,spin_turn,tilt_ratio,patch_radius,load,friction,brush_model,brush_model_used,"
          "brush_resolution,brush_fx,brush_fy,brush_mz,sliding_fraction,max_utilisation,brush_error_estimate,brush_flags,"
          "brush_valid,"
          "brush_power,rr_model,rr_speed,rr_h,rr_xi_plus,rr_xi_minus,rr_force,rr_torque,rr_mu_roll,rr_regime,"
          "rr_flags,rr_valid,rr_power,valid,flags,compute_time,covariance_status,brush_covariance_method,brush_fx_std,"
          "brush_fy_std,brush_mz_std,rr_force_std,brush_accuracy_target,sliding_law,motion_to_noise,work,brush_covariance_age\n";
}

namespace
{
// A CSV row built in place: std::to_chars writes what printf's %.*g and %.*f would (the C locale), without printf's
// parsing and its arbitrary-precision digit loop, which were 40 % of bag_analyze's time.
class Row
{
public:
  void g(double x, int precision = 10)
  {
    sep();
    put(std::to_chars(p_, end(), x, std::chars_format::general, precision));
  }
  void fixed9(double x)
  {
    sep();
    put(std::to_chars(p_, end(), x, std::chars_format::fixed, 9));
  }
  // a ROS stamp to the nanosecond, from its integers (as a double, seconds since 1970 resolve only 2.4e-7 s)
  void stamp(const ros::Time& t)
  {
    sep();
    put(std::to_chars(p_, end(), t.sec));
    char digits[10];
    const std::to_chars_result r = std::to_chars(digits, digits + sizeof digits, t.nsec);
    const std::size_t n = static_cast<std::size_t>(r.ptr - digits);
    if (r.ec != std::errc() || n > 9 || end() - p_ < 10)
      return;
    *p_++ = '.';
    p_ = std::fill_n(p_, 9 - n, '0');
    p_ = std::copy(digits, r.ptr, p_);
  }
  void i(long long x)
  {
    sep();
    put(std::to_chars(p_, end(), x));
  }
  void empty() { sep(); }
  std::string_view text()
  {
    *p_++ = '\n';
    return { buffer_, static_cast<std::size_t>(p_ - buffer_) };
  }

private:
  char* end() { return buffer_ + sizeof(buffer_) - 2; }
  void sep()
  {
    if (!first_)
      *p_++ = ',';
    first_ = false;
  }
  void put(std::to_chars_result r)
  {
    if (r.ec == std::errc())  // always, with this buffer; else an empty field rather than garbage
      p_ = r.ptr;
  }
  char buffer_[2048];
  char* p_ = buffer_;
  bool first_ = true;
};
}  // namespace

void EstimateCsv::write(const ContactEstimate& e)
{
  if (!have_start_)
  {
    have_start_ = true;
    start_ = e.header.stamp;
  }
  const RollingResistance& r = e.rolling_resistance;
  // ten significant digits, more than any model's accuracy; the stamp to the nanosecond
  Row w;
  w.stamp(e.header.stamp);
  w.fixed9((e.header.stamp - start_).toSec());  // by the stamps' integers: the same in every recording of a stream
  for (double x : { e.rolling_speed, e.heading, e.turn_rate, e.sliding_velocity.x, e.sliding_velocity.y })
    w.g(x);
  w.i(e.slips_defined ? 1 : 0);
  for (double x : { e.slip.x, e.slip.y, e.spin, e.spin_tilt, e.spin_turn, e.tilt_ratio, e.patch_radius, e.load,
                    e.friction })
    w.g(x);
  w.i(e.brush_model);
  w.i(e.brush_model_used);
  w.i(e.brush_resolution);
  for (double x : { e.brush_force.x, e.brush_force.y, e.brush_moment, e.sliding_fraction, e.max_utilisation })
    w.g(x);
  w.g(e.brush_error_estimate, 4);
  w.i(e.brush_flags);
  w.i(e.brush_valid ? 1 : 0);
  w.g(e.brush_power);
  w.i(r.model);
  for (double x : { r.speed, r.h, r.xi_plus, r.xi_minus, r.force, r.torque, r.mu_roll })
    w.g(x);
  w.i(r.regime);
  w.i(r.flags);
  w.i(r.valid ? 1 : 0);
  w.g(e.rolling_resistance_power);
  w.i(e.valid ? 1 : 0);
  w.i(e.flags);
  w.g(e.compute_time, 4);
  // the standard deviations from the odometry's covariance; empty where unknown
  w.i(e.covariance_status);
  w.i(e.brush_covariance_method);
  const bool brush = e.brush_covariance_method != ContactEstimate::COVARIANCE_METHOD_NONE;
  for (int k : { 0, 4, 8 })
  {
    if (brush)
      w.g(std::sqrt(std::max(0.0, e.brush_covariance[k])), 6);
    else
      w.empty();
  }
  if (e.rolling_resistance_force_variance >= 0.0)
    w.g(std::sqrt(e.rolling_resistance_force_variance), 6);
  else
    w.empty();
  w.g(e.brush_accuracy_target, 6);
  w.i(e.sliding_law);  // as brush_model: the message's constants, coulomb (0) or rigid (1), so every column is numeric
  w.g(e.motion_to_noise, 4);
  w.i(e.work);
  w.g(e.brush_covariance_age, 4);
  out_ << w.text();
}

}  // namespace sphere_contact_estimator
