// Wires the hider to the world: answers every observation batch with one action batch, from the
// random hider, a scripted evader, or a network (Learner: policy and train modes).
#pragma once

#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <ros/ros.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_game/game_options.h"
#include "hideseek_game/reply_cache.h"
#include "hideseek_game/wall_throttle.h"
#include "hideseek_hider/hider_policy.h"
#include "hideseek_hider/learner.h"

namespace hideseek_hider {

// The hider node's parameters: its mode and policy here, the network's (policy and train modes)
// in LearnerOptions, shared with the learning seeker.
struct HiderNodeOptions {
  enum class Mode { kRandom, kScripted, kLearner };
  Mode mode = Mode::kRandom;
  std::string policy = "random";  // random, scripted/NAME or a checkpoint path
  LearnerOptions learner;         // the policy and train modes (Mode::kLearner)
};
// Reads them once and validates them: a bad value throws before the node publishes, naming the
// parameter (or the file and field).
HiderNodeOptions loadHiderNodeOptions(const ros::NodeHandle& pnh);

class HiderNode {
 public:
  HiderNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // The process's exit status once spinning ends: non-zero when training stopped on an error.
  int exitCode() const { return learner_ ? learner_->exitCode() : 0; }
  // Once spinning ends: a training run not finished writes its checkpoint (Learner::stop).
  void stop() {
    if (learner_) learner_->stop();
  }

 private:
  void onObservations(const hideseek_msgs::ObservationBatch::ConstPtr& msg);

  ros::NodeHandle nh_;
  std::unique_ptr<HiderPolicy> policy_;  // random mode and the scripted evaders
  std::unique_ptr<Learner> learner_;     // policy and train modes
  hideseek_game::ReplyCache reply_;      // a batch the world re-sent gets the same answer again
  int image_height_ = 0;
  int image_width_ = 0;
  ros::Publisher actions_pub_;
  ros::Subscriber observations_sub_;
  uint64_t malformed_ = 0;
  hideseek_game::WallThrottle malformed_throttle_{2.0};  // warnings of malformed batches
};

}  // namespace hideseek_hider
