// The odometry -> estimate path: any sequence of stamps, twists and twist covariances gives a finite estimate or none,
// and a covariance that is finite where it is known. The cost per input is bounded (resolution 4-8, at most 16
// messages, a covariance on at most the first two), so that CI runs 10^5 inputs in a few minutes.
#include <cmath>
#include <cstdlib>

#include "fuzz_input.h"
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

using namespace sphere_contact_estimator;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  fuzz::Input in(data, size);
  EstimatorSettings s;
  s.brush_model = static_cast<BrushModelKind>(static_cast<int>(in.in(0.0, 4.99)));
  s.rolling_resistance_model = static_cast<CylinderModelKind>(static_cast<int>(in.in(0.0, 3.99)));
  s.tilt = in.in(0.0, 1.0) < 0.5;
  s.resolution = 4 + static_cast<int>(in.in(0.0, 4.99));
  s.sliding_law = in.in(0.0, 1.0) < 0.5 ? SlidingLaw::Coulomb : SlidingLaw::Rigid;
  ContactEstimator e(s);
  for (int message = 0; message < 16 && in.more(); ++message)
  {
    EstimatorInput x;
    x.stamp = in.next();
    x.omega = Eigen::Vector3d(in.next(), in.next(), in.next());
    x.v_contact = Eigen::Vector3d(in.next(), in.next(), in.next());
    if (message < 2 && in.in(0.0, 1.0) < 0.5)
    {
      // a covariance as a driver might send it: scaled, correlated, or raw doubles; checked as the ROS layer does
      TwistCovariance C = TwistCovariance::Zero();
      const double scale = std::pow(10.0, in.in(-20.0, 20.0));
      if (in.in(0.0, 1.0) < 0.5)
      {
        Eigen::Matrix<double, 6, 6> L = Eigen::Matrix<double, 6, 6>::Zero();
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j <= i; ++j)
            L(i, j) = in.in(-1.0, 1.0);
        C = scale * L * L.transpose();
      }
      else
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j < 6; ++j)
            C(i, j) = in.next();
      x.twist_covariance_status = checkTwistCovariance(C);
      if (x.twist_covariance_status == CovarianceStatus::Ok)
        x.twist_covariance = C;
    }
    const ContactEstimateData* d = e.update(x);
    if (d && d->covariance.brush_method != CovarianceMethod::None &&
        !(d->covariance.brush.allFinite() && std::isfinite(d->covariance.rolling_resistance_force_variance)))
      std::abort();
    if (d && !(std::isfinite(d->brush.F_x) && std::isfinite(d->brush.M_z) && d->slip.allFinite() &&
               std::isfinite(d->rolling_resistance_force) && std::isfinite(d->turn_rate) && std::isfinite(d->heading)))
      std::abort();
    if (d && !(d->motion_to_noise >= 0.0 || d->motion_to_noise == -1.0))  // a distance, infinity, or -1: never NaN
      std::abort();
  }
  return 0;
}
