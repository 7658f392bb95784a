#include "hideseek_hider/hider_node.h"

#include <hideseek_msgs/ActionBatch.h>

#include <stdexcept>

#include "hideseek_game/game_selection.h"
#include "hideseek_game/msg_conversion.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_game/params.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_game/topic_names.h"
#include "hideseek_game/wall_throttle.h"
#include "hideseek_hider/hider_defaults.h"

namespace hideseek_hider {

HiderNodeOptions loadHiderNodeOptions(const ros::NodeHandle& pnh) {
  using hideseek_game::readString;
  HiderNodeOptions o;
  LearnerOptions& l = o.learner;
  // Every default below comes from the defaults file (config/hider.yaml); a parameter overrides it.
  const HiderDefaults d =
      loadHiderDefaults(readString(pnh, "defaults", hideseek_game::configDirectory() + "/hider.yaml"));
  l.variant = hideseek_game::loadVariantParams(pnh);
  o.policy = readString(pnh, "policy", "random");
  // Parsed in every mode, so that a typo is refused even where the network is not used.
  const std::string network = hideseek_game::readChoice(pnh, "network", d.network, {"auto", "ff", "gru"});
  if (network != "auto") l.network = parseNetwork(network, pnh.resolveName("network"));
  std::string mode =
      hideseek_game::readChoice(pnh, "mode", o.policy == "random" ? "random" : "policy", {"random", "policy", "train"});
  if (o.policy == hideseek_game::kShippedPolicy && mode == "policy") {
    const std::string registry = hideseek_game::requireString(pnh, "policy_registry", "the run registry file");
    o.policy = hideseek_game::shippedPolicyFile(registry, l.variant.name, network == "gru" ? "gru" : "ff",
                                                l.variant.game.name);
    if (o.policy.empty()) {
      ROS_WARN(
          "hider: no policy is shipped for variant '%s' on game %s (%s); playing the uniformly random hider. "
          "policy:=FILE plays a checkpoint; hideseek_pipeline train trains one.",
          l.variant.name.c_str(), l.variant.game.name.c_str(), registry.c_str());
      o.policy = "random";
      mode = "random";
    }
  }
  if (o.policy == "scripted" || o.policy == "scripted/") {
    throw std::invalid_argument("parameter " + pnh.resolveName("policy") + " is '" + o.policy +
                                "': name the evader, scripted/EVADER (backpedal, flee, hide, lap)");
  }
  std::optional<EvaderKind> evader;
  try {
    if (mode == "policy") evader = scriptedPolicy(o.policy);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("parameter " + pnh.resolveName("policy") + ": " + e.what());
  }
  o.mode = mode == "random" ? HiderNodeOptions::Mode::kRandom
           : evader         ? HiderNodeOptions::Mode::kScripted
                            : HiderNodeOptions::Mode::kLearner;
  l.role = "hider";
  l.actions = kActions;
  l.mode = mode == "train" ? LearnerMode::kTrain : LearnerMode::kPolicy;
  l.policy = o.policy;
  // Read for the scripted evaders too (a policy mode): a bad device or greedy is refused in both.
  loadLearnerParams(pnh, d, l, o.mode != HiderNodeOptions::Mode::kRandom);
  if (l.memoryless && o.mode != HiderNodeOptions::Mode::kLearner) {
    throw std::invalid_argument("parameter " + pnh.resolveName("memoryless") + " is true, but the hider " +
                                (evader ? "plays " + o.policy : "is in random mode") +
                                ": memoryless applies to a GRU policy only");
  }
  return o;
}

HiderNode::HiderNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh) {
  const HiderNodeOptions o = loadHiderNodeOptions(pnh);
  image_height_ = o.learner.variant.game.camera.height;
  image_width_ = o.learner.variant.game.camera.width;
  switch (o.mode) {
    case HiderNodeOptions::Mode::kRandom:
      policy_ = std::make_unique<RandomHiderPolicy>();
      ROS_INFO("hider: uniformly random policy");
      break;
    case HiderNodeOptions::Mode::kScripted:
      policy_ = std::make_unique<ScriptedHiderPolicy>(*scriptedPolicy(o.policy), o.learner.variant);
      ROS_INFO("hider: scripted evader %s (a baseline that reads the true state, not the image)", o.policy.c_str());
      break;
    case HiderNodeOptions::Mode::kLearner:
      learner_ = std::make_unique<Learner>(o.learner);
      break;
  }
  actions_pub_ = nh_.advertise<hideseek_msgs::ActionBatch>(hideseek_game::kHiderActionsTopic, 2);
  observations_sub_ = nh_.subscribe(hideseek_game::kHiderObservationsTopic, 2, &HiderNode::onObservations, this,
                                    ros::TransportHints().tcpNoDelay());
}

void HiderNode::onObservations(const hideseek_msgs::ObservationBatch::ConstPtr& msg) {
  const size_t n = msg->num_arenas;
  const size_t image_bytes = static_cast<size_t>(image_height_) * image_width_ * 3;
  const std::string problem =
      hideseek_game::checkObservationBatch(*msg, image_height_, image_width_, hideseek_game::kMaxArenas);
  if (!problem.empty()) {
    ++malformed_;
    hideseek_game::WallThrottle& throttle = malformed_throttle_;
    if (throttle.ready()) {
      ROS_WARN("hider: ignored an observation batch: %s (%lu so far; %lu more like it since the last)", problem.c_str(),
               static_cast<unsigned long>(malformed_), static_cast<unsigned long>(throttle.suppressed()));
    }
    return;
  }
  // The world re-sent a batch: same step, same answer.
  if (const hideseek_msgs::ActionBatch* again = reply_.find(msg->header.stamp, msg->step, msg->seed)) {
    actions_pub_.publish(*again);
    return;
  }
  hideseek_msgs::ActionBatch out;
  out.header.stamp = msg->header.stamp;
  out.step = msg->step;
  if (learner_) {
    out.actions = learner_->act({n, msg->images.data(), &msg->rewards, &msg->done, &msg->step, &msg->seed});
    // Training stopped, or finished with its final checkpoint written: the node's work is done.
    if (out.actions.empty()) {
      ros::shutdown();
      return;
    }
  } else {
    std::vector<ArenaObservation> batch(n);
    const bool poses = msg->hider_pose.size() == n && msg->seeker_pose.size() == n;
    for (size_t i = 0; i < n; ++i) {
      batch[i] = {msg->images.data() + i * image_bytes, msg->seed[i], msg->step[i], {}, {}};
      if (poses) {
        batch[i].hider = {{msg->hider_pose[i].x, msg->hider_pose[i].y}, msg->hider_pose[i].theta, 0.0, {}};
        batch[i].seeker = {{msg->seeker_pose[i].x, msg->seeker_pose[i].y}, msg->seeker_pose[i].theta, 0.0, {}};
      }
    }
    out.actions = policy_->act(batch);
  }
  reply_.keep(msg->header.stamp, msg->seed, out);
  actions_pub_.publish(out);
}

}  // namespace hideseek_hider
