// A hider of your own in C++ that plays a trained network through the project's library: what
// examples/hider_node.py does with a reflex, this node does with hideseek_hider's
// NetworkHiderPolicy. It answers every observation batch with one action per arena, echoing the
// batch's stamp and step ids.
//   ~policy   a hider checkpoint (.pt); empty: the one the registry ships for the game the world
//             plays (its world/game and world/variant parameters)
//   ~greedy   take the most likely action (true) or sample it
// Build it in a workspace of your own overlaid on this one (docs/launch_files.md, A hider of your
// own), then: roslaunch hideseek_world evaluate.launch policy:=external & rosrun my_hider policy_hider_node
#include <hideseek_game/game_selection.h>
#include <hideseek_game/package_paths.h>
#include <hideseek_game/reply_cache.h>
#include <hideseek_hider/checkpoint.h>
#include <hideseek_hider/hider_policy.h>
#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <ros/ros.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::string shippedPolicy(const std::string& game, const std::string& variant) {
  const hideseek_game::GameSelection selection =
      hideseek_game::selectGame(hideseek_game::configDirectory(), game, variant);
  const std::string registry = hideseek_game::packageDirectory("hideseek_world") + "/policies/policies.yaml";
  const std::string shipped = hideseek_game::shippedPolicy(registry, selection);
  if (shipped.empty()) {
    throw std::runtime_error("no policy ships for variant " + selection.variant + " on game " + selection.game +
                             ": set ~policy to a checkpoint");
  }
  return shipped;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "my_hider");
  ros::NodeHandle nh, pnh("~");
  std::string policy = pnh.param<std::string>("policy", "");
  const bool greedy = pnh.param("greedy", true);
  std::unique_ptr<hideseek_hider::NetworkHiderPolicy> hider;
  hideseek_game::ReplyCache answered;  // a batch the world re-sends gets the same answer, not a new act()
  ros::Publisher actions = nh.advertise<hideseek_msgs::ActionBatch>("hider/actions", 2);
  auto on_batch = [&](const hideseek_msgs::ObservationBatch::ConstPtr& batch) {
    const size_t n = batch->num_arenas, image_bytes = size_t{batch->height} * batch->width * 3;
    if (batch->images.size() != n * image_bytes || batch->step.size() != n || batch->seed.size() != n) {
      ROS_WARN_THROTTLE(2.0, "my_hider: skipped a malformed batch");
      return;
    }
    if (const hideseek_msgs::ActionBatch* again = answered.find(batch->header.stamp, batch->step, batch->seed)) {
      actions.publish(*again);  // a GRU's state must not advance twice on one observation
      return;
    }
    std::vector<hideseek_hider::ArenaObservation> arenas(n);
    for (size_t i = 0; i < n; ++i) {
      arenas[i].image = batch->images.data() + i * image_bytes;
      arenas[i].seed = batch->seed[i];  // a new seed starts a new episode (a GRU's state is reset)
      arenas[i].step = batch->step[i];
    }
    hideseek_msgs::ActionBatch reply;
    reply.header.stamp = batch->header.stamp;
    reply.step = batch->step;
    try {
      if (!hider) {  // at the first batch: the world's parameters are set, and its image size known
        if (policy.empty()) {
          policy = shippedPolicy(nh.param<std::string>("world/game", ""), nh.param<std::string>("world/variant", ""));
        }
        ROS_INFO("my_hider: playing %s (%s)", policy.c_str(), greedy ? "greedy" : "sampled");
        hider = std::make_unique<hideseek_hider::NetworkHiderPolicy>(
            hideseek_hider::loadCheckpoint(policy, batch->height, batch->width), torch::kCPU, greedy);
      }
      reply.actions = hider->act(arenas);
    } catch (const std::exception& e) {  // no policy shipped, a checkpoint for another image size, ...
      ROS_FATAL("my_hider: %s", e.what());
      ros::shutdown();
      return;
    }
    answered.keep(batch->header.stamp, batch->seed, reply);
    actions.publish(reply);
  };
  try {
    if (!policy.empty()) hideseek_hider::readCheckpointInfo(policy);  // a bad file stops the node at once
  } catch (const std::exception& e) {
    ROS_FATAL("my_hider: %s", e.what());
    return 1;
  }
  ros::Subscriber observations = nh.subscribe<hideseek_msgs::ObservationBatch>(
      "hider/observations", 2, on_batch, ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  ros::spin();
  return 0;
}
