#include <malloc.h>
#include <ros/ros.h>

#include <exception>

#include "hideseek_world/world_node.h"

int main(int argc, char** argv) {
  // Every lockstep step builds the hider's image batch (338 kB at 16 arenas) and roscpp serialises
  // a copy of it; glibc would map each such block anew and unmap it when freed (blocks of 128 kB
  // and more), or hand a freed heap top back to the kernel, so every step faulted its pages in
  // again. Kept in the heap instead: the world's CPU time per PPO update fell by about 10 %
  // (docs/performance.md). 32 MB is the largest threshold glibc accepts.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  ros::init(argc, argv, "world");
  // The node handles outlive the try block: an error thrown while the node starts is logged
  // while roscpp still runs, so roslaunch shows it instead of only "process has died".
  ros::NodeHandle nh, pnh("~");
  try {
    hideseek_world::WorldNode node{nh, pnh};
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("world: %s", e.what());
    return 1;
  }
  return 0;
}
