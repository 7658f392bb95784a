#include <ros/ros.h>

#include <exception>

#include "hideseek_world/world_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "world");
  try {
    hideseek_world::WorldNode node{ros::NodeHandle(), ros::NodeHandle("~")};
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("world: %s", e.what());
    return 1;
  }
  return 0;
}
