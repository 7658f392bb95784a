// Options of the world node, read once from the parameter server and validated.
#pragma once

#include <ros/ros.h>

#include <string>

#include "hideseek_game/game_loop.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"

namespace hideseek_world {

struct WorldNodeOptions {
  hideseek_game::VariantConfig variant;
  hideseek_game::MapSpec map;
  // The game loop's own options (clock mode, arenas, seeds, render threads, stale and re-send
  // times), read here once and handed to it whole.
  hideseek_game::GameLoopOptions loop;
  std::string frame_id = "map";
  // Prefix of every TF frame the world names (the fixed frame, agents, cameras), so that two
  // worlds keep their frames apart on one tf tree: "game1" gives game1/map, game1/hider/base_link, ...
  std::string tf_prefix;
  // A frame name with the prefix applied.
  std::string frame(const std::string& name) const { return tf_prefix.empty() ? name : tf_prefix + "/" + name; }
  double publish_rate = 30.0;  // Hz of wall time for rviz outputs (markers, paths, images) in lockstep
  // s of wall time between two status lines of arena 0 on the console (its step, the distance,
  // who sees whom; 0: none): a headless game that is not silent between episodes.
  double status_period = 0.0;
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

// Reads ~game and ~variant (or ~game_config, ~variant_config: hideseek_game::loadVariantParams), ~mode, ~num_arenas,
// ~seed, ... Throws std::runtime_error (or ConfigError for files) naming the parameter or file field at fault.
WorldNodeOptions loadWorldNodeOptions(const ros::NodeHandle& private_nh);

}  // namespace hideseek_world
