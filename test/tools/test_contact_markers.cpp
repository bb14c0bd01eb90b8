// The contact's drawing for RViz (contact_markers.h): what each marker shows against the estimate it draws.

// STL
#include <cmath>
#include <vector>

// Gtest
#include <gtest/gtest.h>

// Package
#include "sphere_contact_estimator/ros/contact_markers.h"

namespace sphere_contact_estimator
{
namespace
{
namespace cm = contact_markers;
using visualization_msgs::Marker;

EstimatorSettings settings(BrushModelKind brush, SlidingLaw law = SlidingLaw::Coulomb)
{
  EstimatorSettings s;
  s.brush_model = brush;
  s.sliding_law = law;
  s.rolling_resistance_model = CylinderModelKind::Exact;
  s.standstill_speed = 0.01;
  s.turn_rate_time_constant = 0.0;
  return s;
}

// rolling along x at 1 m/s with the contact centre sliding by (ds_x, ds_y) [m/s], ROS frame, spinning at omega_z
EstimatorInput rolling(double stamp, double ds_x, double ds_y, double omega_z = 0.0)
{
  EstimatorInput in;
  in.stamp = stamp;
  const double v = 1.0, R = 0.1;
  in.omega = Eigen::Vector3d(0.0, v / R, omega_z);
  in.v_contact = Eigen::Vector3d(v + ds_x, ds_y, 0.0);
  return in;
}

std_msgs::Header header()
{
  std_msgs::Header h;
  h.frame_id = "contact_patch";
  h.stamp = ros::Time(12.5);
  return h;
}

double length(const geometry_msgs::Point& p, const geometry_msgs::Point& q)
{
  return std::hypot(q.x - p.x, q.y - p.y);
}

TEST(ContactMarkers, DrawTheEstimateToThePatchScale)
{
  // both sliding laws, with a little spin (where they differ)
  for (BrushModelKind model : { BrushModelKind::Steady, BrushModelKind::Transient })
  {
    for (SlidingLaw law : { SlidingLaw::Coulomb, SlidingLaw::Rigid })
    {
      SCOPED_TRACE(std::string(toString(model)) + ", " + toString(law));
      ContactEstimator estimator(settings(model, law));
      const ContactEstimateData* e = nullptr;
      for (int i = 0; i < 50; ++i)
        e = estimator.update(rolling(0.01 * i, 0.01, 0.02, 2.0));
      ASSERT_TRUE(e);
      visualization_msgs::MarkerArray out;
      fillContactMarkers(*e, estimator, header(), 0.5, out);
      ASSERT_EQ(out.markers.size(), static_cast<std::size_t>(cm::kCount));
      const double a = e->patch_radius, R_f = cm::kFrictionCircleRadius * a, mu_F_z = e->friction * e->load;
      ASSERT_GT(mu_F_z, 0.0);
      for (int id = 0; id < cm::kCount; ++id)
      {
        EXPECT_EQ(out.markers[id].id, id);
        EXPECT_EQ(out.markers[id].header.frame_id, "contact_patch");
        EXPECT_EQ(out.markers[id].action, Marker::ADD) << "marker " << id;
      }
      EXPECT_DOUBLE_EQ(out.markers[cm::kPatch].scale.x, 2.0 * a);

      // one deflection line per bristle, from its root, no longer than the largest deflection the friction allows
      const Marker& bristles = out.markers[cm::kBristles];
      const Marker& lines = out.markers[cm::kDeflections];
      ASSERT_GT(bristles.points.size(), 100u);
      EXPECT_EQ(bristles.colors.size(), bristles.points.size());
      ASSERT_EQ(lines.points.size(), 2 * bristles.points.size());
      EXPECT_EQ(lines.colors.size(), lines.points.size());
      // each line is the bristle's deflection u (as the estimator shows it), kDeflectionScale a for mu q_z(0) / k
      std::vector<Eigen::Vector2d> x, u;
      std::vector<bool> slides;
      estimator.visitBristles([&](const Eigen::Vector2d& xi, const Eigen::Vector2d& ui, bool si) {
        x.push_back(xi);
        u.push_back(ui);
        slides.push_back(si);
      });
      ASSERT_EQ(x.size(), bristles.points.size());
      const BrushParameters& p = estimator.brushModel()->parameters();
      const double per_metre = cm::kDeflectionScale * a / (p.mu * p.qz(0.0) / p.k);
      double longest = 0.0;
      int sliding = 0;
      for (std::size_t i = 0; i < x.size(); ++i)
      {
        EXPECT_DOUBLE_EQ(bristles.points[i].x, x[i].x());
        EXPECT_DOUBLE_EQ(bristles.points[i].y, x[i].y());
        EXPECT_DOUBLE_EQ(lines.points[2 * i].x, x[i].x());
        EXPECT_DOUBLE_EQ(lines.points[2 * i].y, x[i].y());
        EXPECT_NEAR(lines.points[2 * i + 1].x - x[i].x(), per_metre * u[i].x(), 1e-12 * a);
        EXPECT_NEAR(lines.points[2 * i + 1].y - x[i].y(), per_metre * u[i].y(), 1e-12 * a);
        EXPECT_EQ(bristles.colors[i].r > 0.5f, slides[i]);
        longest = std::max(longest, length(lines.points[2 * i], lines.points[2 * i + 1]));
        sliding += slides[i];
      }
      EXPECT_LE(longest, cm::kDeflectionScale * a * (1.0 + 1e-9));  // no bristle deflects past the friction bound
      EXPECT_GT(longest, 0.0);
      EXPECT_GT(sliding, 0);
      EXPECT_LT(sliding, static_cast<int>(bristles.points.size()));

      // the friction circle has radius kFrictionCircle a, closed
      const Marker& circle = out.markers[cm::kFrictionCircle];
      ASSERT_EQ(circle.points.size(), static_cast<std::size_t>(cm::kCircleSegments + 1));
      for (const auto& p : circle.points)
        EXPECT_NEAR(std::hypot(p.x, p.y), R_f, 1e-12 * R_f);
      EXPECT_NEAR(length(circle.points.front(), circle.points.back()), 0.0, 1e-12 * R_f);

      // the brush force on that scale: the same direction, |F_t| / (mu F_z) of the radius
      const Marker& force = out.markers[cm::kBrushForce];
      ASSERT_EQ(force.points.size(), 2u);
      EXPECT_NEAR(force.points[1].x, e->brush.F_x / mu_F_z * R_f, 1e-12 * R_f);
      EXPECT_NEAR(force.points[1].y, e->brush.F_y / mu_F_z * R_f, 1e-12 * R_f);
      EXPECT_LT(force.points[1].x, 0.0);  // the ground pushes against the sliding
      EXPECT_LT(force.points[1].y, 0.0);
      const Marker& resistance = out.markers[cm::kRollingResistanceForce];
      EXPECT_NEAR(resistance.points[1].x, -e->rolling_resistance_force / mu_F_z * R_f, 1e-12 * R_f);
      EXPECT_NE(out.markers[cm::kLabel].text.find("sliding"), std::string::npos);
    }
  }
}

TEST(ContactMarkers, FullSlidingReachesTheFrictionCircle)
{
  ContactEstimator estimator(settings(BrushModelKind::Steady));
  const ContactEstimateData* e = estimator.update(rolling(0.0, 0.8, -0.6));  // 100 % slip: the whole patch slides
  ASSERT_TRUE(e);
  visualization_msgs::MarkerArray out;
  fillContactMarkers(*e, estimator, header(), 0.5, out);
  const Marker& force = out.markers[cm::kBrushForce];
  const double R_f = cm::kFrictionCircleRadius * e->patch_radius;
  EXPECT_NEAR(std::hypot(force.points[1].x, force.points[1].y), R_f, 0.01 * R_f);
  for (const auto& c : out.markers[cm::kBristles].colors)
    EXPECT_GT(c.r, 0.5f);  // every bristle slides
}

TEST(ContactMarkers, WithoutBristlesTheirMarkersAreDeleted)
{
  // the linear model has no bristle field: nothing stale may stay on the screen
  ContactEstimator estimator(settings(BrushModelKind::Linear));
  const ContactEstimateData* e = estimator.update(rolling(0.0, 0.01, 0.02));
  ASSERT_TRUE(e);
  visualization_msgs::MarkerArray out;
  fillContactMarkers(*e, estimator, header(), 0.5, out);
  EXPECT_EQ(out.markers[cm::kBristles].action, Marker::DELETE);
  EXPECT_EQ(out.markers[cm::kDeflections].action, Marker::DELETE);
  EXPECT_EQ(out.markers[cm::kBrushForce].action, Marker::ADD);
  EXPECT_EQ(out.markers[cm::kFrictionCircle].action, Marker::ADD);
}

TEST(ContactMarkers, ASteadyStreamReusesTheBuffers)
{
  ContactEstimator estimator(settings(BrushModelKind::Transient));
  visualization_msgs::MarkerArray out;
  const ContactEstimateData* e = estimator.update(rolling(0.0, 0.01, 0.02));
  fillContactMarkers(*e, estimator, header(), 0.5, out);
  const void* points = out.markers[cm::kDeflections].points.data();
  const void* text = out.markers[cm::kLabel].text.data();
  for (int i = 1; i < 20; ++i)
  {
    e = estimator.update(rolling(0.01 * i, 0.01, 0.02));
    fillContactMarkers(*e, estimator, header(), 0.5, out);
    EXPECT_EQ(out.markers[cm::kDeflections].points.data(), points);
    EXPECT_EQ(out.markers[cm::kLabel].text.data(), text);
  }
}

}  // namespace
}  // namespace sphere_contact_estimator
