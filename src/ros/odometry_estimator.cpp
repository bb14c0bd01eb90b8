#include "sphere_contact_estimator/ros/odometry_estimator.h"

// STL
#include <cmath>

// ROS
#include <tf2/exceptions.h>
#include <tf2_eigen/tf2_eigen.h>

// Package
#include "sphere_contact_estimator/ros/config_settings.h"
#include "sphere_contact_estimator/ros/estimate_message.h"

namespace sphere_contact_estimator
{
namespace
{
bool validQuaternion(const geometry_msgs::Quaternion& q, Eigen::Quaterniond& out)
{
  out = Eigen::Quaterniond(q.w, q.x, q.y, q.z);
  const double n = out.norm();
  if (!(std::isfinite(n) && n > 0.5 && n < 1.5))  // unset (all zero) or garbage
    return false;
  out.normalize();
  return true;
}

Eigen::Vector3d vector(const geometry_msgs::Vector3& v)
{
  return { v.x, v.y, v.z };
}
}  // namespace

OdometryEstimator::OdometryEstimator(const ContactEstimatorConfig& config) : estimator_(settingsFromConfig(config))
{
  configureFrames(config);
}

void OdometryEstimator::configure(const ContactEstimatorConfig& config)
{
  estimator_.configure(settingsFromConfig(config));  // throws, changing nothing, when invalid
  configureFrames(config);
}

void OdometryEstimator::configureFrames(const ContactEstimatorConfig& config)
{
  ground_frame_ = config.ground_frame;
  contact_frame_ = config.contact_frame.empty() ? std::string("contact_patch") : config.contact_frame;
  publish_tf_ = config.publish_tf;
}

void OdometryEstimator::reset()
{
  estimator_.reset();
  last_transform_stamp_ = ros::Time();
}

// Transform at the stamp, else tf's latest; never waits. Counts which one it was.
bool OdometryEstimator::lookup(const tf2::BufferCore& tf, const std::string& target, const std::string& source,
                               const ros::Time& stamp, geometry_msgs::TransformStamped& out)
{
  if (target.empty() || source.empty())
    return false;
  try
  {
    if (tf.canTransform(target, source, stamp))
    {
      out = tf.lookupTransform(target, source, stamp);
      ++counters_.tf_at_stamp;
      return true;
    }
    last_tf_error_.clear();  // canTransform appends its reason
    if (tf.canTransform(target, source, ros::Time(0), &last_tf_error_))
    {
      out = tf.lookupTransform(target, source, ros::Time(0));
      ++counters_.tf_latest;
      return true;
    }
  }
  catch (const tf2::TransformException& e)
  {
    last_tf_error_ = e.what();
  }
  return false;
}

bool OdometryEstimator::groundPose(const nav_msgs::Odometry& msg, const std::string& ground, const tf2::BufferCore& tf,
                                   Eigen::Quaterniond& rotation, Eigen::Vector3d& centre, bool& have_centre)
{
  geometry_msgs::TransformStamped t;
  const ros::Time& stamp = msg.header.stamp;
  // tf from the twist's frame (the sphere's, whose origin is its centre)
  if (lookup(tf, ground, msg.child_frame_id, stamp, t))
  {
    rotation = tf2::transformToEigen(t).rotation();
    centre = vector(t.transform.translation);
    have_centre = true;
    return true;
  }
  // the odometry's own pose, moved into the ground frame by tf when that is another frame
  Eigen::Quaterniond q;
  if (!validQuaternion(msg.pose.pose.orientation, q))
    return false;
  const Eigen::Vector3d position(msg.pose.pose.position.x, msg.pose.pose.position.y, msg.pose.pose.position.z);
  if (ground == msg.header.frame_id)
  {
    rotation = q;
    centre = position;
    have_centre = position.allFinite();
    ++counters_.from_odometry;
    return true;
  }
  if (lookup(tf, ground, msg.header.frame_id, stamp, t))
  {
    const Eigen::Isometry3d T = tf2::transformToEigen(t);
    rotation = Eigen::Quaterniond(T.rotation()) * q;
    centre = T * position;
    have_centre = centre.allFinite();
    ++counters_.from_odometry;
    return true;
  }
  return false;
}

const EstimateOutputs* OdometryEstimator::process(const nav_msgs::Odometry& msg, const tf2::BufferCore& tf,
                                                  SkipReason& reason)
{
  reason = SkipReason::None;
  const std::string& ground = ground_frame_.empty() ? msg.header.frame_id : ground_frame_;
  Eigen::Quaterniond q;
  Eigen::Vector3d centre;
  bool have_centre = false;
  const std::uint64_t from_odometry = counters_.from_odometry;
  if (!groundPose(msg, ground, tf, q, centre, have_centre))
  {
    ++counters_.no_orientation;
    reason = SkipReason::NoOrientation;
    return nullptr;
  }
  // The twist is in child_frame_id (REP 105): into the gravity-aligned ground frame.
  EstimatorInput in;
  in.stamp = msg.header.stamp.toSec();
  in.omega = q * vector(msg.twist.twist.angular);
  in.v_contact = q * vector(msg.twist.twist.linear);
  // its covariance (row-major, linear x, y, z, angular x, y, z) the same way, checked first; linear z is never used
  // and often marked unknown or huge by planar odometry, so it counts as exact (its row and column dropped)
  TwistCovariance C = Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(msg.twist.covariance.data());
  const char* problem = nullptr;
  in.twist_covariance_status = checkTwistCovariance(C, &problem);
  if (in.twist_covariance_status == CovarianceStatus::Ok)
  {
    C.row(2).setZero();
    C.col(2).setZero();
    in.twist_covariance = rotateTwistCovariance(C, q.toRotationMatrix());
  }
  else
  {
    ++counters_.bad_covariance;
    last_covariance_problem_ = problem;
  }
  const ContactEstimateData* e = estimator_.update(in);
  if (!e)
  {
    ++counters_.rejected;
    reason = SkipReason::RejectedInput;
    return nullptr;
  }
  if (e->flags & estimate_flags::kTimeJumpReset)
  {
    ++counters_.time_jumps;
    last_transform_stamp_ = ros::Time();
  }
  out_.data = e;

  ContactEstimate& m = out_.estimate;
  m.header.stamp = msg.header.stamp;
  m.header.frame_id = contact_frame_;
  toMessage(*e, m);
  if (counters_.from_odometry != from_odometry)
    m.flags |= ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY;
  out_.brush_wrench.header = m.header;
  brushWrench(*e, out_.brush_wrench);
  out_.rolling_resistance_wrench.header = m.header;
  rollingResistanceWrench(*e, out_.rolling_resistance_wrench);

  // The contact point, R_r below the centre along gravity, x along the rolling direction. One per stamp:
  // re-sending an unchanged stamp is what makes tf print TF_REPEATED_DATA.
  out_.has_transform = publish_tf_ && have_centre && msg.header.stamp != last_transform_stamp_;
  if (out_.has_transform)
  {
    geometry_msgs::TransformStamped& t = out_.contact_transform;
    t.header.stamp = msg.header.stamp;
    t.header.frame_id = ground;
    t.child_frame_id = contact_frame_;
    t.transform.translation.x = centre.x();
    t.transform.translation.y = centre.y();
    t.transform.translation.z = centre.z() - estimator_.settings().rolling_radius;
    t.transform.rotation.x = t.transform.rotation.y = 0.0;
    t.transform.rotation.z = std::sin(0.5 * e->heading);
    t.transform.rotation.w = std::cos(0.5 * e->heading);
    last_transform_stamp_ = msg.header.stamp;
  }
  return &out_;
}

}  // namespace sphere_contact_estimator
