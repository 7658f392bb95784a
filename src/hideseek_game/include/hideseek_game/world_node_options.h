// Options of the world node, read once from the parameter server and validated.
#pragma once

#include <ros/ros.h>

#include <string>

#include "hideseek_game/decision_scheduler.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"

namespace hideseek_game {

struct WorldNodeOptions {
  VariantConfig variant;
  MapSpec map;
  ClockMode mode = ClockMode::kRealtime;
  int num_arenas = 1;
  uint32_t seed = 0;
  uint32_t seed_stride = 0;  // an arena's next episode seed: its last + this (0: num_arenas)
  std::string frame_id = "map";
  // Prefix of every TF frame the world names (the fixed frame, agents, cameras), so that two
  // worlds keep their frames apart on one tf tree: "game1" gives game1/map, game1/hider/base_link, ...
  std::string tf_prefix;
  // A frame name with the prefix applied.
  std::string frame(const std::string& name) const { return tf_prefix.empty() ? name : tf_prefix + "/" + name; }
  double stale_action_timeout = 0.5;  // s of wall time; realtime agents without news stand still
  double resend_period = 1.0;         // s of wall time; lockstep re-sends a batch nobody answered
  double publish_rate = 30.0;         // Hz of wall time for rviz outputs (markers, paths, images) in lockstep
  // s of wall time between two status lines of arena 0 on the console (its step, the distance,
  // who sees whom; 0: none): a headless game that is not silent between episodes.
  double status_period = 0.0;
  int render_threads = 2;  // llvmpipe rasteriser threads
  // The game starts once world/episodes has this many subscribers (an evaluator, a recorder for
  // analysis): whoever must see the first episodes, however late it connects.
  int episode_listeners = 0;
  // Lockstep also waits for this many subscribers of world/steps (an analysis recorder), so that
  // its record starts at the first decision.
  int step_listeners = 0;
  // world/steps carries the hider images on every step_image_every-th decision (0: never).
  int step_image_every = 10;
  // Lockstep stops advancing after this many decisions (0: never): a rollout of fixed length,
  // such as an analysis recording. The world then idles until the launch ends.
  int64_t max_decisions = 0;
};

constexpr int kMaxArenas = 64;

// Reads the files named by ~game_config and ~variant_config: every node of the game needs them.
// Throws naming the missing parameter, or the file and field at fault.
VariantConfig loadVariantParams(const ros::NodeHandle& private_nh);

// Reads ~game_config, ~variant_config, ~mode, ~num_arenas, ~seed, ... Throws std::runtime_error
// (or ConfigError for files) naming the parameter or file field at fault.
WorldNodeOptions loadWorldNodeOptions(const ros::NodeHandle& private_nh);

}  // namespace hideseek_game
