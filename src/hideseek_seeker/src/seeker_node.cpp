#include "hideseek_seeker/seeker_node.h"

#include <geometry_msgs/PointStamped.h>
#include <hideseek_msgs/ActionBatch.h>
#include <nav_msgs/Path.h>

#include <cmath>
#include <stdexcept>

#include "hideseek_game/game_selection.h"
#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/msg_conversion.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_game/params.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_game/topic_names.h"
#include "hideseek_game/wall_throttle.h"
#include "hideseek_hider/hider_defaults.h"

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

SeekerNodeOptions loadSeekerNodeOptions(const ros::NodeHandle& pnh) {
  using hideseek_game::readString;
  SeekerNodeOptions o;
  o.variant = hideseek_game::loadVariantParams(pnh);
  const std::string policy = readString(pnh, "policy", "");
  const std::string mode = hideseek_game::readChoice(pnh, "mode", policy.empty() ? "scripted" : "policy",
                                                     {"scripted", "random", "policy", "train"});
  o.mode = mode == "scripted" ? SeekerNodeOptions::Mode::kScripted
           : mode == "random" ? SeekerNodeOptions::Mode::kRandom
                              : SeekerNodeOptions::Mode::kLearner;
  o.grid_resolution = hideseek_game::readDouble(pnh, "grid_resolution", 0.1, 0.02, 1.0);
  if (o.mode != SeekerNodeOptions::Mode::kLearner) {
    if (!policy.empty()) {
      throw std::invalid_argument("parameter " + pnh.resolveName("policy") + " is '" + policy +
                                  "', but the seeker is in " + mode + " mode: a checkpoint plays in mode policy");
    }
    return o;
  }
  hideseek_hider::LearnerOptions& l = o.learner;
  // A learning seeker decides once a step, as the hider does (the world's learned_seeker).
  l.variant = o.variant;
  l.variant.game = hideseek_game::withLearnedSeeker(o.variant.game);
  l.role = "seeker";
  l.actions = hideseek_game::actionCount(l.variant.game, true);
  l.mode = mode == "train" ? hideseek_hider::LearnerMode::kTrain : hideseek_hider::LearnerMode::kPolicy;
  if (l.mode == hideseek_hider::LearnerMode::kPolicy) {
    l.policy = hideseek_game::requireString(pnh, "policy", "a seeker's checkpoint, in policy mode");
    if (l.policy == hideseek_game::kShippedPolicy || l.policy == "random" || l.policy.rfind("scripted", 0) == 0) {
      throw std::invalid_argument("parameter " + pnh.resolveName("policy") + " is '" + l.policy +
                                  "', a hider's policy: the seeker plays a seeker's checkpoint (or mode scripted or "
                                  "random)");
    }
  }
  const hideseek_hider::HiderDefaults d =
      hideseek_hider::loadHiderDefaults(readString(pnh, "defaults", hideseek_game::configDirectory() + "/hider.yaml"));
  const std::string network = hideseek_game::readChoice(pnh, "network", d.network, {"auto", "ff", "gru"});
  if (network != "auto") l.network = hideseek_hider::parseNetwork(network, pnh.resolveName("network"));
  hideseek_hider::loadLearnerParams(pnh, d, l);
  return o;
}

SeekerNode::SeekerNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh) {
  const SeekerNodeOptions o = loadSeekerNodeOptions(pnh);
  mode_ = o.mode;
  // The same seeker the in-process calibration plays.
  options_ = seekerOptionsFor(o.variant, o.grid_resolution);
  actions_ = hideseek_game::actionCount(o.variant.game, true);
  image_height_ = o.variant.game.camera.height;
  image_width_ = o.variant.game.camera.width;
  switch (mode_) {
    case SeekerNodeOptions::Mode::kScripted:
      ROS_INFO("seeker: %s policy, planning on a %.2f m grid", o.variant.seeker_policy.c_str(),
               options_.grid_resolution);
      break;
    case SeekerNodeOptions::Mode::kRandom:
      ROS_INFO("seeker: uniformly random among its %d actions", actions_);
      break;
    case SeekerNodeOptions::Mode::kLearner:
      learner_ = std::make_unique<hideseek_hider::Learner>(o.learner);
      ROS_INFO(
          "seeker: learned, from its own %dx%d camera alone, %d actions, one decision a step (the world's "
          "~learned_seeker, set by the launch files for this mode)",
          image_width_, image_height_, o.learner.actions);
      break;
  }
  actions_pub_ = nh_.advertise<hideseek_msgs::ActionBatch>(hideseek_game::kSeekerActionsTopic, 2);
  if (mode_ == SeekerNodeOptions::Mode::kScripted) {
    // Latched: rviz started later shows the plan being followed.
    plan_pub_ = nh_.advertise<nav_msgs::Path>(hideseek_game::kSeekerPlanTopic, 2, true);
    target_pub_ = nh_.advertise<geometry_msgs::PointStamped>(hideseek_game::kSeekerTargetTopic, 2, true);
  }
  observations_sub_ = nh_.subscribe(hideseek_game::kSeekerObservationsTopic, 2, &SeekerNode::onObservations, this,
                                    ros::TransportHints().tcpNoDelay());
}

