// When the world takes a decision step, from the agents' answers and a clock: the rules of the
// lockstep and realtime exchange, free of ROS so that they are unit-tested with an injected time.
//
// Both modes: an action answers the current step of its arena (its step id), else it is refused.
// The seeker may decide more often than the hider (seeker_decision_frames): a decision step then
// holds several seeker decisions, the first taken with the hider's action, the others alone.
// Lockstep: a decision is taken once both agents answered every arena (the seeker alone for its
//   later decisions in the step); an unanswered observation is re-sent every resend_period.
// Realtime: a decision starts once both agents answered every arena, or once stale_action_timeout
//   has passed since it could have started (a silent agent then stands still for that step), or at
//   once while an agent is absent; the seeker's later decisions likewise. While a decision's
//   frames play, the hider's answers to that step are late and refused, and so is the seeker's
//   answer to the decision being played (never kept for its next one); any other id is a wrong step.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "hideseek_game/agent.h"

namespace hideseek_game {

enum class ClockMode { kRealtime, kLockstep };

enum class Player { kHider = 0, kSeeker = 1 };

// What became of an offered action. kLate (realtime): an answer to a decision already taken,
// without it, after stale_action_timeout. kSupersededByReset: the answer to the step an arena
// awaited when a reset restarted it (sent before the agent saw the reset); dropped, no fault of
// the agent.
enum class Verdict { kAccepted, kInvalidAction, kWrongStep, kLate, kSupersededByReset };

// A realtime decision's start: wait for answers, start with them, or start without some.
enum class RealtimeStart { kWait, kReady, kStale };

// The actions a decision applies, one per arena.
struct DecisionActions {
  std::vector<Action> hider;
  std::vector<Action> seeker;
};

class DecisionScheduler {
 public:
  // The seeker may take seeker_actions actions (kNumActions, or kNumSeekerActions where the game
  // lets it move while it turns); the hider always kNumActions.
  DecisionScheduler(ClockMode mode, int num_arenas, double stale_action_timeout, double resend_period,
                    int seeker_actions = kNumActions);

  // An action of `player` for `arena`, answering step `step_id` while the arena is at `current_step`
  // (in realtime while a decision's frames play, the step or seeker decision being played).
  Verdict offer(Player player, int arena, uint8_t action, uint32_t step_id, uint32_t current_step);
  // Both agents answered every arena.
  bool complete() const { return completeFor(Player::kHider) && completeFor(Player::kSeeker); }
  // `player` answered every arena.
  bool completeFor(Player player) const;
  // Whether the pending answer of `player` for `arena` has arrived.
  bool answered(Player player, int arena) const { return pending_[index(player, arena)].has_value(); }
  // The actions `player` may take: codes 0 .. actions(player) - 1.
  int actions(Player player) const { return player == Player::kSeeker ? seeker_actions_ : kNumActions; }

  // Realtime: may the next decision start at `now_s`? `agents_connected`: both agents publish.
  RealtimeStart realtimeStart(double now_s, bool agents_connected);
  // Realtime: may the seeker's next decision inside the step be taken at `now_s`?
  RealtimeStart realtimeSeekerStart(double now_s, bool seeker_connected);
  // Takes the decision: every arena's pending actions (STAY where missing), then clears them.
  // In realtime the decision's frames now play until finishDecision(), and answers are late.
  DecisionActions takeDecision();
  // Takes the seeker's later decision inside a step (STAY where missing), then clears it.
  std::vector<Action> takeSeekerDecision();
  void finishDecision() { executing_ = false; }
  bool executing() const { return executing_; }
  // The seeker's decision taken last has played its frames: its next one is due. Until then, in
  // realtime, an answer to the decision already taken is late (not kept for the next one).
  void finishSeekerDecision() { seeker_executing_ = false; }

  // Forgets the answers of `arena` (-1: all) after a reset; a realtime wait starts afresh.
  // `awaited[player * num_arenas + arena]`: the step id each arena awaited from each player (none
  // where it awaited nothing); only the reset arenas' are read. One answer to it may still be on
  // its way: it is kSupersededByReset, until the player's next accepted answer for that arena; a
  // second is a wrong step.
  void reset(int arena, const std::vector<std::optional<uint32_t>>& awaited);

  // Lockstep: an observation went out at `now_s`; is a re-send due at `now_s`?
  void observationSent(double now_s) { last_sent_ = now_s; }
  bool resendDue(double now_s) const { return now_s - last_sent_ > resend_period_; }
  double sinceSent(double now_s) const { return now_s - last_sent_; }

 private:
  size_t index(Player p, int arena) const { return static_cast<size_t>(p) * num_arenas_ + arena; }
  RealtimeStart waitOrStale(bool ready, double now_s, bool connected);

  ClockMode mode_;
  int num_arenas_;
  double stale_action_timeout_;
  double resend_period_;
  int seeker_actions_;
  std::vector<std::optional<Action>> pending_;       // [player][arena]
  std::vector<std::optional<uint32_t>> superseded_;  // [player][arena]: the step id a reset left unanswered
  bool executing_ = false;
  bool seeker_executing_ = false;        // realtime: the seeker's decision is taken and its frames play
  std::optional<double> waiting_since_;  // realtime: when the next decision could first have started
  double last_sent_ = 0.0;
};

}  // namespace hideseek_game
