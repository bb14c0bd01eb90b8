#pragma once

// ROS
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

// Package
#include "sphere_contact_estimator/core/estimator/contact_estimator.h"

namespace sphere_contact_estimator
{
/// The contact drawn for RViz (topic contact_markers), in the contact frame (REP 103, z up), every length scaled to
/// the patch radius a so that the picture reads the same for any robot:
/// - the patch (a grey disc of radius a);
/// - the bristles, green where they adhere and red where they slide (the transient lattice or the steady field);
/// - their deflections u, lines from each bristle's root x to x + u (kDeflectionScale a for the largest deflection
///   the friction allows, mu q_z(0) / k, eq. 37), coloured as the bristles;
/// - the friction circle, the largest tangential force mu F_z, drawn with radius kFrictionCircleRadius a;
/// - the resultant brush force (F_x, F_y) on the sphere and the rolling-resistance force F_R L, arrows from the
///   patch centre on the friction circle's scale (an arrow that reaches the circle: full sliding);
/// - a label: |F_t| and its share of mu F_z, M_z, the sliding share, F_R L.
namespace contact_markers
{
enum Id : int
{
  kPatch = 0,
  kBristles,
  kDeflections,
  kFrictionCircle,
  kBrushForce,
  kRollingResistanceForce,
  kLabel,
  kCount
};
constexpr double kFrictionCircleRadius = 1.5;  ///< the friction circle's radius [a]
constexpr double kDeflectionScale = 0.25; ///< the largest deflection's drawn length [a]
constexpr int kCircleSegments = 64;
}  // namespace contact_markers

/// Fills `out` (kCount markers, ids as contact_markers::Id; its vectors keep their capacity from one call to the
/// next, so a steady stream does not allocate) with the drawing of estimate `e`, whose bristles `estimator` shows.
/// Markers without content (no brush model, no load, no bristles) are sent as DELETE. `lifetime` [s]: how long
/// RViz keeps them if no newer ones come.
void fillContactMarkers(const ContactEstimateData& e, const ContactEstimator& estimator, const std_msgs::Header& header,
                        double lifetime, visualization_msgs::MarkerArray& out);

}  // namespace sphere_contact_estimator
