#include "hideseek_seeker/seeker_policy.h"

#include <cmath>
#include <cstddef>
#include <utility>

namespace hideseek_seeker {

using hideseek_game::distance;
using hideseek_game::kPi;
using hideseek_game::wrapAngle;

SeekerOptions seekerOptionsFor(const hideseek_game::VariantConfig& variant, double grid_resolution) {
  SeekerOptions o;
  o.type = variant.seeker_policy == "stochastic" ? SeekerPolicyType::kStochastic : SeekerPolicyType::kDeterministic;
  o.radius = variant.game.agent_radius;
  o.turn_per_step = variant.game.seeker.turn_rate * variant.game.physics_dt * variant.game.seeker_decision_frames;
  o.turn_while_moving = variant.game.seeker_steering == hideseek_game::SeekerSteering::kTurnWhileMoving;
  o.move_angle = variant.game.seeker_move_angle;
  o.path_following = variant.game.seeker_path_following;
  o.grid_resolution = grid_resolution;
  return o;
}

const char* modeName(SeekerMode mode) {
  switch (mode) {
    case SeekerMode::kChase:
      return "chase";
    case SeekerMode::kLastKnown:
      return "last_known";
    case SeekerMode::kWander:
      return "wander";
    default:
      return "patrol";
  }
}

void SeekerPolicy::reset(const Layout& layout, uint32_t seed) {
  // A fixed map keeps its grid from episode to episode; a new layout is planned afresh.
  if (!planner_ || !sameFootprints(layout, planned_layout_)) {
    planner_ = std::make_unique<GridPlanner>(layout, options_.radius, options_.grid_resolution);
    planned_layout_ = layout;
  }
  waypoints_ = layout.waypoints;
  next_waypoint_ = 0;
  last_known_.reset();
  goal_.reset();
  path_.clear();
  target_.reset();
  afresh_cell_.reset();
  mode_ = options_.type == SeekerPolicyType::kDeterministic ? SeekerMode::kPatrol : SeekerMode::kWander;
  rng_.seed(seed ^ 0x5eed5eedu);
  last_action_ = Action::kStay;
}

void SeekerPolicy::setGoal(const AgentState& pose, Vec2 goal) {
  // Replan only when the goal moved: a chase re-targets every step, but a straight line needs no search.
  if (goal_ && distance(*goal_, goal) < options_.grid_resolution && !path_.empty()) return;
  goal_ = goal;
  ++plans_;
  if (planner_->lineOfSight(pose.position, goal)) {
    path_ = {goal};
  } else {
    path_ = planner_->plan(pose.position, goal);
    // no_backtrack's once a cell holds for one searched plan: a new goal searched for may plan afresh
    // where the last one did (a goal in a straight line, as a chase's often is, does not reopen it,
    // so a chase searches at most twice for each search of its own)
    afresh_cell_.reset();
  }
}

namespace {

// The turn an action makes: a forward turn counts as its turn.
Action turnOf(Action a) {
  if (a == Action::kForwardLeft) return Action::kTurnLeft;
  if (a == Action::kForwardRight) return Action::kTurnRight;
  return a;
}

}  // namespace

Action SeekerPolicy::steerTowards(const AgentState& pose, Vec2 target) const {
  const double bearing = std::atan2(target.y - pose.position.y, target.x - pose.position.x);
  const double error = wrapAngle(bearing - pose.yaw);
  // Turn while more than half a turn step off, so the heading error stays within a half step.
  if (std::abs(error) <= 0.5 * options_.turn_per_step) return Action::kForward;
  Action turn = error > 0 ? Action::kTurnLeft : Action::kTurnRight;
  // Never undo the previous turn. When the target flips between two sides from one step to the
  // next (a hider stepping forward and back with the bearing near the middle between two
  // reachable headings, or a path that changes corner), undoing would keep the seeker turning
  // left, right, left, ... on the spot for good. Instead it moves forward when the target is
  // ahead, which changes the geometry and still closes in, or keeps turning the same way.
  const Action last_turn = turnOf(last_action_);
  const Action back = last_turn == Action::kTurnLeft ? Action::kTurnRight : Action::kTurnLeft;
  const bool just_turned = last_turn == Action::kTurnLeft || last_turn == Action::kTurnRight;
  if (just_turned && turn == back) {
    if (std::abs(error) < 0.5 * kPi) return Action::kForward;
    turn = last_turn;
  }
  // Game v3: a target within move_angle of the heading is approached while turning.
  if (options_.turn_while_moving && std::abs(error) <= options_.move_angle) {
    return turn == Action::kTurnLeft ? Action::kForwardLeft : Action::kForwardRight;
  }
  return turn;
}

Action SeekerPolicy::act(const SeekerPerception& p) {
  last_action_ = decide(p);
  return last_action_;
}

Action SeekerPolicy::decide(const SeekerPerception& p) {
  target_.reset();
  if (!planner_) return Action::kStay;
  const Vec2 here = p.pose.position;
  if (p.hider_position) {
    mode_ = SeekerMode::kChase;
    last_known_ = *p.hider_position;
    setGoal(p.pose, *p.hider_position);
  } else if (last_known_ && distance(here, *last_known_) > options_.goal_tolerance) {
    mode_ = SeekerMode::kLastKnown;
    setGoal(p.pose, *last_known_);
  } else {
    last_known_.reset();
    if (options_.type == SeekerPolicyType::kDeterministic && !waypoints_.empty()) {
      if (mode_ != SeekerMode::kPatrol) {
        // Resume the round from the nearest waypoint rather than walking back to the old one.
        size_t best = 0;
        for (size_t i = 1; i < waypoints_.size(); ++i) {
          if (distance(here, waypoints_[i]) < distance(here, waypoints_[best])) best = i;
        }
        next_waypoint_ = best;
        goal_.reset();
      }
      mode_ = SeekerMode::kPatrol;
      if (distance(here, waypoints_[next_waypoint_]) <= options_.goal_tolerance) {
        next_waypoint_ = (next_waypoint_ + 1) % waypoints_.size();
      }
      setGoal(p.pose, waypoints_[next_waypoint_]);
    } else {
      if (mode_ != SeekerMode::kWander || !goal_ || distance(here, *goal_) <= options_.goal_tolerance ||
          path_.empty()) {
        goal_.reset();
        setGoal(p.pose, planner_->randomReachablePoint(here, rng_));
      }
      mode_ = SeekerMode::kWander;
    }
  }
  // Follow the path: drop reached points, then head for the farthest one in a straight line.
  const double reach = 0.5 * options_.goal_tolerance;
  const bool no_backtrack = options_.path_following == hideseek_game::SeekerPathFollowing::kNoBacktrack;
  if (no_backtrack) {
    size_t passed = 0;  // every point up to the last one within reach; the goal, last, stays
    for (size_t i = 0; i + 1 < path_.size(); ++i) {
      if (distance(here, path_[i]) <= reach) passed = i + 1;
    }
    path_.erase(path_.begin(), path_.begin() + static_cast<std::ptrdiff_t>(passed));
  } else {
    while (path_.size() > 1 && distance(here, path_.front()) <= reach) path_.erase(path_.begin());
  }
  if (path_.empty()) return Action::kStay;
  // next_point judges a straight line from where the seeker stands; no_backtrack from the centre of
  // its grid cell, where the planner starts a plan, so that a line does not come and go with every
  // centimetre moved (its plan afresh, below, then holds while the seeker stays in the cell).
  const hideseek_game::FreeSpaceGrid& grid = planner_->grid();
  const Vec2 from = no_backtrack ? grid.centerOf(grid.cellOf(here)) : here;
  size_t target = 0;
  while (target + 1 < path_.size() && planner_->lineOfSight(from, path_[target + 1])) ++target;
  if (no_backtrack) {  // the points before the one it heads for are passed: it does not come back for them
    path_.erase(path_.begin(), path_.begin() + static_cast<std::ptrdiff_t>(target));
    target = 0;
    // The point it heads for has lost its straight line (a turn taken while moving cut a corner, a
    // slide along a wall): it plans afresh from here to the same goal, rather than drive into the
    // obstacle for good, and heads for the farthest point of the new path in sight (the planner
    // starts from this cell's centre, so its first point is). At most once in a grid cell: a new
    // plan's first point may lie within reach, be dropped at the next decision and leave a hidden
    // one again, and planning again there would search every frame to the same end. From a cell
    // the grid counts as blocked, touching an obstacle, no line is clear; there, and where no path
    // is found, it keeps the path it has.
    const hideseek_game::GridCell cell = grid.cellOf(here);
    const bool planned_here = afresh_cell_ && afresh_cell_->x == cell.x && afresh_cell_->y == cell.y;
    if (goal_ && !planned_here && planner_->isFree(here) && !planner_->lineOfSight(from, path_.front())) {
      std::vector<Vec2> fresh = planner_->plan(here, *goal_);
      ++plans_;
      afresh_cell_ = cell;
      if (!fresh.empty()) path_ = std::move(fresh);
      while (target + 1 < path_.size() && planner_->lineOfSight(from, path_[target + 1])) ++target;
      path_.erase(path_.begin(), path_.begin() + static_cast<std::ptrdiff_t>(target));
      target = 0;
    }
  }
  target_ = path_[target];
  return steerTowards(p.pose, path_[target]);
}

}  // namespace hideseek_seeker
