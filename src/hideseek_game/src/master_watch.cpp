#include "hideseek_game/master_watch.h"

#include <ros/master.h>
#include <ros/ros.h>
#include <ros/this_node.h>

namespace hideseek_game {

namespace {

// Whether the master that answers now has this node registered.
bool masterKnowsThisNode() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = ros::this_node::getName();
  return ros::master::execute("lookupNode", args, result, payload, false);
}

}  // namespace

MasterWatch::MasterWatch(double period_s) : thread_([this, period_s] { run(period_s); }) {}

MasterWatch::~MasterWatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void MasterWatch::run(double period_s) {
  const std::string node = ros::this_node::getName();
  const std::string uri = ros::master::getURI();
  bool up = true;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::duration<double>(period_s), [this] { return stop_; })) {
    // The lock guards stop_ only: the master is asked without it.
    lock.unlock();
    const bool answers = ros::master::check();
    if (up && !answers) {
      ROS_ERROR(
          "%s: the ROS master at %s does not answer. This node goes on over the connections it has; "
          "nothing new can join until a master answers again.",
          node.c_str(), uri.c_str());
    } else if (!up && answers) {
      if (masterKnowsThisNode()) {
        ROS_WARN("%s: the ROS master at %s answers again and still knows this node.", node.c_str(), uri.c_str());
      } else {
        ROS_ERROR(
            "%s: a new ROS master answers at %s and does not know this node: its topics, services and "
            "parameters are not registered there, so a subscriber that starts now (rviz, rostopic, rosbag "
            "record) will not find them. The running game and any training go on over their existing "
            "connections. To register again, stop the launch and run the same command (training resumes "
            "from its last checkpoint).",
            node.c_str(), uri.c_str());
      }
    }
    up = answers;
    lock.lock();
  }
}

}  // namespace hideseek_game
