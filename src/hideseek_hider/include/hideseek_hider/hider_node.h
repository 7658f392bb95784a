// Wires a HiderPolicy to the world: answers every observation batch with one action batch.
#pragma once

#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <ros/ros.h>

#include <memory>
#include <vector>

#include "hideseek_hider/hider_policy.h"
#include "hideseek_hider/training_run.h"

namespace hideseek_hider {

class HiderNode {
 public:
  HiderNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

 private:
  void onObservations(const hideseek_msgs::ObservationBatch::ConstPtr& msg);

  void startTraining(const ros::NodeHandle& pnh, const std::string& variant, torch::Device device,
                     const PrecisionChoice& precision, NetworkKind network);

  ros::NodeHandle nh_;
  std::unique_ptr<HiderPolicy> policy_;  // random and policy modes
  std::unique_ptr<TrainingRun> training_;  // train mode
  ros::Time last_stamp_;                   // a batch the world re-sent gets the same answer again
  hideseek_msgs::ActionBatch last_answer_;
  std::vector<uint32_t> last_seeds_;       // seeds of the batch last_answer_ answers
  int image_height_ = 0;
  int image_width_ = 0;
  ros::Publisher actions_pub_;
  ros::Subscriber observations_sub_;
  uint64_t malformed_ = 0;
};

}  // namespace hideseek_hider
