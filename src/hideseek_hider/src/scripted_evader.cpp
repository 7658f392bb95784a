#include "hideseek_hider/scripted_evader.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/visibility.h"

namespace hideseek_hider {

using hideseek_game::Action;
using hideseek_game::AgentState;
using hideseek_game::distance;
using hideseek_game::wrapAngle;

namespace {

constexpr float kUnreachable = std::numeric_limits<float>::infinity();
constexpr double kOutOfViewPenalty = 100.0;  // m: backpedal never trades the seeker's view for distance
constexpr double kInViewMargin = 10.0 * hideseek_game::kPi / 180.0;  // keep the seeker this far inside the image
constexpr double kArrived = 0.3;                                     // m: a path point or hiding spot counts as reached
constexpr Action kLookahead[] = {Action::kBackward, Action::kStay, Action::kTurnLeft, Action::kTurnRight,
                                 Action::kForward};

}  // namespace

const char* evaderName(EvaderKind kind) {
  switch (kind) {
    case EvaderKind::kBackpedal:
      return "backpedal";
    case EvaderKind::kFlee:
      return "flee";
    case EvaderKind::kHide:
      return "hide";
    case EvaderKind::kLap:
      return "lap";
    default:
      return "random";
  }
}

std::optional<EvaderKind> evaderKind(const std::string& name) {
  for (EvaderKind k : kAllEvaders) {
    if (name == evaderName(k)) return k;
  }
  return std::nullopt;
}

ScriptedEvader::ScriptedEvader(EvaderKind kind, const hideseek_game::GameOptions& game, const EvaderOptions& options)
    : kind_(kind), game_(game), options_(options) {}

void ScriptedEvader::reset(const hideseek_game::Layout& layout) {
  goal_.reset();
  last_seen_.reset();
  path_.clear();
  lap_sign_ = 0;
  if (kind_ == EvaderKind::kRandom) return;
  if (planner_ && sameFootprints(layout, layout_)) return;
  layout_ = layout;
  planner_ = std::make_unique<GridPlanner>(layout, game_.agent_radius, options_.grid_resolution);
  const auto& grid = planner_->grid();
  clearance_.assign(static_cast<size_t>(grid.width()) * grid.height(), 0.f);
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const Vec2 c = grid.centerOf({x, y});
      double d = layout.half_extent - std::max(std::abs(c.x), std::abs(c.y));
      for (const auto& b : layout.obstacles) d = std::min(d, hideseek_game::footprintDistance(b, c));
      clearance_[grid.index({x, y})] = static_cast<float>(std::max(0.0, d - game_.agent_radius));
    }
  }
}

float ScriptedEvader::fieldAt(const std::vector<float>& field, Vec2 p) const {
  const auto& grid = planner_->grid();
  const hideseek_game::GridCell c = grid.cellOf(p);
  if (grid.isFree(c)) return field[grid.index(c)];
  // Inside the inflation (pressed against a box): the best free neighbour plus the step to it.
  float best = kUnreachable;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      const hideseek_game::GridCell n{c.x + dx, c.y + dy};
      if (grid.isFree(n))
        best = std::min(best, field[grid.index(n)] + static_cast<float>(distance(p, grid.centerOf(n))));
    }
  }
  return best;
}

bool ScriptedEvader::hiddenFrom(Vec2 seeker, Vec2 p) const {
  AgentState viewer{seeker, std::atan2(p.y - seeker.y, p.x - seeker.x), 0.0, {}};
  AgentState target{p, 0.0, 0.0, {}};
  return !hideseek_game::agentSeesAgent(viewer, target, layout_, game_);
}

bool ScriptedEvader::hiddenFromSearch(Vec2 seeker, Vec2 p) const {
  if (!hiddenFrom(seeker, p)) return false;
  if (!last_seen_) return true;
  const Vec2 mid = 0.5 * (seeker + *last_seen_);
  return hiddenFrom(mid, p) && hiddenFrom(*last_seen_, p);
}

