// Wires the seeker to the world: the scripted SeekerPolicy (one per arena, fed only the seeker's
// perception), the uniformly random seeker, or a network that sees only the seeker's own camera
// (the hider's Learner: policy and train modes, role seeker).
#pragma once

#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/SeekerObservationBatch.h>
#include <ros/ros.h>

#include <memory>
#include <string>
#include <vector>

#include "hideseek_game/reply_cache.h"
#include "hideseek_game/wall_throttle.h"
#include "hideseek_hider/learner.h"
#include "hideseek_seeker/seeker_policy.h"

namespace hideseek_seeker {

// Builds the core's layout from the map the world sent.
Layout toLayout(const hideseek_msgs::ArenaMap& map);
// The perception of arena i: the hider's position only while the seeker sees it.
SeekerPerception toPerception(const hideseek_msgs::SeekerObservationBatch& batch, size_t i);

// The seeker node's parameters, read once and validated: a bad value throws before the node
// publishes, naming the parameter.
struct SeekerNodeOptions {
  enum class Mode { kScripted, kRandom, kLearner };
  Mode mode = Mode::kScripted;
  hideseek_game::VariantConfig variant;
  double grid_resolution = 0.1;            // scripted mode: the planner's grid (m)
  hideseek_hider::LearnerOptions learner;  // policy and train modes: role seeker, the learned seeker's game
};
SeekerNodeOptions loadSeekerNodeOptions(const ros::NodeHandle& pnh);

class SeekerNode {
 public:
  SeekerNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // The process's exit status once spinning ends: non-zero when training stopped on an error.
  int exitCode() const { return learner_ ? learner_->exitCode() : 0; }
  // Once spinning ends: a learning seeker's training run not finished writes its checkpoint.
  void stop() {
    if (learner_) learner_->stop();
  }

 private:
  void onObservations(const hideseek_msgs::SeekerObservationBatch::ConstPtr& msg);
  // Scripted mode: arena 0's plan on seeker/plan (nav_msgs/Path: the seeker's pose, then the path
  // points it has not dropped) and the point it heads for on seeker/target (geometry_msgs/
  // PointStamped), in the world's frame, latched, at most 30 times a wall second.
  void publishPlan(const std_msgs::Header& header, const AgentState& seeker, const SeekerPolicy& policy);
  // The actions of the random seeker or the network; empty once training ended.
  std::vector<uint8_t> learnedOrRandom(const hideseek_msgs::SeekerObservationBatch& msg);

  ros::NodeHandle nh_;
  SeekerNodeOptions::Mode mode_;
  int actions_ = 0;  // random mode: the seeker's actions in this game
  int image_height_ = 0, image_width_ = 0;
  std::unique_ptr<hideseek_hider::Learner> learner_;
  // A batch the world re-sent gets the same answer again (random and learned modes): a training
  // run must not take one step twice.
  hideseek_game::ReplyCache reply_;
  SeekerOptions options_;
  std::vector<SeekerPolicy> policies_;
  std::vector<int64_t> episodes_;  // episode each policy was reset for, -1 before the first
  ros::Publisher actions_pub_;
  ros::Publisher plan_pub_, target_pub_;
  ros::WallTime last_plan_publish_;
  ros::Subscriber observations_sub_;
  uint64_t malformed_ = 0;
  hideseek_game::WallThrottle malformed_throttle_{2.0};  // warnings of malformed batches
};

}  // namespace hideseek_seeker
