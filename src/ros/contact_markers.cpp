#include "sphere_contact_estimator/ros/contact_markers.h"

// STL
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sphere_contact_estimator
{
namespace
{
using visualization_msgs::Marker;

std_msgs::ColorRGBA rgba(float r, float g, float b, float a)
{
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

geometry_msgs::Point point(double x, double y, double z)
{
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

// an arrow from the patch centre to (x, y), or nothing when it has no length
void arrow(Marker& m, double x, double y, double z, double width)
{
  m.points.resize(2);
  m.points[0] = point(0.0, 0.0, z);
  m.points[1] = point(x, y, z);
  m.scale.x = width;        // shaft diameter
  m.scale.y = 2.0 * width;  // head diameter
  m.scale.z = 0.0;          // head length: RViz's default share of the arrow
  if (!(std::hypot(x, y) > 0.0))
    m.action = Marker::DELETE;
}

}  // namespace

void fillContactMarkers(const ContactEstimateData& e, const ContactEstimator& estimator, const std_msgs::Header& header,
                        double lifetime, visualization_msgs::MarkerArray& out)
{
  namespace cm = contact_markers;
  out.markers.resize(cm::kCount);
  for (int id = 0; id < cm::kCount; ++id)
  {
    Marker& m = out.markers[id];
    m.header = header;
    m.ns = "contact";
    m.id = id;
    m.action = Marker::ADD;
    m.pose.position = geometry_msgs::Point();
    m.pose.orientation = geometry_msgs::Quaternion();
    m.pose.orientation.w = 1.0;
    m.lifetime = ros::Duration(lifetime);
    m.points.clear();
    m.colors.clear();
    m.text.clear();
    m.frame_locked = true;  // moves with the contact frame as tf updates it, not left where the stamp put it
  }
  // drawn a little above the ground, each layer over the one before
  const double a = e.patch_radius > 0.0 ? e.patch_radius : 1e-3;
  const double z0 = 1e-3 * a;

  Marker& patch = out.markers[cm::kPatch];
  patch.type = Marker::CYLINDER;
  patch.scale.x = patch.scale.y = 2.0 * a;
  patch.scale.z = 0.01 * a;
  patch.color = rgba(0.6f, 0.6f, 0.6f, 0.5f);

  // the bristles and their deflections, scaled by the largest deflection the friction allows (eq. 37)
  Marker& bristles = out.markers[cm::kBristles];
  bristles.type = Marker::POINTS;
  bristles.scale.x = bristles.scale.y = 0.04 * a;
  Marker& deflections = out.markers[cm::kDeflections];
  deflections.type = Marker::LINE_LIST;
  deflections.scale.x = 0.01 * a;
  const BrushModel* brush = estimator.brushModel();
  double u_max = 0.0;
  if (brush)
  {
    const BrushParameters& p = brush->parameters();
    u_max = p.mu * p.qz(0.0) / p.k;
  }
  const double u_scale = u_max > 0.0 ? cm::kDeflectionScale * a / u_max : 0.0;
  const std_msgs::ColorRGBA adhering = rgba(0.1f, 0.8f, 0.1f, 1.0f), sliding = rgba(0.9f, 0.1f, 0.1f, 1.0f);
  estimator.visitBristles([&](const Eigen::Vector2d& x, const Eigen::Vector2d& u, bool slides) {
    const std_msgs::ColorRGBA& c = slides ? sliding : adhering;
    bristles.points.push_back(point(x.x(), x.y(), 2.0 * z0));
    bristles.colors.push_back(c);
    deflections.points.push_back(point(x.x(), x.y(), 3.0 * z0));
    deflections.points.push_back(point(x.x() + u_scale * u.x(), x.y() + u_scale * u.y(), 3.0 * z0));
    deflections.colors.push_back(c);
    deflections.colors.push_back(c);
  });
  if (bristles.points.empty())
    bristles.action = Marker::DELETE;
  if (deflections.points.empty() || u_scale == 0.0)
    deflections.action = Marker::DELETE;

  // the forces on the friction circle's scale: mu F_z (or F_z without a brush model) reaches the circle
  const double mu_F_z = e.friction * e.load;
  const double F_ref = mu_F_z > 0.0 ? mu_F_z : e.load;
  const double R_f = cm::kFrictionCircleRadius * a;
  const double per_newton = F_ref > 0.0 ? R_f / F_ref : 0.0;

  Marker& circle = out.markers[cm::kFrictionCircle];
  circle.type = Marker::LINE_STRIP;
  circle.scale.x = 0.04 * a;
  circle.color = rgba(1.0f, 0.85f, 0.1f, 1.0f);
  if (mu_F_z > 0.0)
    for (int i = 0; i <= cm::kCircleSegments; ++i)
    {
      const double t = 2.0 * M_PI * i / cm::kCircleSegments;
      circle.points.push_back(point(R_f * std::cos(t), R_f * std::sin(t), 4.0 * z0));
    }
  else
    circle.action = Marker::DELETE;

  Marker& force = out.markers[cm::kBrushForce];
  force.type = Marker::ARROW;
  force.color = rgba(0.2f, 0.4f, 1.0f, 1.0f);
  arrow(force, per_newton * e.brush.F_x, per_newton * e.brush.F_y, 5.0 * z0, 0.08 * a);

  Marker& resistance = out.markers[cm::kRollingResistanceForce];
  resistance.type = Marker::ARROW;
  resistance.color = rgba(1.0f, 0.5f, 0.0f, 1.0f);
  arrow(resistance, -per_newton * e.rolling_resistance_force, 0.0, 6.0 * z0, 0.06 * a);

  Marker& label = out.markers[cm::kLabel];
  label.type = Marker::TEXT_VIEW_FACING;
  label.pose.position = point(0.0, 0.0, 2.0 * R_f);  // above the patch whichever way the view looks
  label.scale.z = 0.3 * a;  // text height
  label.color = rgba(1.0f, 1.0f, 1.0f, 1.0f);
  const double F_t = std::hypot(e.brush.F_x, e.brush.F_y);
  char text[160];
  std::snprintf(text, sizeof text, "|F_t| %.3g N (%.0f %% of mu F_z)  M_z %.3g N m\nsliding %.0f %%  F_R %.3g N", F_t,
                mu_F_z > 0.0 ? 100.0 * F_t / mu_F_z : 0.0, e.brush.M_z, 100.0 * e.brush.sliding_fraction,
                e.rolling_resistance_force);
  label.text.reserve(sizeof text);  // so that the next text, longer or not, fits where this one is
  label.text.assign(text);
}

}  // namespace sphere_contact_estimator
