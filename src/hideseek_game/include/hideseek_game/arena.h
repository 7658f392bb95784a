// One arena: an episode of the game with its physics, spawns, rewards and labels.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>

#include "hideseek_game/agent.h"
#include "hideseek_game/free_space_grid.h"

namespace hideseek_game {

// Ground-truth labels of the current state (SPEC section 2); never given to the learner.
struct Labels {
  bool hider_sees_seeker = false;  // S
  bool seeker_sees_hider = false;  // H
  bool obstacle_in_view = false;   // O
};

enum class Outcome : uint8_t { kRunning = 0, kCaptured = 1, kSurvived = 2 };

struct StepResult {
  double reward = 0.0;         // the hider's (GameOptions::rewards)
  double seeker_reward = 0.0;  // a learning seeker's (GameOptions::seeker_rewards)
  Outcome outcome = Outcome::kRunning;
  bool done() const { return outcome != Outcome::kRunning; }
};

// Resolution of the grid used to check that a path joins the two spawns.
constexpr double kSpawnGridResolution = 0.1;

class Arena {
 public:
  Arena(const GameOptions& options, std::shared_ptr<const MapSpec> map);

  // Starts an episode: draws the layout (stochastic maps) and the spawns from `seed` alone.
  void reset(uint32_t seed);
  // Restarts the episode `reset` began from these poses instead of its spawns (the orbit study
  // starts the seeker at chosen angles round a circling hider); the layout and seed stay.
  void startFrom(const AgentState& hider, const AgentState& seeker);
  // Advances one decision step (action_repeat physics frames, fewer when a capture ends it).
  StepResult step(Action hider, Action seeker);
  // Advances one physics frame of the current decision step; returns the step's result when this
  // frame completes it (its last frame, or a capture), else nothing.
  std::optional<StepResult> advanceFrame(Action hider, Action seeker);

  // Physics frames already played of the current decision step.
  int frameInStep() const { return frame_; }
  // Whether the seeker decides before the next frame: every seeker_decision_frames frames.
  bool seekerDecisionDue() const { return frame_ % options_.seeker_decision_frames == 0; }
  // The seeker's decisions in this episode before the current one: its step id in the exchange.
  uint32_t seekerDecisionIndex() const;
  // Whether the seeker sees the hider now, between decision steps too (the labels hold the last
  // decision step's value).
  bool seekerSeesHiderNow() const;

  const AgentState& hider() const { return hider_; }
  const AgentState& seeker() const { return seeker_; }
  const Layout& layout() const { return layout_; }
  const Labels& labels() const { return labels_; }
  int stepCount() const { return step_; }
  uint32_t seed() const { return seed_; }
  double episodeReturn() const { return return_; }
  double seekerEpisodeReturn() const { return seeker_return_; }  // a learning seeker's (seeker_rewards)
  // Changes whenever the layout does, so renderers and planners know when to rebuild.
  uint64_t layoutVersion() const { return layout_version_; }
  const GameOptions& options() const { return options_; }
  const MapSpec& map() const { return *map_; }

 private:
  bool trySpawn(std::mt19937& rng, const FreeSpaceGrid& grid);
  bool fits(Vec2 p, const FreeSpaceGrid& grid) const;
  void requirePlayableLayout() const;
  void updateLabels();

  GameOptions options_;
  std::shared_ptr<const MapSpec> map_;
  std::unique_ptr<FreeSpaceGrid> fixed_grid_;  // fixed maps: built once
  Layout layout_;
  AgentState hider_;
  AgentState seeker_;
  Labels labels_;
  int step_ = 0;
  int frame_ = 0;  // physics frames done in the current decision step
  uint32_t seed_ = 0;
  double return_ = 0.0;
  double seeker_return_ = 0.0;
  bool captured_ = false;
  uint64_t layout_version_ = 0;
};

// What the seeker may act on (SPEC section 3): its own pose, and the hider's position while it
// sees the hider, and at its first decision of an episode when the game gives it the hider's
// spawn point (seeker_knows_spawn). Every seeker, in process or behind the world node, gets
// exactly this.
struct SeekerPerception {
  AgentState pose;
  std::optional<Vec2> hider_position;
};
SeekerPerception seekerPerception(const Arena& arena);

// A seeker played in process: its action for a perception.
using SeekerDecide = std::function<Action(const SeekerPerception&)>;

// Plays one decision step of `arena` with the hider's action, asking `seeker` for an action at
// each of its decisions in the step, in the world node's order: the one game loop of an arena.
StepResult playDecisionStep(Arena& arena, Action hider, const SeekerDecide& seeker);

}  // namespace hideseek_game
