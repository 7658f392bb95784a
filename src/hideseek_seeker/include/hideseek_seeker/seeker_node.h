// Wires SeekerPolicy to the world: one policy per arena, fed only the seeker's perception.
#pragma once

#include <hideseek_msgs/SeekerObservationBatch.h>
#include <ros/ros.h>

#include <vector>

#include "hideseek_game/wall_throttle.h"
#include "hideseek_seeker/seeker_policy.h"

namespace hideseek_seeker {

// Builds the core's layout from the map the world sent.
Layout toLayout(const hideseek_msgs::ArenaMap& map);
// The perception of arena i: the hider's position only while the seeker sees it.
SeekerPerception toPerception(const hideseek_msgs::SeekerObservationBatch& batch, size_t i);

class SeekerNode {
 public:
  SeekerNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

 private:
  void onObservations(const hideseek_msgs::SeekerObservationBatch::ConstPtr& msg);

  ros::NodeHandle nh_;
  SeekerOptions options_;
  std::vector<SeekerPolicy> policies_;
  std::vector<int64_t> episodes_;  // episode each policy was reset for, -1 before the first
  ros::Publisher actions_pub_;
  ros::Subscriber observations_sub_;
  uint64_t malformed_ = 0;
  hideseek_game::WallThrottle malformed_throttle_{2.0};  // warnings of malformed batches
};

}  // namespace hideseek_seeker
