#include "hideseek_seeker/seeker_node.h"

#include <hideseek_msgs/ActionBatch.h>

#include <stdexcept>

#include "hideseek_game/game_selection.h"
#include "hideseek_game/msg_conversion.h"
#include "hideseek_game/params.h"
#include "hideseek_game/topic_names.h"
#include "hideseek_game/wall_throttle.h"

namespace hideseek_seeker {

Layout toLayout(const hideseek_msgs::ArenaMap& map) {
  Layout layout;
  layout.half_extent = map.half_extent;
  for (const auto& b : map.obstacles) {
    layout.obstacles.push_back(hideseek_game::Box::make({b.x, b.y}, {b.size_x, b.size_y}, b.height, b.yaw));
  }
  for (const auto& w : map.waypoints) layout.waypoints.push_back({w.x, w.y});
  return layout;
}

SeekerPerception toPerception(const hideseek_msgs::SeekerObservationBatch& batch, size_t i) {
  SeekerPerception p;
  p.pose.position = {batch.pose[i].x, batch.pose[i].y};
  p.pose.yaw = batch.pose[i].theta;
  if (batch.sees_hider[i]) p.hider_position = Vec2{batch.hider_position[i].x, batch.hider_position[i].y};
  return p;
}

SeekerNode::SeekerNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh) {
  const hideseek_game::VariantConfig v = hideseek_game::loadVariantParams(pnh);
  const double grid_resolution = hideseek_game::readDouble(pnh, "grid_resolution", 0.1, 0.02, 1.0);
  // The same seeker the in-process calibration plays.
  options_ = seekerOptionsFor(v, grid_resolution);
  actions_pub_ = nh_.advertise<hideseek_msgs::ActionBatch>(hideseek_game::kSeekerActionsTopic, 2);
  observations_sub_ = nh_.subscribe(hideseek_game::kSeekerObservationsTopic, 2, &SeekerNode::onObservations, this,
                                    ros::TransportHints().tcpNoDelay());
  ROS_INFO("seeker: %s policy, planning on a %.2f m grid", v.seeker_policy.c_str(), options_.grid_resolution);
}

void SeekerNode::onObservations(const hideseek_msgs::SeekerObservationBatch::ConstPtr& msg) {
  const size_t n = msg->num_arenas;
  const std::string problem = hideseek_game::checkSeekerObservationBatch(*msg, hideseek_game::kMaxArenas);
  if (!problem.empty()) {
    ++malformed_;
    hideseek_game::WallThrottle& throttle = malformed_throttle_;
    if (throttle.ready()) {
      ROS_WARN("seeker: ignored an observation batch: %s (%lu so far; %lu more like it since the last)",
               problem.c_str(), static_cast<unsigned long>(malformed_),
               static_cast<unsigned long>(throttle.suppressed()));
    }
    return;
  }
  if (policies_.size() != n) {
    policies_.clear();
    for (size_t i = 0; i < n; ++i) policies_.emplace_back(options_);
    episodes_.assign(n, -1);
  }
  hideseek_msgs::ActionBatch out;
  out.header.stamp = msg->header.stamp;
  out.step = msg->step;
  out.actions.resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (episodes_[i] != msg->episode[i]) {
      policies_[i].reset(toLayout(msg->maps[i]), msg->seed[i]);
      episodes_[i] = msg->episode[i];
    }
    out.actions[i] = static_cast<uint8_t>(policies_[i].act(toPerception(*msg, i)));
  }
  actions_pub_.publish(out);
}

}  // namespace hideseek_seeker
