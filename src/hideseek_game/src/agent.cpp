#include "hideseek_game/agent.h"

#include <algorithm>
#include <cmath>

namespace hideseek_game {

namespace {

double nextSpeed(double speed, Action action, const MotionOptions& m, double dt) {
  if (m.mode == SpeedMode::kConstant) {
    if (action == Action::kForward) return m.speed;
    if (action == Action::kBackward) return -m.speed;
    return 0.0;
  }
  const double dv = m.acceleration * dt;
  if (action == Action::kForward) return std::min(speed + dv, m.max_speed);
  if (action == Action::kBackward) return std::max(speed - dv, -m.max_speed);
  // Any other action coasts down towards rest.
  if (speed > 0.0) return std::max(speed - dv, 0.0);
  return std::min(speed + dv, 0.0);
}

// Resolves overlaps; a few passes settle corners where two boxes meet.
void resolveCollisions(Vec2& p, const Layout& layout, double radius) {
  constexpr int kPasses = 4;
  const double limit = layout.half_extent - radius;
  for (int pass = 0; pass < kPasses; ++pass) {
    bool moved = false;
    for (const Box& box : layout.obstacles) moved |= pushCircleOut(box, radius, p);
    const Vec2 clamped{std::clamp(p.x, -limit, limit), std::clamp(p.y, -limit, limit)};
    moved |= clamped.x != p.x || clamped.y != p.y;
    p = clamped;
    if (!moved) break;
  }
}

}  // namespace

void advanceAgent(AgentState& agent, Action action, const MotionOptions& motion, double dt, const Layout& layout,
                  double radius) {
  if (action == Action::kTurnLeft) agent.yaw = wrapAngle(agent.yaw + motion.turn_rate * dt);
  if (action == Action::kTurnRight) agent.yaw = wrapAngle(agent.yaw - motion.turn_rate * dt);
  agent.speed = nextSpeed(agent.speed, action, motion, dt);
  if (agent.speed == 0.0) return;
  const Vec2 heading{std::cos(agent.yaw), std::sin(agent.yaw)};
  const Vec2 start = agent.position;
  agent.position = start + (agent.speed * dt) * heading;
  resolveCollisions(agent.position, layout, radius);
  if (motion.mode == SpeedMode::kAccelerate) {
    // A wall absorbs the part of the motion it blocks, so momentum does not pile up against it.
    const double achieved = dot(agent.position - start, heading) / dt;
    agent.speed = agent.speed > 0.0 ? std::clamp(achieved, 0.0, agent.speed) : std::clamp(achieved, agent.speed, 0.0);
  }
}

}  // namespace hideseek_game
