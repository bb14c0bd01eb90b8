// contact_estimator_node: the contact estimator as a stand-alone node.
#include <ros/ros.h>

#include "sphere_contact_estimator/ros/contact_estimator_ros.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "contact_estimator");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  sphere_contact_estimator::ContactEstimatorRos estimator(nh, pnh);
  ros::spin();
  return 0;
}
