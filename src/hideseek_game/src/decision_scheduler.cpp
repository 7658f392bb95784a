#include "hideseek_game/decision_scheduler.h"

#include <stdexcept>
#include <string>

namespace hideseek_game {

DecisionScheduler::DecisionScheduler(ClockMode mode, int num_arenas, double stale_action_timeout, double resend_period,
                                     int seeker_actions)
    : mode_(mode),
      num_arenas_(num_arenas),
      stale_action_timeout_(stale_action_timeout),
      resend_period_(resend_period),
      seeker_actions_(seeker_actions),
      pending_(2 * static_cast<size_t>(num_arenas)),
      superseded_(2 * static_cast<size_t>(num_arenas)) {}

Verdict DecisionScheduler::offer(Player player, int arena, uint8_t action, uint32_t step_id, uint32_t current_step) {
  if (action >= actions(player)) return Verdict::kInvalidAction;
  if (mode_ == ClockMode::kRealtime) {
    // An answer to the decision being played is late: the hider's to the step, the seeker's to its
    // decision inside the step (it may be asked again there). Any other id is a wrong step.
    if (player == Player::kHider && executing_ && step_id == current_step) return Verdict::kLate;
    if (player == Player::kSeeker && seeker_executing_ && step_id == current_step) return Verdict::kLate;
  }
  std::optional<uint32_t>& superseded = superseded_[index(player, arena)];
  if (step_id != current_step) {
    if (superseded != step_id) return Verdict::kWrongStep;
    superseded.reset();
    return Verdict::kSupersededByReset;
  }
  superseded.reset();  // answers come in order: none to the step before the reset follows
  pending_[index(player, arena)] = static_cast<Action>(action);
  return Verdict::kAccepted;
}

bool DecisionScheduler::completeFor(Player player) const {
  for (int i = 0; i < num_arenas_; ++i) {
    if (!pending_[index(player, i)]) return false;
  }
  return true;
}

RealtimeStart DecisionScheduler::waitOrStale(bool ready, double now_s, bool connected) {
  if (ready) return RealtimeStart::kReady;
  if (!connected) return RealtimeStart::kStale;
  if (!waiting_since_) waiting_since_ = now_s;
  return now_s - *waiting_since_ < stale_action_timeout_ ? RealtimeStart::kWait : RealtimeStart::kStale;
}

RealtimeStart DecisionScheduler::realtimeStart(double now_s, bool agents_connected) {
  return waitOrStale(complete(), now_s, agents_connected);
}

RealtimeStart DecisionScheduler::realtimeSeekerStart(double now_s, bool seeker_connected) {
  return waitOrStale(completeFor(Player::kSeeker), now_s, seeker_connected);
}

std::vector<Action> DecisionScheduler::takeSeekerDecision() {
  std::vector<Action> seeker;
  for (int i = 0; i < num_arenas_; ++i) {
    auto& a = pending_[index(Player::kSeeker, i)];
    seeker.push_back(a.value_or(Action::kStay));
    a.reset();
  }
  waiting_since_.reset();
  seeker_executing_ = mode_ == ClockMode::kRealtime;
  return seeker;
}

DecisionActions DecisionScheduler::takeDecision() {
  DecisionActions d;
  for (int i = 0; i < num_arenas_; ++i) {
    d.hider.push_back(pending_[index(Player::kHider, i)].value_or(Action::kStay));
    d.seeker.push_back(pending_[index(Player::kSeeker, i)].value_or(Action::kStay));
  }
  for (auto& a : pending_) a.reset();
  waiting_since_.reset();
  executing_ = seeker_executing_ = mode_ == ClockMode::kRealtime;
  return d;
}

void DecisionScheduler::reset(int arena, const std::vector<std::optional<uint32_t>>& awaited) {
  if (awaited.size() != pending_.size()) {
    throw std::invalid_argument("DecisionScheduler::reset: awaited holds " + std::to_string(awaited.size()) +
                                " step ids, not one per player and arena (" + std::to_string(pending_.size()) + ")");
  }
  for (int i = 0; i < num_arenas_; ++i) {
    if (arena != -1 && arena != i) continue;
    for (const Player p : {Player::kHider, Player::kSeeker}) {
      pending_[index(p, i)].reset();
      superseded_[index(p, i)] = awaited[index(p, i)];
    }
  }
  waiting_since_.reset();
  // A decision taken but not played (a reset between takeDecision and its first frame) is dropped:
  // the answers to the next one are not late.
  executing_ = seeker_executing_ = false;
}

}  // namespace hideseek_game
