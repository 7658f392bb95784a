#include "hideseek_game/game_loop.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace hideseek_game {

GameLoop::GameLoop(const GameOptions& game, std::shared_ptr<const MapSpec> map, const GameLoopOptions& options)
    : world_(game, std::move(map), options.num_arenas, options.seed, options.render, options.render_threads,
             options.seed_stride),
      scheduler_(options.mode, options.num_arenas, options.stale_action_timeout, options.resend_period,
                 actionCount(game, true)),
      render_(options.render),
      render_seeker_(options.render_seeker) {
  if (render_seeker_ && game.seeker_decision_frames != game.action_repeat) {
    throw std::invalid_argument(
        "GameLoop: a learning seeker decides once a decision step, but the game's seeker "
        "decides every " +
        std::to_string(game.seeker_decision_frames) + " of its " + std::to_string(game.action_repeat) +
        " frames (play withLearnedSeeker(game))");
  }
  if (render_seeker_ && !render_) throw std::invalid_argument("GameLoop: render_seeker needs render");
  const size_t n = static_cast<size_t>(options.num_arenas);
  if (render_) images_.resize(world_.imageBytes() * n);
  if (render_seeker_) seeker_images_.resize(world_.imageBytes() * n);
  rewards_.assign(n, 0.f);
  seeker_rewards_.assign(n, 0.f);
  done_.assign(n, 0);
  outcomes_.assign(n, 0);
  last_hider_.assign(n, Action::kStay);
  last_seeker_.assign(n, Action::kStay);
  step_hider_.assign(n, Action::kStay);
  step_first_seeker_.assign(n, Action::kStay);
  seeker_now_.assign(n, Action::kStay);
  render();
}

void GameLoop::render() {
  if (render_) world_.renderHiderViews(images_.data());
  if (render_seeker_) world_.renderSeekerViews(seeker_images_.data());
}

uint32_t GameLoop::expectedStepId(Player player, int arena) const {
  // The hider answers a step's first frame; inside the step only the seeker decides.
  if (player == Player::kSeeker) return world_.seekerDecisionId(arena);
  return atStepStart() ? static_cast<uint32_t>(world_.arena(arena).stepCount()) : kNoStep;
}

Verdict GameLoop::offer(Player player, int arena, uint8_t action, uint32_t step_id) {
  // Realtime, while a step's frames play: the hider's answer to that step is late, any other a wrong step.
  const uint32_t current = player == Player::kHider && scheduler_.executing()
                               ? static_cast<uint32_t>(world_.stepPlaying(arena))
                               : expectedStepId(player, arena);
  return scheduler_.offer(player, arena, action, step_id, current);
}

bool GameLoop::decisionReady() const {
  return atStepStart() ? scheduler_.complete() : scheduler_.completeFor(Player::kSeeker);
}

RealtimeStart GameLoop::realtimeStart(double now_s, bool hider_connected, bool seeker_connected) {
  if (atStepStart()) return scheduler_.realtimeStart(now_s, hider_connected && seeker_connected);
  return scheduler_.realtimeSeekerStart(now_s, seeker_connected);
}

void GameLoop::takeDecision() {
  if (decided_) throw std::logic_error("GameLoop: a decision taken twice before its frames played");
  if (atStepStart()) {
    DecisionActions d = scheduler_.takeDecision();
    step_hider_ = std::move(d.hider);
    step_first_seeker_ = d.seeker;
    seeker_now_ = std::move(d.seeker);
  } else {
    seeker_now_ = scheduler_.takeSeekerDecision();
  }
  decided_ = true;
}

std::optional<Decision> GameLoop::playFrame() {
  if (!decided_) throw std::logic_error("GameLoop: a frame played before its decision was taken");
  std::optional<std::vector<ArenaStep>> steps = world_.advanceFrame(step_hider_, seeker_now_);
  // The next frame needs a decision first: a new step's, or the seeker's inside this one.
  if (world_.seekerDecisionDue()) {
    decided_ = false;
    scheduler_.finishSeekerDecision();
  }
  if (!steps) return std::nullopt;
  scheduler_.finishDecision();
  return conclude(std::move(*steps));
}

