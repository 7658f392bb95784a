#include <ros/ros.h>

#include <exception>

#include "hideseek_game/heap.h"
#include "hideseek_game/interrupt.h"
#include "hideseek_game/master_watch.h"
#include "hideseek_seeker/seeker_node.h"

int main(int argc, char** argv) {
  // Ctrl-C lets a training run write its checkpoint and say so (hideseek_game/interrupt.h).
  ros::init(argc, argv, "seeker", ros::init_options::NoSigintHandler);
  hideseek_game::catchInterrupt();
  // A learning seeker trains or infers batches of images, as the hider does (hideseek_game/heap.h).
  if (!hideseek_game::keepFreedMemoryInHeap())
    ROS_WARN("seeker: the allocator refused its settings; a learning seeker may train slower");
  // The node handles outlive the try block: an error thrown while the node starts is logged
  // while roscpp still runs, so roslaunch shows it instead of only "process has died".
  ros::NodeHandle nh, pnh("~");
  const hideseek_game::MasterWatch master_watch;  // says when the master dies or restarts
  try {
    hideseek_seeker::SeekerNode node{nh, pnh};
    hideseek_game::spinUntilInterrupted();
    node.stop();  // a training run not finished keeps its last update
    const int code = node.exitCode();
    ros::shutdown();
    return code;
  } catch (const std::exception& e) {
    ROS_FATAL("seeker: %s", e.what());
    return 1;
  }
  return 0;
}
