#include "hideseek_game/arena.h"

#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "hideseek_game/config_error.h"
#include "hideseek_game/visibility.h"

namespace hideseek_game {

namespace {

constexpr int kLayoutAttempts = 200;
constexpr int kSpawnAttempts = 500;

}  // namespace

Arena::Arena(const GameOptions& options, std::shared_ptr<const MapSpec> map) : options_(options), map_(std::move(map)) {
  if (!map_->stochastic) {
    std::mt19937 unused(0);
    layout_ = makeLayout(*map_, unused);
    fixed_grid_ = std::make_unique<FreeSpaceGrid>(layout_, options_.agent_radius, kSpawnGridResolution);
    requirePlayableLayout();
  }
}

// A fixed map must leave room for the spawns: two cell centres where an agent fits, in one free
// region, min_spawn_distance apart; and an agent must fit at each of its waypoints. Checked once, so that a map without
// room is refused at start, naming its obstacles, instead of being searched at every reset. A region's diameter is
// taken over its extreme cells along kDirections directions round the circle: at most 0.2 % short of the true one.
void Arena::requirePlayableLayout() const {
  constexpr int kDirections = 64;
  const FreeSpaceGrid& grid = *fixed_grid_;
  const double limit = layout_.half_extent - options_.agent_radius;  // where trySpawn draws
  std::array<Vec2, kDirections> directions;
  for (int k = 0; k < kDirections; ++k) {
    directions[k] = {std::cos(2.0 * kPi * k / kDirections), std::sin(2.0 * kPi * k / kDirections)};
  }
  std::map<int, std::array<std::pair<double, Vec2>, kDirections>> extremes;  // region -> per direction
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const GridCell c{x, y};
      const Vec2 p = grid.centerOf(c);
      if (std::abs(p.x) > limit || std::abs(p.y) > limit || !fits(p, grid)) continue;
      auto [region, first] = extremes.try_emplace(grid.component(c));
      for (int k = 0; k < kDirections; ++k) {
        const double along = dot(directions[k], p);
        auto& e = region->second[k];
        if (first || along > e.first) e = {along, p};
      }
    }
  }
  double widest = 0.0;
  for (const auto& [label, ends] : extremes) {
    for (const auto& a : ends) {
      for (const auto& b : ends) widest = std::max(widest, distance(a.second, b.second));
    }
  }
  // The seeker patrols the waypoints: each must be a place where an agent stands.
  for (size_t i = 0; i < layout_.waypoints.size(); ++i) {
    const Vec2 w = layout_.waypoints[i];
    if (std::abs(w.x) > limit || std::abs(w.y) > limit || !fits(w, grid)) {
      std::ostringstream m;
      m << "lies closer than the agent radius (" << options_.agent_radius
        << " m) to a wall or an obstacle: no agent can stand there";
      throw ConfigError(map_->source, "waypoints[" + std::to_string(i) + "]", m.str());
    }
  }
  if (widest < options_.min_spawn_distance) {
    std::ostringstream m;
    m << "leave no room for the spawns: no two free points in one region are min_spawn_distance ("
      << options_.min_spawn_distance << " m) apart for an agent of radius " << options_.agent_radius
      << " m (widest: " << widest << " m)";
    throw ConfigError(map_->source, "obstacles", m.str());
  }
}

bool Arena::fits(Vec2 p, const FreeSpaceGrid& grid) const {
  for (const Box& b : layout_.obstacles) {
    if (footprintDistance(b, p) < options_.agent_radius) return false;
  }
  return grid.isFree(grid.cellOf(p));
}

bool Arena::trySpawn(std::mt19937& rng, const FreeSpaceGrid& grid) {
  const double limit = layout_.half_extent - options_.agent_radius;
  std::uniform_real_distribution<double> coordinate(-limit, limit);
  auto sample = [&](Vec2& p) {
    for (int i = 0; i < kSpawnAttempts; ++i) {
      p = {coordinate(rng), coordinate(rng)};
      if (fits(p, grid)) return true;
    }
    return false;
  };
  for (int attempt = 0; attempt < kSpawnAttempts; ++attempt) {
    Vec2 h, s;
    if (!sample(h) || !sample(s)) return false;
    if (distance(h, s) < options_.min_spawn_distance || !grid.connected(h, s)) continue;
    hider_ = {h, std::atan2(s.y - h.y, s.x - h.x), 0.0, {}};
    seeker_ = {s, std::atan2(h.y - s.y, h.x - s.x), 0.0, {}};
    return true;
  }
  return false;
}

