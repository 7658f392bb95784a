// Agent state, the action set and planar kinematics with sliding collisions.
#pragma once

#include <cstdint>

#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"

namespace hideseek_game {

enum class Action : uint8_t { kStay = 0, kForward = 1, kBackward = 2, kTurnLeft = 3, kTurnRight = 4 };
constexpr int kNumActions = 5;

struct AgentState {
  Vec2 position;
  double yaw = 0.0;
  double speed = 0.0;  // signed, along the heading
};

// Advances one physics frame: turn, speed update, move, then slide out of walls and boxes.
void advanceAgent(AgentState& agent, Action action, const MotionOptions& motion, double dt, const Layout& layout,
                  double radius);

}  // namespace hideseek_game
