#include "hideseek_game/agent.h"

#include <algorithm>
#include <cmath>

namespace hideseek_game {

namespace {

bool pushesForward(Action a) {
  return a == Action::kForward || a == Action::kForwardLeft || a == Action::kForwardRight;
}

double nextSpeed(double speed, Action action, const MotionOptions& m, double dt) {
  if (m.mode == SpeedMode::kConstant) {
    if (pushesForward(action)) return m.speed;
    if (action == Action::kBackward) return -m.speed;
    return 0.0;
  }
  const double dv = m.acceleration * dt;
  if (pushesForward(action)) return std::min(speed + dv, m.max_speed);
  if (action == Action::kBackward) return std::max(speed - dv, -m.max_speed);
  // Any other action coasts down towards rest.
  if (speed > 0.0) return std::max(speed - dv, 0.0);
  return std::min(speed + dv, 0.0);
}

// Removes from the velocity the part that points against a contact's push (from `before` to
// `after`): what a wall or box stops, leaving the part along it, so the agent slides.
void removeInto(Vec2 before, Vec2 after, Vec2& velocity) {
  const Vec2 push = after - before;
  const double length = norm(push);
  if (length <= 0.0) return;
  const Vec2 normal = (1.0 / length) * push;
  const double into = dot(velocity, normal);
  if (into < 0.0) velocity = velocity - into * normal;
}

// Resolves overlaps; a few passes settle corners where two boxes meet. With a velocity, each
// contact also removes the part of it that points into the contact (the momentum model).
void resolveCollisions(Vec2& p, const Layout& layout, double radius, Vec2* velocity = nullptr) {
  constexpr int kPasses = 4;
  const double limit = layout.half_extent - radius;
  for (int pass = 0; pass < kPasses; ++pass) {
    bool moved = false;
    for (const Box& box : layout.obstacles) {
      const Vec2 before = p;
      const bool pushed = pushCircleOut(box, radius, p);
      if (pushed && velocity) removeInto(before, p, *velocity);
      moved |= pushed;
    }
    const Vec2 clamped{std::clamp(p.x, -limit, limit), std::clamp(p.y, -limit, limit)};
    moved |= clamped.x != p.x || clamped.y != p.y;
    if (velocity) {
      removeInto({p.x, 0.0}, {clamped.x, 0.0}, *velocity);
      removeInto({0.0, p.y}, {0.0, clamped.y}, *velocity);
    }
    p = clamped;
    if (!moved) break;
  }
}

// The momentum model: forward and backward push along the heading, stay and the turns only
// apply the drag; the speed is capped at max_speed; contacts remove what points into them.
void advanceRigidBody(AgentState& agent, Action action, const MotionOptions& m, double dt, const Layout& layout,
                      double radius) {
  const Vec2 heading{std::cos(agent.yaw), std::sin(agent.yaw)};
  Vec2 v = agent.velocity;
  if (pushesForward(action)) {
    v = v + (m.acceleration * dt) * heading;
  } else if (action == Action::kBackward) {
    v = v - (m.acceleration * dt) * heading;
  } else {
    v = std::max(0.0, 1.0 - m.drag * dt) * v;
  }
  const double speed = norm(v);
  if (speed > m.max_speed) v = (m.max_speed / speed) * v;
  if (v.x != 0.0 || v.y != 0.0) {
    agent.position = agent.position + dt * v;
    resolveCollisions(agent.position, layout, radius, &v);
  }
  agent.velocity = v;
  agent.speed = dot(v, heading);
}

}  // namespace

int actionCount(const GameOptions& game, bool seeker) {
  return seeker && game.seeker_steering == SeekerSteering::kTurnWhileMoving ? kNumSeekerActions : kNumActions;
}

void advanceAgent(AgentState& agent, Action action, const MotionOptions& motion, double dt, const Layout& layout,
                  double radius) {
  if (action == Action::kTurnLeft || action == Action::kForwardLeft) {
    agent.yaw = wrapAngle(agent.yaw + motion.turn_rate * dt);
  }
  if (action == Action::kTurnRight || action == Action::kForwardRight) {
    agent.yaw = wrapAngle(agent.yaw - motion.turn_rate * dt);
  }
  if (motion.mode == SpeedMode::kAccelerate && motion.accelerate_model == AccelerateModel::kMomentum) {
    advanceRigidBody(agent, action, motion, dt, layout, radius);
    return;
  }
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
