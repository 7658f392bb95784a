#include <ros/ros.h>

#include <exception>

#include "hideseek_game/heap.h"
#include "hideseek_game/interrupt.h"
#include "hideseek_game/master_watch.h"
#include "hideseek_hider/hider_node.h"

int main(int argc, char** argv) {
  // Ctrl-C lets a training run write its checkpoint and say so (hideseek_game/interrupt.h).
  ros::init(argc, argv, "hider", ros::init_options::NoSigintHandler);
  hideseek_game::catchInterrupt();
  // The hider trains or infers batches of images: reuse freed memory instead of faulting it in
  // again every update (hideseek_game/heap.h).
  if (!hideseek_game::keepFreedMemoryInHeap())
    ROS_WARN("hider: the allocator refused its settings; training may be slower");
  // The node handles outlive the try block: an error thrown while the node starts is logged
  // while roscpp still runs, so roslaunch shows it instead of only "process has died".
  ros::NodeHandle nh, pnh("~");
  const hideseek_game::MasterWatch master_watch;  // says when the master dies or restarts
  try {
    hideseek_hider::HiderNode node{nh, pnh};
    hideseek_game::spinUntilInterrupted();
    node.stop();  // a training run not finished keeps its last update
    const int code = node.exitCode();
    ros::shutdown();
    return code;
  } catch (const std::exception& e) {
    ROS_FATAL("hider: %s", e.what());
    return 1;
  }
  return 0;
}
