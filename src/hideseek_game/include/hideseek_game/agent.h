// Agent state, the action set and planar kinematics with sliding collisions.
#pragma once

#include <cstdint>

#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"

namespace hideseek_game {

// The hider's five actions (kNumActions), and two more that only a seeker steering with
// SeekerSteering::kTurnWhileMoving may take: a turn and a forward move in the same frame.
enum class Action : uint8_t {
  kStay = 0,
  kForward = 1,
  kBackward = 2,
  kTurnLeft = 3,
  kTurnRight = 4,
  kForwardLeft = 5,
  kForwardRight = 6
};
constexpr int kNumActions = 5;
constexpr int kNumSeekerActions = 7;
// The actions an agent may take in a game: the hider always kNumActions; the seeker the two more
// only where it steers while it moves.
int actionCount(const GameOptions& game, bool seeker);

struct AgentState {
  Vec2 position;
  double yaw = 0.0;
  double speed = 0.0;  // signed, along the heading
  Vec2 velocity;       // m/s in the map frame: the momentum model's state (zero in the other models)
};

// Advances one physics frame: turn, speed update, move, then slide out of walls and boxes.
void advanceAgent(AgentState& agent, Action action, const MotionOptions& motion, double dt, const Layout& layout,
                  double radius);

}  // namespace hideseek_game