Action ScriptedEvader::act(const EvaderObservation& o) {
  if (kind_ == EvaderKind::kRandom) {
    return static_cast<Action>(hideseek_game::hashAction(o.seed, o.step, hideseek_game::kSaltRandomHider));
  }
  // What the seeker knows of the hider, read off the true state as the seeker would perceive it.
  if ((o.step == 0 && game_.seeker_knows_spawn) || hideseek_game::agentSeesAgent(o.seeker, o.hider, layout_, game_)) {
    last_seen_ = o.hider.position;
  }
  switch (kind_) {
    case EvaderKind::kBackpedal:
      return backpedal(o);
    case EvaderKind::kFlee:
      return flee(o);
    case EvaderKind::kLap:
      return lap(o);
    default:
      return hide(o);
  }
}

Action ScriptedEvader::backpedal(const EvaderObservation& o) {
  from_seeker_ = planner_->distancesFrom(o.seeker.position);
  const auto& grid = planner_->grid();
  const double view_limit = 0.5 * game_.camera.horizontal_fov - kInViewMargin;
  // Two decision steps ahead, the seeker standing still: the first action of the best pair.
  auto play = [&](AgentState s, Action a) {
    for (int f = 0; f < game_.action_repeat; ++f) {
      hideseek_game::advanceAgent(s, a, game_.hider, game_.physics_dt, layout_, game_.agent_radius);
    }
    return s;
  };
  auto score = [&](const AgentState& s) {
    const Vec2 to_seeker = o.seeker.position - s.position;
    const double off = std::abs(wrapAngle(std::atan2(to_seeker.y, to_seeker.x) - s.yaw));
    const hideseek_game::GridCell c = grid.cellOf(s.position);
    const double clearance = grid.isFree(c) ? clearance_[grid.index(c)] : 0.0;
    return static_cast<double>(fieldAt(from_seeker_, s.position)) +
           options_.clearance_weight * std::min(clearance, options_.clearance_cap) -
           (off > view_limit ? kOutOfViewPenalty : 0.0);
  };
  Action best = Action::kBackward;
  double best_score = -std::numeric_limits<double>::infinity();
  for (Action first : kLookahead) {
    const AgentState one = play(o.hider, first);
    for (Action second : kLookahead) {
      const double v = score(play(one, second));
      if (v > best_score + 1e-9) {
        best_score = v;
        best = first;
      }
    }
  }
  return best;
}

Action ScriptedEvader::flee(const EvaderObservation& o) {
  from_seeker_ = planner_->distancesFrom(o.seeker.position);
  from_hider_ = planner_->distancesFrom(o.hider.position);
  int far = -1;
  for (size_t i = 0; i < from_seeker_.size(); ++i) {
    if (from_hider_[i] == kUnreachable || from_seeker_[i] == kUnreachable) continue;
    if (far < 0 || from_seeker_[i] > from_seeker_[far]) far = static_cast<int>(i);
  }
  if (far < 0) return Action::kStay;
  const auto& grid = planner_->grid();
  const Vec2 target = grid.centerOf({far % grid.width(), far / grid.width()});
  if (!goal_ || distance(*goal_, target) > options_.retarget_distance) {
    goal_ = target;
    path_ = planner_->plan(o.hider.position, target);
  }
  return follow(o.hider);
}

