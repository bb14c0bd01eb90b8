#pragma once

// STL
#include <vector>

// Package
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_parameters.h"

namespace sphere_contact_estimator::test
{
/// The paper's steel cylinder on rubber (Sect. II, after eq. 29). Its quoted mu*_roll and v* follow
/// from eqs. 28-29 with g = 10 m/s^2.
inline CylinderParameters paperParameters(double g = 10.0)
{
  CylinderParameters p;
  p.R = 0.1;
  p.M = 250.0;
  p.m = 100.0;
  p.k = 1.0e7;
  p.gamma = 5.0e5;
  p.g = g;
  return p;
}

/// Overdamped parameter sets of other character than the paper's: heavy inertia, light damping,
/// a small stiff wheel, no surface mass.
inline std::vector<CylinderParameters> variedParameters()
{
  std::vector<CylinderParameters> out{ paperParameters() };
  CylinderParameters p = paperParameters(9.81);
  p.m = 2000.0;  // 4 m k = 8e10 < gamma^2 = 2.5e11: inertia matters, still overdamped
  out.push_back(p);
  p = paperParameters(9.81);
  p.R = 0.02;
  p.M = 5.0;
  p.k = 5.0e8;
  p.gamma = 2.0e6;
  p.m = 50.0;
  out.push_back(p);
  p = paperParameters(9.81);
  p.m = 0.0;
  out.push_back(p);
  return out;
}

}  // namespace sphere_contact_estimator::test
