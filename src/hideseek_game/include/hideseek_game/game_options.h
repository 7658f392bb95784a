// Every number of the game. Their values have one home, the base game file (config/game.yaml),
// which must give every key (issue #49): these structs hold zeros until a game file is loaded,
// so no value can come from here silently.
#pragma once

#include <string>

#include "hideseek_game/geometry.h"

namespace hideseek_game {

// The largest seed a parameter or file may name: seeds grow by arena and episode offsets, which
// stay far inside uint32_t from here.
inline constexpr int kMaxSeed = 1 << 30;

enum class SpeedMode { kConstant, kAccelerate };

// What the accelerating ("A") mode does with the actions that push nothing: stay and the turns.
enum class AccelerateModel {
  kBrake,     // games v1 and v2: they slow the agent by `acceleration`, and its velocity turns with its body
  kMomentum,  // game v3: a rigid body whose velocity is a vector of the map frame, kept through turns and
              // stays, where only `drag` slows it; forward and backward push along the heading
};

// How an agent moves under the five actions.
struct MotionOptions {
  SpeedMode mode{};
  double speed{};         // m/s, constant mode
  double max_speed{};     // m/s, accelerate mode: the cap on the speed
  double acceleration{};  // m/s^2, accelerate mode
  double turn_rate{};     // rad/s
  AccelerateModel accelerate_model{};
  double drag{};  // 1/s, momentum model: each frame of stay or a turn scales the velocity by 1 - drag dt
};

// How the scripted seeker steers towards its target.
enum class SeekerSteering {
  kTurnOrMove,       // games v1 and v2: each decision turns on the spot or moves forward
  kTurnWhileMoving,  // game v3: it also moves forward while it turns (Action::kForwardLeft, kForwardRight)
                     // when its target lies within move_angle of its heading
};

// How the scripted seeker drops the points of its planned path (docs/calibration.md, "The scripted
// seeker's stalls"). Either way it heads for the farthest point it has a straight line to, clear on
// the planner's grid, and a point counts as reached within half its goal tolerance (0.25 m).
enum class SeekerPathFollowing {
  kNextPoint,    // games v1-v3: only the path's next point is dropped once reached; points it passed
                 // further off, and any after them, stay, and can become its target again
  kNoBacktrack,  // every point up to the last one reached, and every one before the one it heads for, is dropped
};

struct CameraOptions {
  int width{};
  int height{};
  double horizontal_fov{};  // rad
  double mount_height{};    // m above the floor
  double near_clip{};
  double far_clip{};
  // Vertical field of view implied by the horizontal one and the aspect ratio.
  double verticalFov() const;
};

// One agent's reward per decision step: the hider's (`rewards`), or a learning seeker's
// (`seeker_rewards`, the hider's mirrored: +1 on capture, -0.001 a step, the visibility terms
// with their signs reversed).
struct RewardOptions {
  double survive{};   // every step the hider is not captured
  double capture{};   // the step it is captured (replaces every other term)
  bool visibility{};  // add the visibility terms below
  double unseen{};    // a step after which the seeker does not see the hider
  double seen{};      // a step after which it does
};

struct GameOptions {
  // The game's name (a game file's `game`: v2, v1): the run registry records which game a
  // policy trained on, and a variant plays by default only a policy of its own game.
  std::string name;
  double physics_dt{};
  int action_repeat{};
  int max_steps{};
  double agent_radius{};
  double agent_height{};
  double capture_distance{};
  double min_spawn_distance{};
  MotionOptions hider;
  MotionOptions seeker;
  // Physics frames between two decisions of the scripted seeker; divides action_repeat. The
  // paper gives the action repeat for the learner only; a scripted agent in a game engine
  // usually decides every frame (game v2: 1; game v1: 6).
  int seeker_decision_frames{};
  // The seeker starts knowing the hider's spawn point, as its last known position: both
  // agents start facing each other (game v2: true; game v1: false).
  bool seeker_knows_spawn{};
  SeekerSteering seeker_steering{};
  double seeker_move_angle{};  // rad, turn-while-moving steering: the target's bearing within which it moves
  SeekerPathFollowing seeker_path_following{};
  CameraOptions camera;
  RewardOptions rewards;
  RewardOptions seeker_rewards;  // a learning seeker's (the seeker node's train mode); the scripted one has none

  double stepDuration() const { return physics_dt * action_repeat; }
  int seekerDecisionsPerStep() const { return action_repeat / seeker_decision_frames; }
};

// The game a learning seeker plays: it decides once a decision step, as the hider does (every
// action_repeat frames), where the scripted seeker decides every seeker_decision_frames frames.
GameOptions withLearnedSeeker(GameOptions game);

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