void Arena::reset(uint32_t seed) {
  seed_ = seed;
  std::mt19937 rng(seed);
  bool spawned = false;
  for (int attempt = 0; attempt < kLayoutAttempts && !spawned; ++attempt) {
    if (map_->stochastic) {
      layout_ = makeLayout(*map_, rng);
      ++layout_version_;
      const FreeSpaceGrid grid(layout_, options_.agent_radius, kSpawnGridResolution);
      spawned = trySpawn(rng, grid);
    } else {
      spawned = trySpawn(rng, *fixed_grid_);
    }
  }
  if (!spawned) {
    throw std::runtime_error(map_->source + ": no valid spawn pair (free, " +
                             std::to_string(options_.min_spawn_distance) + " m apart, connected) found for seed " +
                             std::to_string(seed));
  }
  step_ = 0;
  frame_ = 0;
  return_ = 0.0;
  seeker_return_ = 0.0;
  captured_ = false;
  updateLabels();
}

void Arena::startFrom(const AgentState& hider, const AgentState& seeker) {
  hider_ = hider;
  seeker_ = seeker;
  step_ = 0;
  frame_ = 0;
  return_ = 0.0;
  seeker_return_ = 0.0;
  captured_ = false;
  updateLabels();
}

StepResult Arena::step(Action hider, Action seeker) {
  std::optional<StepResult> result;
  while (!result) result = advanceFrame(hider, seeker);
  return *result;
}

std::optional<StepResult> Arena::advanceFrame(Action hider, Action seeker) {
  if (captured_ || step_ >= options_.max_steps) throw std::logic_error("Arena: stepped a finished episode");
  advanceAgent(hider_, hider, options_.hider, options_.physics_dt, layout_, options_.agent_radius);
  advanceAgent(seeker_, seeker, options_.seeker, options_.physics_dt, layout_, options_.agent_radius);
  const Vec2 d = hider_.position - seeker_.position;
  captured_ = dot(d, d) <= options_.capture_distance * options_.capture_distance;
  if (++frame_ < options_.action_repeat && !captured_) return std::nullopt;
  frame_ = 0;
  ++step_;
  updateLabels();
  StepResult result;
  // One rule, two agents: the seeker's reward mirrors the hider's through its own numbers.
  auto reward = [&](const RewardOptions& r) {
    if (captured_) return r.capture;
    return r.survive + (r.visibility ? (labels_.seeker_sees_hider ? r.seen : r.unseen) : 0.0);
  };
  result.reward = reward(options_.rewards);
  result.seeker_reward = reward(options_.seeker_rewards);
  if (captured_) {
    result.outcome = Outcome::kCaptured;
  } else if (step_ >= options_.max_steps) {
    result.outcome = Outcome::kSurvived;
  }
  return_ += result.reward;
  seeker_return_ += result.seeker_reward;
  return result;
}

void Arena::updateLabels() {
  labels_.hider_sees_seeker = agentSeesAgent(hider_, seeker_, layout_, options_);
  labels_.seeker_sees_hider = agentSeesAgent(seeker_, hider_, layout_, options_);
  labels_.obstacle_in_view = obstacleInView(hider_, layout_, options_);
}

uint32_t Arena::seekerDecisionIndex() const {
  return static_cast<uint32_t>((step_ * options_.action_repeat + frame_) / options_.seeker_decision_frames);
}

bool Arena::seekerSeesHiderNow() const {
  // At a decision step's boundary the labels are current; between them, look again.
  if (frame_ == 0) return labels_.seeker_sees_hider;
  return agentSeesAgent(seeker_, hider_, layout_, options_);
}

SeekerPerception seekerPerception(const Arena& arena) {
  SeekerPerception p;
  p.pose = arena.seeker();
  const bool told_spawn = arena.options().seeker_knows_spawn && arena.stepCount() == 0 && arena.frameInStep() == 0;
  if (told_spawn || arena.seekerSeesHiderNow()) p.hider_position = arena.hider().position;
  return p;
}

StepResult playDecisionStep(Arena& arena, Action hider, const SeekerDecide& seeker) {
  Action seeker_action = Action::kStay;
  for (;;) {
    if (arena.seekerDecisionDue()) seeker_action = seeker(seekerPerception(arena));
    if (const std::optional<StepResult> r = arena.advanceFrame(hider, seeker_action)) return *r;
  }
}

}  // namespace hideseek_game
