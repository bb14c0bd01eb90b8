// The odometry -> estimate path: any sequence of stamps and twists gives a finite estimate or none. The cost per
// input is bounded (resolution 4-8, at most 16 messages), so that CI runs 10^5 inputs in a few minutes.
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
  ContactEstimator e(s);
  for (int message = 0; message < 16 && in.more(); ++message)
  {
    EstimatorInput x;
    x.stamp = in.next();
    x.omega = Eigen::Vector3d(in.next(), in.next(), in.next());
    x.v_contact = Eigen::Vector3d(in.next(), in.next(), in.next());
    const ContactEstimateData* d = e.update(x);
    if (d && !(std::isfinite(d->brush.F_x) && std::isfinite(d->brush.M_z) && d->slip.allFinite() &&
               std::isfinite(d->rolling_resistance_force) && std::isfinite(d->turn_rate) && std::isfinite(d->heading)))
      std::abort();
  }
  return 0;
}
