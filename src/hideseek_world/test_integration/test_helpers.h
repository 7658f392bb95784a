// Helpers shared by the integration tests.
#pragma once

#include <ros/ros.h>
#include <xmlrpcpp/XmlRpc.h>

#include <functional>
#include <string>

namespace hideseek_test {

// Spins until pred() holds or the wall-clock timeout passes.
inline bool waitFor(const std::function<bool()>& pred, double seconds) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && ros::WallTime::now() < end) {
    ros::spinOnce();
    if (pred()) return true;
    ros::WallDuration(0.002).sleep();
  }
  return pred();
}

// The XML-RPC URI of a running node, empty when the master does not know it.
inline std::string nodeUri(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, false)) return "";
  return static_cast<std::string>(payload);
}

}  // namespace hideseek_test
