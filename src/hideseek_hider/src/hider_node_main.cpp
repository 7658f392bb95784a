#include <ros/ros.h>

#include <exception>

#include "hideseek_hider/hider_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "hider");
  try {
    hideseek_hider::HiderNode node{ros::NodeHandle(), ros::NodeHandle("~")};
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("hider: %s", e.what());
    return 1;
  }
  return 0;
}
