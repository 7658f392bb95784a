#include "hideseek_world/world_node_options.h"

#include <stdexcept>

namespace hideseek_world {

namespace {

std::string requireString(const ros::NodeHandle& nh, const std::string& name) {
  std::string value;
  if (!nh.getParam(name, value) || value.empty()) {
    throw std::runtime_error("parameter " + nh.resolveName(name) + " is required (a file path)");
  }
  return value;
}

double readDouble(const ros::NodeHandle& nh, const std::string& name, double fallback, double min, double max) {
  double value = fallback;
  if (nh.hasParam(name) && !nh.getParam(name, value)) {
    throw std::runtime_error("parameter " + nh.resolveName(name) + " must be a number");
  }
  if (!(value >= min && value <= max)) {
    throw std::runtime_error("parameter " + nh.resolveName(name) + " must be in [" + std::to_string(min) + ", " +
                             std::to_string(max) + "], got " + std::to_string(value));
  }
  return value;
}

int readInt(const ros::NodeHandle& nh, const std::string& name, int fallback, int min, int max) {
  int value = fallback;
  if (nh.hasParam(name) && !nh.getParam(name, value)) {
    throw std::runtime_error("parameter " + nh.resolveName(name) + " must be an integer");
  }
  if (value < min || value > max) {
    throw std::runtime_error("parameter " + nh.resolveName(name) + " must be in [" + std::to_string(min) + ", " +
                             std::to_string(max) + "], got " + std::to_string(value));
  }
  return value;
}

}  // namespace

VariantConfig loadVariantParams(const ros::NodeHandle& nh) {
  return loadVariantConfig(requireString(nh, "game_config"), requireString(nh, "variant_config"));
}

WorldNodeOptions loadWorldNodeOptions(const ros::NodeHandle& nh) {
  WorldNodeOptions o;
  o.variant = loadVariantParams(nh);
  o.map = loadMapFile(o.variant.map_file);
  const std::string mode = nh.param<std::string>("mode", "realtime");
  if (mode == "realtime") {
    o.mode = ClockMode::kRealtime;
  } else if (mode == "lockstep") {
    o.mode = ClockMode::kLockstep;
  } else {
    throw std::runtime_error("parameter " + nh.resolveName("mode") + " must be 'realtime' or 'lockstep', got '" + mode + "'");
  }
  o.num_arenas = readInt(nh, "num_arenas", 1, 1, kMaxArenas);
  o.seed = static_cast<uint32_t>(readInt(nh, "seed", 0, 0, 1 << 30));
  o.frame_id = nh.param<std::string>("frame_id", "map");
  if (o.frame_id.empty()) throw std::runtime_error("parameter " + nh.resolveName("frame_id") + " must not be empty");
  o.tf_prefix = nh.param<std::string>("tf_prefix", "");
  while (!o.tf_prefix.empty() && o.tf_prefix.back() == '/') o.tf_prefix.pop_back();
  if (!o.tf_prefix.empty() && o.tf_prefix.front() == '/') o.tf_prefix.erase(0, 1);
  o.frame_id = o.frame(o.frame_id);
  o.stale_action_timeout = readDouble(nh, "stale_action_timeout", 0.5, 0.01, 60.0);
  o.resend_period = readDouble(nh, "resend_period", 1.0, 0.05, 60.0);
  o.publish_rate = readDouble(nh, "publish_rate", 30.0, 0.1, 1000.0);
  o.render_threads = readInt(nh, "render_threads", 2, 0, 64);
  o.episode_listeners = readInt(nh, "episode_listeners", 0, 0, 64);
  o.step_listeners = readInt(nh, "step_listeners", 0, 0, 64);
  o.step_image_every = readInt(nh, "step_image_every", 10, 0, 1000000);
  o.max_decisions = readInt(nh, "max_decisions", 0, 0, 1 << 30);
  return o;
}

}  // namespace hideseek_world
