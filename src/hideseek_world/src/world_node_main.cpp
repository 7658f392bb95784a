#include <ros/ros.h>

#include <exception>

#include "hideseek_game/heap.h"
#include "hideseek_game/master_watch.h"
#include "hideseek_world/world_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "world");
  // Every step builds the hider's image batch and roscpp serialises a copy of it: reuse freed
  // memory instead of faulting it in again every step (hideseek_game/heap.h).
  if (!hideseek_game::keepFreedMemoryInHeap())
    ROS_WARN("world: the allocator refused its settings; stepping may be slower");
  // The node handles outlive the try block: an error thrown while the node starts is logged
  // while roscpp still runs, so roslaunch shows it instead of only "process has died".
  ros::NodeHandle nh, pnh("~");
  const hideseek_game::MasterWatch master_watch;  // says when the master dies or restarts
  try {
    hideseek_world::WorldNode node{nh, pnh};
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("world: %s", e.what());
    return 1;
  }
  return 0;
}
