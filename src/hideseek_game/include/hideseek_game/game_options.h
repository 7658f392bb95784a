// Every number of the game (SPEC section 2), with SPEC's values as defaults.
#pragma once

#include <string>

#include "hideseek_game/geometry.h"

namespace hideseek_game {

// The largest seed a parameter or file may name: seeds grow by arena and episode offsets, which
// stay far inside uint32_t from here.
inline constexpr int kMaxSeed = 1 << 30;

enum class SpeedMode { kConstant, kAccelerate };

// How an agent moves under the five actions.
struct MotionOptions {
  SpeedMode mode = SpeedMode::kConstant;
  double speed = 2.0;         // m/s, constant mode
  double max_speed = 4.0;     // m/s, accelerate mode
  double acceleration = 2.0;  // m/s^2, accelerate mode
  double turn_rate = kPi;     // rad/s
};

struct CameraOptions {
  int width = 84;
  int height = 84;
  double horizontal_fov = 120.0 * kPi / 180.0;  // rad
  double mount_height = 1.0;                    // m above the floor
  double near_clip = 0.05;
  double far_clip = 30.0;
  // Vertical field of view implied by the horizontal one and the aspect ratio.
  double verticalFov() const;
};

struct RewardOptions {
  double survive = 0.001;   // every step the hider is not captured
  double capture = -1.0;    // the step it is captured (replaces every other term)
  bool visibility = false;  // add the visibility terms below
  double unseen = 0.001;    // a step after which the seeker does not see the hider
  double seen = -0.001;     // a step after which it does
};

struct GameOptions {
  // The game's name (a game file's `game`: v2, v1): the run registry records which game a
  // policy trained on, and a variant plays by default only a policy of its own game.
  std::string name = "v2";
  double physics_dt = 0.02;
  int action_repeat = 6;
  int max_steps = 1000;
  double agent_radius = 0.4;
  double agent_height = 1.2;
  double capture_distance = 0.8;
  double min_spawn_distance = 3.0;
  MotionOptions hider;
  MotionOptions seeker{SpeedMode::kConstant, 1.5, 1.5, 2.0, kPi};
  // Physics frames between two decisions of the scripted seeker; divides action_repeat. The
  // paper gives the action repeat for the learner only; a scripted agent in a game engine
  // usually decides every frame (game v2: 1; game v1: 6).
  int seeker_decision_frames = 1;
  // The seeker starts knowing the hider's spawn point, as its last known position: both
  // agents start facing each other (game v2: true; game v1: false).
  bool seeker_knows_spawn = true;
  CameraOptions camera;
  RewardOptions rewards;

  double stepDuration() const { return physics_dt * action_repeat; }
  int seekerDecisionsPerStep() const { return action_repeat / seeker_decision_frames; }
};

// A variant file (config/variants/*.yaml): the game options plus what other nodes need.
struct VariantConfig {
  std::string name;
  std::string source;
  std::string game_file;      // the game file the variant was read over (its `extends` chain)
  std::string map_file;       // resolved against the game file's maps_dir
  std::string seeker_policy;  // deterministic | stochastic
  GameOptions game;
};

// Reads a game file (config/game.yaml, or one that `extends` it, such as config/game_v1.yaml),
// then a variant file over it; throws ConfigError.
VariantConfig loadVariantConfig(const std::string& game_file, const std::string& variant_file);

}  // namespace hideseek_game
