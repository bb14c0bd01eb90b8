#pragma once

// STL
#include <optional>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"

namespace sphere_contact_estimator
{
/// The largest rolling-friction coefficient of a model over speed, and where it occurs.
struct CylinderPeak
{
  double v = 0.0;        ///< speed of the maximum [m/s]
  double mu_roll = 0.0;  ///< maximum mu_roll [m]
};

/// Finds the global maximum of model.solve(v).mu_roll for 0 < v < v_c (v_c = infinity when m = 0:
/// then up to 1e4 k xi0 / gamma): a geometric scan locates it, Brent's method (Boost) refines it.
/// For the expansion model this reproduces eqs. 28-29. No peak without damping (gamma = 0).
std::optional<CylinderPeak> findPeak(const CylinderModel& model);

}  // namespace sphere_contact_estimator
