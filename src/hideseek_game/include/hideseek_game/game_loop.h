// The game's one loop, free of ROS: a World's arenas played decision by decision, all in phase,
// under DecisionScheduler's rules. The world node serves it over topics (agents answer by
// message, in lockstep or realtime); the in-process tools (play_episodes, the calibration table,
// the analysis's scripted hiders) drive it with policies called directly (step()). Both ask the
// seeker at the same frames with the same perception and take the same draws in the same order,
// so an episode is the same in process and through the graph.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "hideseek_game/decision_scheduler.h"
#include "hideseek_game/world.h"

namespace hideseek_game {

struct GameLoopOptions {
  ClockMode mode = ClockMode::kLockstep;
  int num_arenas = 1;
  uint32_t seed = 0;         // arena i's first episode has seed seed + i
  uint32_t seed_stride = 0;  // an arena's next episode: its seed + this (0: num_arenas)
  bool render = true;        // render the hider views after each decision
  // A learning seeker plays: render every arena's seeker view after each decision too. Its game
  // must be withLearnedSeeker's (the seeker decides once a step); the loop refuses another.
  bool render_seeker = false;
  int render_threads = 2;             // llvmpipe rasteriser threads
  double stale_action_timeout = 0.5;  // s; realtime: a silent agent stands still after this
  double resend_period = 1.0;         // s; lockstep: an unanswered observation is re-sent after this
};

// What a decision step returns once its last frame has played.
struct Decision {
  uint64_t index = 0;            // decision steps taken before this one
  std::vector<ArenaStep> steps;  // each arena's result, with the episode it ended
  std::vector<Action> hider;     // the hider's actions
  std::vector<Action> seeker;    // the seeker's first decision of the step
};

// The step id an action answers where none is expected (the hider inside a decision step).
constexpr uint32_t kNoStep = UINT32_MAX;

// A seeker called in process: arena i's action for a perception.
using ArenaSeekerDecide = std::function<Action(int arena, const SeekerPerception&)>;

class GameLoop {
 public:
  GameLoop(const GameOptions& game, std::shared_ptr<const MapSpec> map, const GameLoopOptions& options);

  int numArenas() const { return world_.numArenas(); }
  const World& world() const { return world_; }
  World& world() { return world_; }  // to render a seeker view

  // ---- The exchange: agents answer observations (the world node) ----
  // The step id an action of `player` for `arena` must carry now (kNoStep: none is taken).
  uint32_t expectedStepId(Player player, int arena) const;
  // Offers an action answering step `step_id`.
  Verdict offer(Player player, int arena, uint8_t action, uint32_t step_id);
  // At a decision step's start: the next decision is both agents'; inside a step, the seeker's.
  bool atStepStart() const { return world_.frameInStep() == 0; }
  // A decision must be taken before the next frame plays.
  bool decisionDue() const { return !decided_; }
  // Lockstep: every answer the decision due needs has arrived.
  bool decisionReady() const;
  // Realtime: may the decision due be taken at now_s? An absent agent is not waited for.
  RealtimeStart realtimeStart(double now_s, bool hider_connected, bool seeker_connected);
  // Whether `player` answered `arena` for the decision due.
  bool answered(Player player, int arena) const { return scheduler_.answered(player, arena); }
  // The actions `player` may take in this game (codes 0 .. actions - 1).
  int actions(Player player) const { return scheduler_.actions(player); }
  // Takes the decision due: at a step's start both agents' actions, inside it the seeker's
  // (STAY where an answer is missing). Realtime: the hider's answers to the step are late until it
  // ends, the seeker's answer to the decision taken until its frames have played.
  void takeDecision();
  // Plays one physics frame of the decision taken; returns the decision once its step ended
  // (finished episodes replaced by their next ones, the hider views rendered).
  std::optional<Decision> playFrame();
  // Plays frames until the step ends (returns it) or the seeker must decide again (nullopt).
  std::optional<Decision> playToNextDecision();
  // Lockstep timing of the observations (DecisionScheduler).
  void observationSent(double now_s) { scheduler_.observationSent(now_s); }
  bool resendDue(double now_s) const { return scheduler_.resendDue(now_s); }
  double sinceSent(double now_s) const { return scheduler_.sinceSent(now_s); }

  // ---- In process ----
  // One whole decision step of every arena: the hider's actions, and `seeker` asked for arena i at
  // each of its decisions while arena i's step runs. At a step's start only.
  Decision step(const std::vector<Action>& hider, const ArenaSeekerDecide& seeker);

  // Starts a new episode in `arena` (-1: every arena) with seed `seed` (for arena -1, arena i gets
  // seed + i), or the next of the arena's sequence when seed is -1. A decision step in progress is
  // first played to its end with the seeker's latest decision, so that no step is cut in two; it
  // is returned, like any other. Pending answers of the arena are forgotten and the hider views
  // rendered afresh; one answer per agent to the step it awaited before is then dropped as
  // kSupersededByReset (it was sent before the agent saw the reset). Throws
  // std::invalid_argument, changing nothing, for an arena or seed out of range.
  std::optional<Decision> reset(int arena, int64_t seed);

  // What the hider observes after the last decision (or reset): per arena.
  const std::vector<float>& rewards() const { return rewards_; }
  const std::vector<uint8_t>& done() const { return done_; }
  const std::vector<uint8_t>& outcomes() const { return outcomes_; }
  const std::vector<uint8_t>& hiderImages() const { return images_; }  // numArenas() rgb8 images
  // What a learning seeker observes after the last decision: its rewards (done and outcomes are the
  // hider's) and, with render_seeker, its images (else empty).
  const std::vector<float>& seekerRewards() const { return seeker_rewards_; }
  const std::vector<uint8_t>& seekerImages() const { return seeker_images_; }
  const std::vector<Action>& lastHiderActions() const { return last_hider_; }
  const std::vector<Action>& lastSeekerActions() const { return last_seeker_; }
  // Decision steps taken (the world's clock).
  uint64_t decisions() const { return decisions_; }

 private:
  Decision conclude(std::vector<ArenaStep> steps);
  std::optional<Decision> finishStep();
  void render();

  World world_;
  DecisionScheduler scheduler_;
  bool render_;
  bool render_seeker_;
  std::vector<uint8_t> images_, seeker_images_;
  std::vector<float> rewards_, seeker_rewards_;
  std::vector<uint8_t> done_, outcomes_;
  std::vector<Action> last_hider_, last_seeker_;
  // The decision step being played: the hider's actions, the seeker's first decision (what the
  // step reports) and the seeker's decision the frames now play.
  std::vector<Action> step_hider_, step_first_seeker_, seeker_now_;
  bool decided_ = false;  // the decision due has been taken and its frames not yet all played
  uint64_t decisions_ = 0;
};

}  // namespace hideseek_game
