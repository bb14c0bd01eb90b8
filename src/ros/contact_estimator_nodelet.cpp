// The contact estimator as a nodelet: sphere_contact_estimator/ContactEstimatorNodelet.
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "sphere_contact_estimator/ros/contact_estimator_ros.h"

namespace sphere_contact_estimator
{
class ContactEstimatorNodelet : public nodelet::Nodelet
{
  // The multi-threaded handles: in a manager with worker threads, a reconfigure (which may rebuild the
  // rolling-resistance table) and the diagnostics run beside the odometry instead of queueing behind it.
  // roscpp still runs one odometry callback at a time, in order; ContactEstimatorRos guards its state.
  void onInit() override
  {
    estimator_ = std::make_unique<ContactEstimatorRos>(getMTNodeHandle(), getMTPrivateNodeHandle());
  }

  std::unique_ptr<ContactEstimatorRos> estimator_;
};
}  // namespace sphere_contact_estimator

PLUGINLIB_EXPORT_CLASS(sphere_contact_estimator::ContactEstimatorNodelet, nodelet::Nodelet)
