// The scripted seeker of SPEC section 3, acting only on what it perceives.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "hideseek_game/agent.h"
#include "hideseek_game/arena.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/grid_planner.h"

namespace hideseek_seeker {

using hideseek_game::Action;
using hideseek_game::AgentState;
using hideseek_game::GridPlanner;
using hideseek_game::Layout;
using hideseek_game::Vec2;

enum class SeekerPolicyType { kDeterministic, kStochastic };

using hideseek_game::SeekerPerception;

struct SeekerOptions {
  SeekerPolicyType type = SeekerPolicyType::kDeterministic;
  double radius = 0.4;                               // m: the map is inflated by this for planning
  double grid_resolution = 0.1;                      // m
  double turn_per_step = 0.12 * hideseek_game::kPi;  // rad turned by one turn action
  double goal_tolerance = 0.5;                       // m: a waypoint or last known position counts as reached
  // Game v3's steering: a turn towards a target within move_angle of the heading also moves forward
  // (Action::kForwardLeft, kForwardRight); games v1 and v2 turn on the spot.
  bool turn_while_moving = false;
  double move_angle = 0.0;  // rad
  // Which path points it drops. Either way it heads for the farthest point it has a straight line
  // to, clear on the planner's grid, and a point counts as reached within half goal_tolerance.
  // kNextPoint (games v1-v3): only the path's next point is dropped once reached. Points it passed
  // further off, cutting a corner, stay, with any after them (even one it stands on), and become its
  // target again whenever the later points lose their straight line, which a 3 cm step can do: it
  // may then spin on the spot, the target flipping between a point inside its turning circle and a
  // later one, or drive back against the wall it has just gone round, for the rest of an episode.
  // kNoBacktrack: every point up to the last one reached (the goal excepted), and every point before
  // the one it heads for, is dropped, so it never turns back for a point it has passed.
  hideseek_game::SeekerPathFollowing path_following = hideseek_game::SeekerPathFollowing::kNextPoint;
};

// The seeker of a variant, as the seeker node builds it: its policy type, radius and turn from the
// variant; the grid resolution is the node's planning setting.
SeekerOptions seekerOptionsFor(const hideseek_game::VariantConfig& variant, double grid_resolution = 0.1);

enum class SeekerMode { kPatrol, kChase, kLastKnown, kWander };
const char* modeName(SeekerMode mode);

// One arena's seeker: chase what it sees, go to where it last saw the hider, else patrol
// (deterministic) or wander to random free points (stochastic).
class SeekerPolicy {
 public:
  explicit SeekerPolicy(const SeekerOptions& options) : options_(options) {}

  // Starts an episode on a new map; `seed` drives the stochastic seeker's choices.
  void reset(const Layout& layout, uint32_t seed);
  Action act(const SeekerPerception& perception);

  SeekerMode mode() const { return mode_; }
  // The path it follows, points not yet passed first (under next_point the ones before its target
  // may lie behind it), and the point it headed for at its last decision (none when it stayed).
  const std::vector<Vec2>& path() const { return path_; }
  std::optional<Vec2> target() const { return target_; }
  std::optional<Vec2> goal() const { return goal_; }
  // Paths planned since the seeker was made (a straight line to the goal counts): a path is one
  // plan while this stays the same.
  size_t plans() const { return plans_; }

 private:
  Action decide(const SeekerPerception& perception);
  Action steerTowards(const AgentState& pose, Vec2 target) const;
  void setGoal(const AgentState& pose, Vec2 goal);

  SeekerOptions options_;
  std::unique_ptr<GridPlanner> planner_;
  Layout planned_layout_;  // the layout planner_ was built for
  std::vector<Vec2> waypoints_;
  size_t next_waypoint_ = 0;
  std::optional<Vec2> last_known_;
  std::optional<Vec2> goal_;
  std::vector<Vec2> path_;
  std::optional<Vec2> target_;
  size_t plans_ = 0;
  std::optional<hideseek_game::GridCell> afresh_cell_;  // where no_backtrack last planned afresh
  SeekerMode mode_ = SeekerMode::kPatrol;
  Action last_action_ = Action::kStay;  // what act() answered last, for steering hysteresis
  std::mt19937 rng_;
};

}  // namespace hideseek_seeker
