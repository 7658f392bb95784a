// The main() of the nodes that may train, the hider and the seeker: a node of type Node, built as
// Node{nh, private_nh}, with stop() (a training run not finished keeps its last update) and
// exitCode() (the learner's verdict; 0 for a node that only acts).
#pragma once

#include <ros/ros.h>

#include <exception>
#include <string>

#include "hideseek_game/heap.h"
#include "hideseek_game/interrupt.h"
#include "hideseek_game/master_watch.h"

namespace hideseek_game {

template <typename Node>
int learnerNodeMain(int argc, char** argv, const std::string& name) {
  // Ctrl-C lets a training run write its checkpoint and say so (interrupt.h).
  ros::init(argc, argv, name, ros::init_options::NoSigintHandler);
  catchInterrupt();
  // A learner trains or infers batches of images: reuse freed memory instead of faulting it in
  // again every update (heap.h).
  if (!keepFreedMemoryInHeap()) {
    ROS_WARN("%s: the allocator refused its settings; its network may train and act slower", name.c_str());
  }
  // The node handles outlive the try block: an error thrown while the node starts is logged
  // while roscpp still runs, so roslaunch shows it instead of only "process has died".
  ros::NodeHandle nh, pnh("~");
  const MasterWatch master_watch;  // says when the master dies or restarts
  try {
    Node node{nh, pnh};
    spinUntilInterrupted();
    node.stop();
    const int code = node.exitCode();
    ros::shutdown();
    return code;
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", name.c_str(), e.what());
    return 1;
  }
}

}  // namespace hideseek_game