void SeekerNode::onObservations(const hideseek_msgs::SeekerObservationBatch::ConstPtr& msg) {
  const size_t n = msg->num_arenas;
  const bool learned = mode_ == SeekerNodeOptions::Mode::kLearner;
  const std::string problem = hideseek_game::checkSeekerObservationBatch(
      *msg, hideseek_game::kMaxArenas, learned ? image_height_ : 0, learned ? image_width_ : 0);
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
  hideseek_msgs::ActionBatch out;
  out.header.stamp = msg->header.stamp;
  out.step = msg->step;
  if (mode_ != SeekerNodeOptions::Mode::kScripted) {
    out.actions = learnedOrRandom(*msg);
    if (out.actions.empty()) return;
    actions_pub_.publish(out);
    return;
  }
  if (policies_.size() != n) {
    policies_.clear();
    for (size_t i = 0; i < n; ++i) policies_.emplace_back(options_);
    episodes_.assign(n, -1);
  }
  out.actions.resize(n);
  AgentState seeker;  // arena 0's, for its plan
  for (size_t i = 0; i < n; ++i) {
    if (episodes_[i] != msg->episode[i]) {
      policies_[i].reset(toLayout(msg->maps[i]), msg->seed[i]);
      episodes_[i] = msg->episode[i];
    }
    const SeekerPerception perception = toPerception(*msg, i);
    out.actions[i] = static_cast<uint8_t>(policies_[i].act(perception));
    if (i == 0) seeker = perception.pose;
  }
  actions_pub_.publish(out);
  if (n > 0) publishPlan(msg->header, seeker, policies_[0]);
}

void SeekerNode::publishPlan(const std_msgs::Header& header, const AgentState& seeker, const SeekerPolicy& policy) {
  // At most 30 times a wall second, as the world sends its own rviz topics: the seeker decides every
  // physics frame.
  const ros::WallTime now = ros::WallTime::now();
  if (now < last_plan_publish_ + ros::WallDuration(1.0 / 30.0)) return;
  last_plan_publish_ = now;
  nav_msgs::Path plan;  // from the seeker, as a navigation stack's global plan starts at the robot
  plan.header = header;
  auto pose = [&](Vec2 p, double yaw) {
    geometry_msgs::PoseStamped out;
    out.header = header;
    out.pose.position.x = p.x;
    out.pose.position.y = p.y;
    out.pose.orientation.z = std::sin(0.5 * yaw);
    out.pose.orientation.w = std::cos(0.5 * yaw);
    return out;
  };
  plan.poses.push_back(pose(seeker.position, seeker.yaw));
  for (const Vec2& p : policy.path()) plan.poses.push_back(pose(p, 0.0));
  plan_pub_.publish(plan);
  // No target (no path found: the seeker stays): its own position, so that rviz does not keep showing
  // a point it no longer heads for.
  const Vec2 target = policy.target().value_or(seeker.position);
  geometry_msgs::PointStamped point;
  point.header = header;
  point.point.x = target.x;
  point.point.y = target.y;
  target_pub_.publish(point);
}

std::vector<uint8_t> SeekerNode::learnedOrRandom(const hideseek_msgs::SeekerObservationBatch& msg) {
  // The world re-sent a batch: same step, same answer.
  if (const hideseek_msgs::ActionBatch* again = reply_.find(msg.header.stamp, msg.step, msg.seed)) {
    return again->actions;
  }
  hideseek_msgs::ActionBatch answer;
  answer.step = msg.step;
  const size_t n = msg.num_arenas;
  if (learner_) {
    answer.actions = learner_->act({n, msg.images.data(), &msg.rewards, &msg.done, &msg.step, &msg.seed});
    // Training stopped, or finished with its final checkpoint written: the node's work is done.
    if (answer.actions.empty()) ros::shutdown();
  } else {
    answer.actions.resize(n);
    for (size_t i = 0; i < n; ++i) {
      answer.actions[i] =
          hideseek_game::hashAction(msg.seed[i], msg.step[i], hideseek_game::kSaltRandomSeeker, actions_);
    }
  }
  reply_.keep(msg.header.stamp, msg.seed, answer);
  return answer.actions;
}

}  // namespace hideseek_seeker
