// Wires a HiderPolicy to the world: answers every observation batch with one action batch.
#pragma once

#include <hideseek_msgs/ObservationBatch.h>
#include <ros/ros.h>

#include <memory>

#include "hideseek_hider/hider_policy.h"

namespace hideseek_hider {

class HiderNode {
 public:
  HiderNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

 private:
  void onObservations(const hideseek_msgs::ObservationBatch::ConstPtr& msg);

  ros::NodeHandle nh_;
  std::unique_ptr<HiderPolicy> policy_;
  int image_height_ = 0;
  int image_width_ = 0;
  ros::Publisher actions_pub_;
  ros::Subscriber observations_sub_;
  uint64_t malformed_ = 0;
};

}  // namespace hideseek_hider
