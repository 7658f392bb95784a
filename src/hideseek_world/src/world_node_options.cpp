#include "hideseek_world/world_node_options.h"

#include <stdexcept>

#include "hideseek_game/game_selection.h"
#include "hideseek_game/params.h"

namespace hideseek_world {

using namespace hideseek_game;

namespace {
constexpr int kMaxDecisions = 1 << 30;  // ~max_decisions: far beyond any rollout
}  // namespace

WorldNodeOptions loadWorldNodeOptions(const ros::NodeHandle& nh) {
  WorldNodeOptions o;
  o.variant = loadVariantParams(nh);
  o.map = loadMapFile(o.variant.map_file);
  o.loop.mode = readChoice(nh, "mode", "realtime", {"realtime", "lockstep"}) == "lockstep" ? ClockMode::kLockstep
                                                                                           : ClockMode::kRealtime;
  o.loop.num_arenas = readInt(nh, "num_arenas", kWatchingArenas, 1, kMaxArenas);
  o.loop.seed = static_cast<uint32_t>(readInt(nh, "seed", 0, 0, kMaxSeed));
  o.loop.seed_stride = static_cast<uint32_t>(readInt(nh, "seed_stride", 0, 0, kMaxSeed));
  o.status_period = readDouble(nh, "status_period", 0.0, 0.0, 3600.0);
  o.frame_id = readString(nh, "frame_id", "map");
  if (o.frame_id.empty()) throw std::runtime_error("parameter " + nh.resolveName("frame_id") + " must not be empty");
  o.tf_prefix = readString(nh, "tf_prefix", "");
  while (!o.tf_prefix.empty() && o.tf_prefix.back() == '/') o.tf_prefix.pop_back();
  if (!o.tf_prefix.empty() && o.tf_prefix.front() == '/') o.tf_prefix.erase(0, 1);
  o.frame_id = o.frame(o.frame_id);
  o.loop.stale_action_timeout = readDouble(nh, "stale_action_timeout", 0.5, 0.01, 60.0);
  o.loop.resend_period = readDouble(nh, "resend_period", 1.0, 0.05, 60.0);
  o.publish_rate = readDouble(nh, "publish_rate", 30.0, 0.1, 1000.0);
  o.loop.render_threads = readInt(nh, "render_threads", 2, 0, 64);
  o.episode_listeners = readInt(nh, "episode_listeners", 0, 0, 64);
  o.step_listeners = readInt(nh, "step_listeners", 0, 0, 64);
  o.step_image_every = readInt(nh, "step_image_every", 10, 0, 1000000);
  o.max_decisions = readInt(nh, "max_decisions", 0, 0, kMaxDecisions);
  // A seeker that decides once a step, as the hider does (the seeker node's random, policy and
  // train modes); with seeker_images (policy and train: a network's input) every arena's seeker
  // camera is rendered after each decision. The random seeker needs no image, so none is rendered.
  const bool learned = readBool(nh, "learned_seeker", false);
  if (learned) o.variant.game = withLearnedSeeker(o.variant.game);
  o.loop.render_seeker = readBool(nh, "seeker_images", learned);
  if (o.loop.render_seeker && !learned) {
    throw std::runtime_error("parameter " + nh.resolveName("seeker_images") + " is true, but " +
                             nh.resolveName("learned_seeker") +
                             " is false: the seeker's images are a learning seeker's");
  }
  return o;
}

}  // namespace hideseek_world
