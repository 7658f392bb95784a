// Scripted evaders: baseline hiders that read the true game state (both poses and the layout),
// never an image. They calibrate the game (does hiding pay, does backing away in view win?) and
// sit beside the learned hiders in every table. They decide once per decision step, like the
// learned hider.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_game/agent.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/grid_planner.h"

namespace hideseek_hider {

using hideseek_game::GridPlanner;
using hideseek_game::Vec2;

enum class EvaderKind {
  kRandom,     // uniformly random actions, drawn from the episode seed and step (the paper's baseline)
  kBackpedal,  // face the seeker and back away from it along free space, keeping it in view
  kFlee,       // turn away and run to the reachable free point farthest from the seeker
  kHide,       // go to a reachable point an obstacle hides from the seeker, stay while hidden, move on
               // when the seeker comes round
  kLap,        // lap the arena's centre backward, facing the seeker that follows: what the first
               // learned hiders of game v2 did
};
constexpr EvaderKind kAllEvaders[] = {EvaderKind::kRandom, EvaderKind::kBackpedal, EvaderKind::kFlee, EvaderKind::kHide,
                                      EvaderKind::kLap};
const char* evaderName(EvaderKind kind);
// The evader called `name` (random, backpedal, flee, hide, lap), or nothing.
std::optional<EvaderKind> evaderKind(const std::string& name);

// The true state an evader decides on.
struct EvaderObservation {
  hideseek_game::AgentState hider;
  hideseek_game::AgentState seeker;
  uint32_t seed = 0;  // the episode's seed
  uint32_t step = 0;  // decision step in the episode
};

// Tuning of the evaders' planning; none of it is a game rule.
struct EvaderOptions {
  double grid_resolution = 0.2;     // m: the distance fields and hiding spots
  double clearance_weight = 1.0;    // backpedal: metres of distance worth one metre of clearance
  double clearance_cap = 1.5;       // m: clearance beyond this earns nothing
  double hide_margin = 1.0;         // m: a hiding spot must be this much nearer the hider than the seeker
  double retarget_distance = 1.0;   // m: flee replans when its goal moved this far
  double move_on_distance = 3.0;    // m: hide leaves its spot when the seeker's way to it is this short
  double hide_search_radius = 8.0;  // m: hide takes the safest spot within this path length
  double lap_radius = 5.5;          // m from the arena's centre: the ring lap aims for (game v2's outer ring)
  double lap_step_deg = 40.0;       // lap aims this far ahead round the centre
  double lap_detour = 2.0;          // lap takes a smaller radius where the way ahead is longer than this
                                    // many times the straight line (a pocket, not the ring)
};

class ScriptedEvader {
 public:
  ScriptedEvader(EvaderKind kind, const hideseek_game::GameOptions& game, const EvaderOptions& options = {});

  EvaderKind kind() const { return kind_; }
  // Starts an episode on `layout`; the grid is rebuilt only when the obstacles changed.
  void reset(const hideseek_game::Layout& layout);
  hideseek_game::Action act(const EvaderObservation& observation);
  // Where flee or hide is heading, if anywhere.
  std::optional<Vec2> goal() const { return goal_; }

 private:
  hideseek_game::Action backpedal(const EvaderObservation& o);
  hideseek_game::Action flee(const EvaderObservation& o);
  hideseek_game::Action hide(const EvaderObservation& o);
  hideseek_game::Action lap(const EvaderObservation& o);
  // The point lap aims for, `sign` (+1 anticlockwise) round the centre from p.
  Vec2 lapTarget(Vec2 p, int sign) const;
  // Turn towards the next point of path_ (replanned to goal_ when needed), else move forward; with
  // `backward`, turn the back towards it and move backward.
  hideseek_game::Action follow(const hideseek_game::AgentState& hider, bool backward = false);
  // A distance field's value at p (pressed against a box: the best free neighbour's, plus the way there).
  float fieldAt(const std::vector<float>& field, Vec2 p) const;
  // Whether the seeker, turned towards an agent at p, would see it past the obstacles.
  bool hiddenFrom(Vec2 seeker, Vec2 p) const;
  // Whether p is hidden from where the seeker is and from where it will search: the hider's
  // position when the seeker last saw it, and the way there.
  bool hiddenFromSearch(Vec2 seeker, Vec2 p) const;

  EvaderKind kind_;
  hideseek_game::GameOptions game_;
  EvaderOptions options_;
  hideseek_game::Layout layout_;
  std::unique_ptr<GridPlanner> planner_;
  std::vector<float> clearance_;                 // m from each cell centre to the nearest obstacle or wall
  std::vector<float> from_seeker_, from_hider_;  // path lengths from each agent, this step
  std::optional<Vec2> goal_;
  std::optional<Vec2> last_seen_;  // the hider's position when the seeker last saw it (or its spawn)
  std::vector<Vec2> path_;
  int lap_sign_ = 0;  // lap's sense round the centre: +1 anticlockwise, -1 clockwise, 0 not chosen yet
};

}  // namespace hideseek_hider
