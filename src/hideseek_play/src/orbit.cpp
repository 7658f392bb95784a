#include "hideseek_play/orbit.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "hideseek_game/arena.h"
#include "hideseek_seeker/seeker_policy.h"

namespace hideseek_play {

using hideseek_game::Action;
using hideseek_game::AgentState;
using hideseek_game::kPi;
using hideseek_game::Vec2;

namespace {

// The turn of one decision step, in rad.
double turnPerStep(const hideseek_game::GameOptions& g) { return g.hider.turn_rate * g.stepDuration(); }

}  // namespace

double orbitRadius(const hideseek_game::GameOptions& g, OrbitShape shape) {
  // Each side of the polygon is forward_steps steps long; the turn between sides is turnPerStep.
  const double side = shape.forward_steps * g.hider.speed * g.stepDuration();
  return side / (2.0 * std::sin(0.5 * turnPerStep(g)));
}

double orbitSpeed(const hideseek_game::GameOptions& g, OrbitShape shape) {
  return g.hider.speed * shape.forward_steps / (shape.forward_steps + 1.0);
}

OrbitEpisode playOrbit(const hideseek_game::VariantConfig& variant, OrbitShape shape, double start_angle_deg,
                       double gap, double half_extent) {
  const hideseek_game::GameOptions& g = variant.game;
  const double room = half_extent - g.agent_radius;  // where an agent's centre may be
  if (orbitRadius(g, shape) + gap > room) {
    throw std::invalid_argument("orbit study: a circle of radius " + std::to_string(orbitRadius(g, shape)) +
                                " m plus the seeker's " + std::to_string(gap) + " m start gap leaves the arena (" +
                                std::to_string(room) +
                                " m from its centre): take fewer forward steps or a smaller gap");
  }
  auto map = std::make_shared<hideseek_game::MapSpec>();
  map->name = "open";
  map->source = "the orbit study's open arena";
  map->half_extent = half_extent;
  map->waypoints = {{0.0, 0.0}};
  hideseek_game::Arena arena(g, map);
  arena.reset(1);
  // The polygon's centre is the arena's: the hider starts at the beginning of a side, heading along it.
  const double r = orbitRadius(g, shape), half_side = 0.5 * shape.forward_steps * g.hider.speed * g.stepDuration();
  AgentState hider;
  hider.position = {std::sqrt(r * r - half_side * half_side), -half_side};
  hider.yaw = 0.5 * kPi;
  const double a = start_angle_deg * kPi / 180.0;
  AgentState seeker;
  seeker.position = {(r + gap) * std::cos(a), (r + gap) * std::sin(a)};
  seeker.yaw = std::atan2(hider.position.y - seeker.position.y, hider.position.x - seeker.position.x);
  arena.startFrom(hider, seeker);
  hideseek_seeker::SeekerPolicy policy(hideseek_seeker::seekerOptionsFor(variant));
  policy.reset(arena.layout(), 1);
  const hideseek_game::SeekerDecide decide = [&](const hideseek_game::SeekerPerception& p) { return policy.act(p); };
  OrbitEpisode out;
  out.start_angle_deg = start_angle_deg;
  int seen = 0, mutual = 0;
  double distance_sum = 0.0;
  for (int step = 0;; ++step) {
    // forward_steps forward, then one left turn, counted from the start.
    const bool turn = step % (shape.forward_steps + 1) == shape.forward_steps;
    const hideseek_game::StepResult result =
        hideseek_game::playDecisionStep(arena, turn ? Action::kTurnLeft : Action::kForward, decide);
    seen += arena.labels().seeker_sees_hider;
    mutual += arena.labels().seeker_sees_hider && arena.labels().hider_sees_seeker;
    distance_sum += hideseek_game::distance(arena.hider().position, arena.seeker().position);
    if (result.done()) {
      out.living_steps = arena.stepCount();
      out.survived = result.outcome == hideseek_game::Outcome::kSurvived;
      break;
    }
  }
  out.seen_share = static_cast<double>(seen) / out.living_steps;
  out.mutual_share = static_cast<double>(mutual) / out.living_steps;
  out.mean_distance = distance_sum / out.living_steps;
  return out;
}

std::vector<OrbitEpisode> playOrbitAngles(const hideseek_game::VariantConfig& variant, OrbitShape shape, int angles,
                                          double gap, double half_extent) {
  std::vector<OrbitEpisode> out;
  for (int k = 0; k < angles; ++k) out.push_back(playOrbit(variant, shape, 360.0 * k / angles, gap, half_extent));
  return out;
}

}  // namespace hideseek_play