std::optional<Decision> GameLoop::playToNextDecision() {
  for (;;) {
    if (std::optional<Decision> d = playFrame()) return d;
    if (!decided_) return std::nullopt;
  }
}

std::optional<Decision> GameLoop::finishStep() {
  if (atStepStart()) return std::nullopt;
  for (;;) {
    decided_ = true;  // the seeker's later decisions, if any are due, keep its latest action
    if (std::optional<Decision> d = playFrame()) return d;
  }
}

Decision GameLoop::step(const std::vector<Action>& hider, const ArenaSeekerDecide& seeker) {
  if (!atStepStart() || decided_) throw std::logic_error("GameLoop: step() inside a decision step");
  if (hider.size() != static_cast<size_t>(numArenas())) {
    throw std::invalid_argument("GameLoop: " + std::to_string(hider.size()) + " hider actions for " +
                                std::to_string(numArenas()) + " arenas");
  }
  step_hider_ = hider;
  // Arenas are independent: each plays its whole step alone (playDecisionStep), its seeker asked at
  // each of its decisions while the step runs, the frames the graph asks the seeker node at.
  std::vector<ArenaStep> steps;
  steps.reserve(hider.size());
  for (int i = 0; i < numArenas(); ++i) {
    bool first = true;
    steps.push_back(world_.stepArena(i, hider[i], [&](const SeekerPerception& p) {
      const Action a = seeker(i, p);
      if (first) step_first_seeker_[i] = a;
      first = false;
      return a;
    }));
  }
  return conclude(std::move(steps));
}

Decision GameLoop::conclude(std::vector<ArenaStep> steps) {
  Decision d;
  d.index = decisions_;
  d.hider = step_hider_;
  d.seeker = step_first_seeker_;
  for (size_t i = 0; i < steps.size(); ++i) {
    rewards_[i] = static_cast<float>(steps[i].result.reward);
    seeker_rewards_[i] = static_cast<float>(steps[i].result.seeker_reward);
    done_[i] = steps[i].result.done();
    outcomes_[i] = static_cast<uint8_t>(steps[i].result.outcome);
  }
  d.steps = std::move(steps);
  last_hider_ = step_hider_;
  last_seeker_ = step_first_seeker_;
  ++decisions_;
  render();
  return d;
}

std::optional<Decision> GameLoop::reset(int arena, int64_t seed) {
  const int n = numArenas();
  if (arena < -1 || arena >= n) {
    throw std::invalid_argument("arena " + std::to_string(arena) + " does not exist (0.." + std::to_string(n - 1) +
                                ", or -1 for all)");
  }
  if (seed < -1 || seed > static_cast<int64_t>(UINT32_MAX))
    throw std::invalid_argument("seed must be -1 or in [0, 2^32)");
  // The step ids awaited now: an agent's answer to one may already be on its way.
  std::vector<std::optional<uint32_t>> awaited;
  for (const Player player : {Player::kHider, Player::kSeeker}) {
    for (int i = 0; i < n; ++i) {
      const uint32_t id = expectedStepId(player, i);
      awaited.push_back(id == kNoStep ? std::nullopt : std::optional<uint32_t>(id));
    }
  }
  std::optional<Decision> finished = finishStep();
  scheduler_.reset(arena, awaited);
  for (int i = 0; i < n; ++i) {
    if (arena != -1 && arena != i) continue;
    std::optional<uint32_t> s;
    if (seed >= 0) s = static_cast<uint32_t>(seed + (arena == -1 ? i : 0));
    world_.resetArena(i, s);
    rewards_[i] = 0.f;
    seeker_rewards_[i] = 0.f;
    done_[i] = 0;
    outcomes_[i] = 0;
  }
  decided_ = false;
  render();
  return finished;
}

}  // namespace hideseek_game
