#include "sphere_contact_estimator/ros/odometry_estimator.h"

// STL
#include <cmath>
#include <cstdio>

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
  tf_max_age_ = config.tf_max_age;
}

void OdometryEstimator::reset()
{
  estimator_.reset();
  last_transform_stamp_ = ros::Time();
  n_sequences_ = 0;
}

double OdometryEstimator::secondsSinceEpoch(const ros::Time& stamp)
{
  if (!have_epoch_)
  {
    epoch_ = stamp;
    have_epoch_ = true;
  }
  return (stamp - epoch_).toSec();  // integer nanoseconds, then seconds (negative before the epoch)
}

std::uint32_t OdometryEstimator::sequenceGap(const std::string& publisher, std::uint32_t seq)
{
  ++messages_;
  int slot = -1;
  for (int i = 0; i < n_sequences_; ++i)
    if (sequences_[i].publisher == publisher)
      slot = i;
  std::uint32_t gap = 0;
  if (slot < 0)
  {
    // a new publisher: a free slot, else the one unseen longest (its string is reused: no allocation once sized)
    if (n_sequences_ < static_cast<int>(sequences_.size()))
      slot = n_sequences_++;
    else
    {
      slot = 0;
      for (int i = 1; i < n_sequences_; ++i)
        if (sequences_[i].used < sequences_[slot].used)
          slot = i;
    }
    sequences_[slot].publisher.assign(publisher);
  }
  else
  {
    // forward by more than one: lost messages. Backwards or equal (a restarted publisher, a looping bag, a source
    // that leaves seq at 0) or a jump past a million (not a loss a queue makes): none counted
    const std::uint32_t ahead = seq - sequences_[slot].last;  // modulo 2^32: wraps around correctly
    if (ahead > 1 && ahead < 1000000u)
      gap = ahead - 1;
  }
  sequences_[slot].last = seq;
  sequences_[slot].used = messages_;
  return gap;
}

// Transform at the stamp, else tf's latest; never waits. Counts which one it was.
bool OdometryEstimator::lookup(const tf2::BufferCore& tf, const std::string& target, const std::string& source,
                               const ros::Time& stamp, geometry_msgs::TransformStamped& out)
{
  if (target.empty() || source.empty())
    return false;
  // A frame tf has never seen (no tf in a bag, none published yet): said here, since canTransform composes its reason
  // in new strings at every call, even when none is asked for (test_ros_hot_path_allocations); _frameExists only looks
  // the name up.
  for (const std::string* frame : { &target, &source })
    if (!tf._frameExists(*frame))
    {
      char text[192];
      std::snprintf(text, sizeof(text), "frame '%s' is not in tf (looking up '%s' in '%s')", frame->c_str(),
                    source.c_str(), target.c_str());
      last_tf_error_.assign(text);  // into the string's capacity: no allocation once sized
      return false;
    }
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
      // the latest is used only close to the stamp: a transform that stopped long ago may have turned since (a
      // static chain has stamp 0 and holds at any time)
      const double age = out.header.stamp.isZero() ? 0.0 : std::abs((stamp - out.header.stamp).toSec());
      if (age > tf_max_age_)
      {
        ++counters_.tf_stale;
        tf_stale_ = true;
        char text[256];
        std::snprintf(text, sizeof(text), "latest transform from '%s' to '%s' is %.3g s from the stamp (tf_max_age %.3g s)",
                      source.c_str(), target.c_str(), age, tf_max_age_);
        last_tf_error_.assign(text);  // into the string's capacity: no allocation once sized
        return false;
      }
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

bool OdometryEstimator::toInput(const nav_msgs::Odometry& msg, const tf2::BufferCore& tf, EstimatorInput& in,
                                Eigen::Vector3d& centre, bool& have_centre)
{
  const std::string& ground = ground_frame_.empty() ? msg.header.frame_id : ground_frame_;
  Eigen::Quaterniond q;
  have_centre = false;
  if (!groundPose(msg, ground, tf, q, centre, have_centre))
  {
    ++counters_.no_orientation;
    return false;
  }
  // The twist is in child_frame_id (REP 105): into the gravity-aligned ground frame.
  in = EstimatorInput{};
  in.stamp = secondsSinceEpoch(msg.header.stamp);
  in.omega = q * vector(msg.twist.twist.angular);
  in.v_contact = q * vector(msg.twist.twist.linear);
  // the robot's yaw: the contact frame's heading until the sphere rolls (none when its x axis stands vertical)
  const Eigen::Vector3d body_x = q * Eigen::Vector3d::UnitX();
  if (body_x.head<2>().norm() > 1e-6)
    in.body_heading = std::atan2(body_x.y(), body_x.x());
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
  return true;
}

const EstimateOutputs* OdometryEstimator::process(const nav_msgs::Odometry& msg, const tf2::BufferCore& tf,
                                                  SkipReason& reason, const std::string& publisher)
{
  reason = SkipReason::None;
  // counted on arrival, also for a message skipped below: the gap is before it
  const std::uint32_t dropped = sequenceGap(publisher, msg.header.seq);
  counters_.dropped += dropped;
  tf_stale_ = false;
  const std::string& ground = ground_frame_.empty() ? msg.header.frame_id : ground_frame_;
  const std::uint64_t from_odometry = counters_.from_odometry;
  EstimatorInput in;
  Eigen::Vector3d centre;
  bool have_centre = false;
  if (!toInput(msg, tf, in, centre, have_centre))
  {
    reason = SkipReason::NoOrientation;
    return nullptr;
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
  if (e->flags & estimate_flags::kStampOutOfOrder)
    ++counters_.out_of_order;
  out_.data = e;

  ContactEstimate& m = out_.estimate;
  m.header.stamp = msg.header.stamp;
  m.header.frame_id = contact_frame_;
  toMessage(*e, m);
  if (counters_.from_odometry != from_odometry)
    m.flags |= ContactEstimate::FLAG_ORIENTATION_FROM_ODOMETRY;
  if (tf_stale_)
    m.flags |= ContactEstimate::FLAG_TF_STALE;
  m.messages_dropped = dropped;
  if (dropped > 0)
    m.flags |= ContactEstimate::FLAG_MESSAGES_DROPPED;
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
