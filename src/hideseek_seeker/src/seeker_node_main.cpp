#include <ros/ros.h>

#include <exception>

#include "hideseek_seeker/seeker_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "seeker");
  try {
    hideseek_seeker::SeekerNode node{ros::NodeHandle(), ros::NodeHandle("~")};
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("seeker: %s", e.what());
    return 1;
  }
  return 0;
}