Action ScriptedEvader::hide(const EvaderObservation& o) {
  from_seeker_ = planner_->distancesFrom(o.seeker.position);
  from_hider_ = planner_->distancesFrom(o.hider.position);
  const double hider_speed =
      game_.hider.mode == hideseek_game::SpeedMode::kConstant ? game_.hider.speed : game_.hider.max_speed;
  const double ratio = game_.seeker.speed / std::max(hider_speed, 1e-6);
  // A spot is safe when the hider gets there, at its speed, well before the seeker at its own.
  auto safe_at = [&](float dh, float ds) {
    return dh != kUnreachable && (ds == kUnreachable || dh * ratio + options_.hide_margin < ds);
  };
  auto safe = [&](Vec2 p) { return safe_at(fieldAt(from_hider_, p), fieldAt(from_seeker_, p)); };
  if (goal_ && hiddenFromSearch(o.seeker.position, *goal_) && safe(*goal_) &&
      fieldAt(from_seeker_, *goal_) > options_.move_on_distance) {
    if (distance(o.hider.position, *goal_) <= kArrived) return Action::kStay;
    return follow(o.hider);
  }
  // The seeker came round, or no spot yet: a new one, among the spots the hider reaches safely
  // before the seeker, nearest first.
  const auto& grid = planner_->grid();
  std::vector<int> candidates;
  for (size_t i = 0; i < from_hider_.size(); ++i) {
    if (safe_at(from_hider_[i], from_seeker_[i])) candidates.push_back(static_cast<int>(i));
  }
  std::sort(candidates.begin(), candidates.end(),
            [&](int a, int b) { return from_hider_[a] != from_hider_[b] ? from_hider_[a] < from_hider_[b] : a < b; });
  // The safest spot within hide_search_radius that the seeker cannot see from where it is, nor
  // from where it will search; failing that, the nearest spot it cannot see from where it is.
  int best = -1;
  double best_margin = -1e9;
  for (int i : candidates) {
    if (from_hider_[i] > options_.hide_search_radius) break;
    const Vec2 p = grid.centerOf({i % grid.width(), i / grid.width()});
    if (!hiddenFromSearch(o.seeker.position, p)) continue;
    const double margin = from_seeker_[i] == kUnreachable ? 1e6 : from_seeker_[i] - ratio * from_hider_[i];
    if (margin > best_margin) {
      best_margin = margin;
      best = i;
    }
  }
  if (best < 0) {
    for (int i : candidates) {
      const Vec2 p = grid.centerOf({i % grid.width(), i / grid.width()});
      if (hiddenFrom(o.seeker.position, p)) {
        best = i;
        break;
      }
    }
  }
  if (best >= 0) {
    const Vec2 p = grid.centerOf({best % grid.width(), best / grid.width()});
    goal_ = p;
    path_ = planner_->plan(o.hider.position, p);
    if (distance(o.hider.position, p) <= kArrived) return Action::kStay;
    return follow(o.hider);
  }
  // Nowhere to hide in time: run.
  goal_.reset();
  return flee(o);
}

Vec2 ScriptedEvader::lapTarget(Vec2 p, int sign) const {
  const double angle = std::atan2(p.y, p.x) + sign * options_.lap_step_deg * hideseek_game::kPi / 180.0;
  const Vec2 direction{std::cos(angle), std::sin(angle)};
  // The ring's point ahead, moved inwards where reaching it means a detour into a pocket.
  for (double r = options_.lap_radius; r > 0.5; r -= 0.5) {
    const Vec2 target = r * direction;
    const float way = fieldAt(from_hider_, target);
    if (way != kUnreachable && way <= options_.lap_detour * distance(p, target)) return target;
  }
  return options_.lap_radius * direction;
}

Action ScriptedEvader::lap(const EvaderObservation& o) {
  from_seeker_ = planner_->distancesFrom(o.seeker.position);
  from_hider_ = planner_->distancesFrom(o.hider.position);
  const float here = fieldAt(from_seeker_, o.hider.position);
  // The sense that leads away from the seeker; turn round when the seeker is ahead.
  if (lap_sign_ == 0) {
    lap_sign_ =
        fieldAt(from_seeker_, lapTarget(o.hider.position, +1)) >= fieldAt(from_seeker_, lapTarget(o.hider.position, -1))
            ? +1
            : -1;
  } else if (fieldAt(from_seeker_, lapTarget(o.hider.position, lap_sign_)) < here) {
    lap_sign_ = -lap_sign_;
  }
  const Vec2 target = lapTarget(o.hider.position, lap_sign_);
  if (!goal_ || distance(*goal_, target) > 0.5 * options_.retarget_distance) {
    goal_ = target;
    path_ = planner_->plan(o.hider.position, target);
  }
  return follow(o.hider, /*backward=*/true);
}

Action ScriptedEvader::follow(const AgentState& hider, bool backward) {
  const Vec2 here = hider.position;
  while (path_.size() > 1 && distance(here, path_.front()) <= kArrived) path_.erase(path_.begin());
  if (path_.empty()) return Action::kStay;
  size_t target = 0;
  while (target + 1 < path_.size() && planner_->lineOfSight(here, path_[target + 1])) ++target;
  const Vec2 t = path_[target];
  const double heading = backward ? hider.yaw + hideseek_game::kPi : hider.yaw;
  const double error = wrapAngle(std::atan2(t.y - here.y, t.x - here.x) - heading);
  const double turn_step = game_.hider.turn_rate * game_.stepDuration();
  if (std::abs(error) <= 0.5 * turn_step) return backward ? Action::kBackward : Action::kForward;
  return error > 0 ? Action::kTurnLeft : Action::kTurnRight;
}

}  // namespace hideseek_hider
