#include "hideseek_seeker/seeker_policy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <set>
#include <vector>

#include "hideseek_game/arena.h"
#include "hideseek_game/visibility.h"
#include "hideseek_seeker/seeker_node.h"

namespace hideseek_seeker {

namespace {

using hideseek_game::GameOptions;

const std::string kConfig = HIDESEEK_CONFIG_DIR;

// The game as the shipped game file gives it: the options structs hold zeros until one is loaded.
GameOptions shippedGame() {
  return hideseek_game::loadVariantConfig(kConfig + "/game.yaml", kConfig + "/variants/basic.yaml").game;
}

Layout deterministicLayout() {
  const auto spec = hideseek_game::loadMapFile(kConfig + "/maps/deterministic.yaml");
  std::mt19937 unused;
  return hideseek_game::makeLayout(spec, unused);
}

// Moves the seeker by its own action for one decision step, as the world would.
void advance(AgentState& s, Action a, const Layout& layout) {
  static const hideseek_game::MotionOptions m = shippedGame().seeker;  // 1.5 m/s, 180 deg/s
  for (int i = 0; i < 6; ++i) hideseek_game::advanceAgent(s, a, m, 0.02, layout, 0.4);
}

// Both rules of seeker.path_following, the shipped games' first.
const hideseek_game::SeekerPathFollowing kPathFollowings[] = {hideseek_game::SeekerPathFollowing::kNextPoint,
                                                              hideseek_game::SeekerPathFollowing::kNoBacktrack};

// A seeker of `variant` that follows its path by `following`, reset onto `layout` with `seed`.
SeekerPolicy seekerFollowing(hideseek_game::VariantConfig variant, hideseek_game::SeekerPathFollowing following,
                             const Layout& layout, uint32_t seed) {
  variant.game.seeker_path_following = following;
  SeekerPolicy seeker(seekerOptionsFor(variant));
  seeker.reset(layout, seed);
  return seeker;
}

}  // namespace

TEST(SeekerPolicy, ReachesAGoalBehindTheCrossFromLastKnownPosition) {
  const Layout layout = deterministicLayout();
  SeekerPolicy seeker({});
  seeker.reset(layout, 1);
  // South of the cross's east arm; the hider was glimpsed once north of it, then never again.
  AgentState s{{0.6, -1.2}, hideseek_game::kPi / 2, 0.0, {}};
  const Vec2 behind{0.6, 1.2};
  seeker.act({s, behind});
  for (int step = 0; step < 200 && hideseek_game::distance(s.position, behind) > 0.5; ++step) {
    const Action a = seeker.act({s, std::nullopt});
    if (hideseek_game::distance(s.position, behind) > 0.5) EXPECT_EQ(seeker.mode(), SeekerMode::kLastKnown);
    advance(s, a, layout);
  }
  EXPECT_LE(hideseek_game::distance(s.position, behind), 0.5);
  // Once there and still seeing nothing, it goes back to its patrol.
  seeker.act({s, std::nullopt});
  EXPECT_EQ(seeker.mode(), SeekerMode::kPatrol);
}

// The planner is kept across episodes on the same map; a seeker reset onto another layout
// must plan around that layout's obstacles, and back again.
TEST(SeekerPolicy, PlansOnTheLayoutOfTheCurrentEpisode) {
  Layout open;
  open.waypoints = {{0.0, 0.0}};
  const Layout cross = deterministicLayout();
  const AgentState s{{0.6, -1.2}, hideseek_game::kPi / 2, 0.0, {}};
  const Vec2 behind{0.6, 1.2};
  auto pathLength = [&](SeekerPolicy& seeker) {
    seeker.act({s, behind});
    double length = 0.0;
    Vec2 from = s.position;
    for (const Vec2& p : seeker.path()) length += hideseek_game::distance(from, p), from = p;
    return length;
  };
  SeekerPolicy seeker({});
  seeker.reset(open, 1);
  EXPECT_NEAR(pathLength(seeker), 2.4, 0.2) << "straight across open ground";
  seeker.reset(cross, 2);
  EXPECT_GT(pathLength(seeker), 2.7) << "around the cross's east arm";
  seeker.reset(cross, 3);
  EXPECT_GT(pathLength(seeker), 2.7);
  seeker.reset(open, 4);
  EXPECT_NEAR(pathLength(seeker), 2.4, 0.2);
}

TEST(SeekerPolicy, ChasesOnSightAndTurnsTowardsTheHider) {
  const Layout layout = deterministicLayout();
  SeekerPolicy seeker({});
  seeker.reset(layout, 1);
  const AgentState s{{0.0, -4.0}, 0.0, 0.0, {}};  // between the cross and the south wall segment, facing east
  EXPECT_EQ(seeker.act({s, Vec2{0.0, -2.0}}), Action::kTurnLeft);  // hider to its left
  EXPECT_EQ(seeker.mode(), SeekerMode::kChase);
  EXPECT_EQ(seeker.act({s, Vec2{3.0, -4.0}}), Action::kForward);  // hider straight ahead
  EXPECT_EQ(seeker.act({s, Vec2{2.0, -4.8}}), Action::kTurnRight);
}

TEST(SeekerPolicy, DeterministicSeekerPatrolsWaypointsInOrder) {
  const Layout layout = deterministicLayout();
  SeekerPolicy seeker({});
  seeker.reset(layout, 1);
  AgentState s{layout.waypoints[0], 0.0, 0.0, {}};
  std::vector<size_t> visited;
  for (int step = 0; step < 3000 && visited.size() < 4; ++step) {
    advance(s, seeker.act({s, std::nullopt}), layout);
    for (size_t w = 0; w < layout.waypoints.size(); ++w) {
      if (hideseek_game::distance(s.position, layout.waypoints[w]) < 0.5 && (visited.empty() || visited.back() != w)) {
        visited.push_back(w);
      }
    }
  }
  ASSERT_GE(visited.size(), 4u) << "patrol stalled";
  for (size_t k = 1; k < visited.size(); ++k) EXPECT_EQ(visited[k], (visited[k - 1] + 1) % layout.waypoints.size());
}

TEST(SeekerPolicy, StochasticSeekerWandersToVariedPointsAndChasesOnSight) {
  const Layout layout = deterministicLayout();
  SeekerOptions o;
  o.type = SeekerPolicyType::kStochastic;
  SeekerPolicy seeker(o);
  seeker.reset(layout, 42);
  AgentState s{{-6.0, -6.0}, 0.0, 0.0, {}};
  std::set<std::pair<int, int>> goals;
  for (int step = 0; step < 1500; ++step) {
    advance(s, seeker.act({s, std::nullopt}), layout);
    EXPECT_EQ(seeker.mode(), SeekerMode::kWander);
    if (seeker.goal())
      goals.insert({static_cast<int>(std::floor(seeker.goal()->x)), static_cast<int>(std::floor(seeker.goal()->y))});
  }
  EXPECT_GE(goals.size(), 5u) << "goals should spread over the map";
  seeker.act({s, Vec2{s.position.x + 2.0, s.position.y}});
  EXPECT_EQ(seeker.mode(), SeekerMode::kChase);
  // Two seekers with different episode seeds wander differently.
  SeekerPolicy other(o);
  other.reset(layout, 43);
  AgentState t{{-6.0, -6.0}, 0.0, 0.0, {}};
  other.act({t, std::nullopt});
  SeekerPolicy again(o);
  again.reset(layout, 42);
  again.act({AgentState{{-6.0, -6.0}, 0.0, 0.0, {}}, std::nullopt});
  EXPECT_NE(other.goal()->x, again.goal()->x);
}

TEST(SeekerPerception, HiderPositionOnlyWhileSeen) {
  hideseek_msgs::SeekerObservationBatch batch;
  batch.num_arenas = 2;
  batch.pose.resize(2);
  batch.sees_hider = {0, 1};
  batch.hider_position.resize(2);
  batch.hider_position[0].x = 3.0;  // a world that leaked ground truth: must be ignored
  batch.hider_position[1].x = 4.0;
  EXPECT_FALSE(toPerception(batch, 0).hider_position.has_value());
  ASSERT_TRUE(toPerception(batch, 1).hider_position.has_value());
  EXPECT_EQ(toPerception(batch, 1).hider_position->x, 4.0);
}

TEST(SeekerPolicy, DeterministicSeekerCatchesAStandingHiderItCanSee) {
  // In the open, the chase must end in capture.
  Layout open;
  open.half_extent = 7.0;
  open.waypoints = {{0.0, 0.0}};
  const GameOptions g = shippedGame();
  SeekerPolicy seeker({});
  seeker.reset(open, 0);
  AgentState s{{-5.0, -5.0}, 2.0, 0.0, {}};
  const AgentState hider{{4.0, 3.0}, 0.0, 0.0, {}};
  int step = 0;
  for (; step < 400 && hideseek_game::distance(s.position, hider.position) > g.capture_distance; ++step) {
    const bool sees = hideseek_game::agentSeesAgent(s, hider, open, g);
    advance(s, seeker.act({s, sees ? std::optional<Vec2>(hider.position) : std::nullopt}), open);
  }
  EXPECT_LE(hideseek_game::distance(s.position, hider.position), g.capture_distance) << "after " << step << " steps";
}

// seeker.path_following (docs/calibration.md, "The scripted seeker's stalls"), game v3's wandering
// seeker moving frame by frame: the point it heads for is always on its path; under no_backtrack it
// is the path's first point, and until the seeker plans afresh (plans() counts) the path only loses
// points from its front, so the seeker never turns back for a point it has passed.
TEST(SeekerPolicy, UnderNoBacktrackTheSeekerNeverTurnsBackForAPassedPoint) {
  const auto v3 =
      hideseek_game::loadVariantConfig(kConfig + "/game_v3.yaml", kConfig + "/variants/stochasticseeker.yaml");
  const Layout layout = deterministicLayout();
  for (const auto following : kPathFollowings) {
    const bool no_backtrack = following == hideseek_game::SeekerPathFollowing::kNoBacktrack;
    SCOPED_TRACE(no_backtrack ? "no_backtrack" : "next_point");
    SeekerPolicy seeker = seekerFollowing(v3, following, layout, 7);
    const GridPlanner planner(layout, seekerOptionsFor(v3).radius, seekerOptionsFor(v3).grid_resolution);
    const hideseek_game::FreeSpaceGrid& grid = planner.grid();
    AgentState s{{-6.0, -6.0}, 0.0, 0.0, {}};
    std::vector<Vec2> before;
    size_t plans_before = 0;
    std::optional<Vec2> goal_before;
    std::optional<hideseek_game::GridCell> afresh_in;  // the cell of the last frame's plan afresh
    int targets = 0, passed = 0, afresh = 0;
    for (int frame = 0; frame < 6000; ++frame) {
      const hideseek_game::GridCell cell = grid.cellOf(s.position);
      const Action a = seeker.act({s, std::nullopt});
      const std::vector<Vec2>& path = seeker.path();
      if (const auto target = seeker.target()) {
        ++targets;
        const auto on_path =
            std::find_if(path.begin(), path.end(), [&](Vec2 p) { return p.x == target->x && p.y == target->y; });
        ASSERT_NE(on_path, path.end()) << "frame " << frame << ": the target is not on the path";
        if (no_backtrack) {
          EXPECT_EQ(on_path, path.begin()) << "frame " << frame << ": a point before the target is kept";
        }
      }
      if (no_backtrack && seeker.plans() == plans_before) {
        // The same plan: what is left is the end of what was there.
        ASSERT_LE(path.size(), before.size()) << "frame " << frame << ": the path grew without a plan";
        EXPECT_TRUE(std::equal(path.begin(), path.end(), before.end() - static_cast<std::ptrdiff_t>(path.size()),
                               [](Vec2 p, Vec2 q) { return p.x == q.x && p.y == q.y; }))
            << "frame " << frame << ": the path regained a point it had dropped";
        passed += static_cast<int>(before.size() - path.size());
      }
      // A plan for the goal it already had is a plan afresh (no_backtrack's lost point): never two
      // frames running in one grid cell, which would be a new search every frame.
      const bool same_goal =
          goal_before && seeker.goal() && goal_before->x == seeker.goal()->x && goal_before->y == seeker.goal()->y;
      const bool planned_afresh = seeker.plans() > plans_before && same_goal;
      EXPECT_FALSE(planned_afresh && afresh_in && afresh_in->x == cell.x && afresh_in->y == cell.y)
          << "frame " << frame << ": planned afresh again in the same cell";
      if (!no_backtrack) {
        EXPECT_FALSE(planned_afresh) << "frame " << frame << ": next_point planned afresh for the same goal";
      }
      afresh += planned_afresh;
      afresh_in.reset();
      if (planned_afresh) afresh_in = cell;
      before = path;
      plans_before = seeker.plans();
      goal_before = seeker.goal();
      hideseek_game::advanceAgent(s, a, v3.game.seeker, v3.game.physics_dt, layout, v3.game.agent_radius);
    }
    EXPECT_GT(targets, 5000) << "the seeker should be on its way nearly every frame";
    if (no_backtrack) {
      EXPECT_GT(passed, 10) << "the seeker should pass points on its paths";
      // a search on at most one frame in 20 (91 here when written)
      EXPECT_LT(afresh, 300) << "plans afresh in 6000 frames";
    }
  }
}

// Under no_backtrack, a seeker whose point to head for has lost its straight line (here: moved
// behind the cross's arm between two decisions, as a turn taken while moving or a slide can carry
// it) plans afresh to the same goal and heads for a point it sees; under next_point it keeps
// heading for the hidden point, as the shipped games always did (what they recorded replays).
TEST(SeekerPolicy, UnderNoBacktrackTheSeekerPlansAfreshWhenItsPointIsOutOfSight) {
  const auto v3 = hideseek_game::loadVariantConfig(kConfig + "/game_v3.yaml", kConfig + "/variants/basic.yaml");
  const Layout layout = deterministicLayout();
  const SeekerOptions options = seekerOptionsFor(v3);
  const GridPlanner sight(layout, options.radius, options.grid_resolution);
  // South of the cross's east arm, in a cell the grid counts free, the hider glimpsed once north of
  // it: a path round the arm's end.
  const AgentState start{{0.6, -1.6}, hideseek_game::kPi / 2, 0.0, {}};
  const Vec2 behind{0.6, 1.2};
  ASSERT_TRUE(sight.isFree(start.position));
  for (const auto following : kPathFollowings) {
    const bool no_backtrack = following == hideseek_game::SeekerPathFollowing::kNoBacktrack;
    SCOPED_TRACE(no_backtrack ? "no_backtrack" : "next_point");
    SeekerPolicy seeker = seekerFollowing(v3, following, layout, 1);
    seeker.act({start, behind});
    ASSERT_TRUE(seeker.target().has_value());
    const Vec2 point = *seeker.target();
    ASSERT_TRUE(sight.lineOfSight(start.position, point));
    // The nearest free place, within 2 m, from which every point of its path is hidden and the
    // goal still reachable.
    const std::vector<Vec2> path = seeker.path();
    const auto hidden = [&](Vec2 q) {
      return std::none_of(path.begin(), path.end(), [&](Vec2 pt) { return sight.lineOfSight(q, pt); });
    };
    std::optional<Vec2> moved;
    for (double r = 0.1; r <= 2.0 && !moved; r += 0.1) {
      for (int k = 0; k < 72 && !moved; ++k) {
        const Vec2 q{start.position.x + r * std::cos(k * hideseek_game::kPi / 36),
                     start.position.y + r * std::sin(k * hideseek_game::kPi / 36)};
        const Vec2 centre = sight.grid().centerOf(sight.grid().cellOf(q));
        if (sight.isFree(q) && hidden(q) && hidden(centre) && !sight.plan(q, behind).empty()) moved = q;
      }
    }
    ASSERT_TRUE(moved.has_value()) << "no place near the start hides the path from (" << point.x << ", " << point.y
                                   << ") on";
    const size_t plans = seeker.plans();
    seeker.act({AgentState{*moved, start.yaw, 0.0, {}}, std::nullopt});  // still heading for `behind`
    ASSERT_TRUE(seeker.target().has_value());
    const Vec2 now = *seeker.target();
    if (no_backtrack) {
      EXPECT_EQ(seeker.plans(), plans + 1) << "one new plan";
      // in sight from where it stands or from the centre of its grid cell, where the planner starts
      const Vec2 centre = sight.grid().centerOf(sight.grid().cellOf(*moved));
      EXPECT_TRUE(sight.lineOfSight(*moved, now) || sight.lineOfSight(centre, now))
          << "it heads for (" << now.x << ", " << now.y << "), out of sight";
      ASSERT_TRUE(seeker.goal().has_value());
      EXPECT_NEAR(hideseek_game::distance(*seeker.goal(), behind), 0.0, 1e-9) << "the same goal";
      // Back at the start it glimpses the hider elsewhere behind the arm: a new goal, whose path is
      // hidden from that cell too, and searched for. Back there, it plans afresh again, for the new
      // goal: once a cell holds for one searched plan.
      const Vec2 cell_centre = sight.grid().centerOf(sight.grid().cellOf(*moved));
      std::optional<Vec2> elsewhere;
      for (double x = -0.6; x <= 2.4 && !elsewhere; x += 0.3) {
        const Vec2 goal{x, 1.4};
        if (hideseek_game::distance(goal, behind) < 2 * options.grid_resolution || !sight.isFree(goal)) continue;
        const std::vector<Vec2> other = sight.plan(start.position, goal);
        if (other.empty() || sight.lineOfSight(start.position, goal)) continue;
        if (std::none_of(other.begin(), other.end(), [&](Vec2 pt) {
              return sight.lineOfSight(*moved, pt) || sight.lineOfSight(cell_centre, pt);
            })) {
          elsewhere = goal;
        }
      }
      ASSERT_TRUE(elsewhere.has_value()) << "no goal behind the arm whose path that cell cannot see";
      const size_t before_new_goal = seeker.plans();
      seeker.act({start, *elsewhere});
      const size_t replanned = seeker.plans();
      ASSERT_EQ(replanned, before_new_goal + 1) << "the new goal's own plan, and no plan afresh at the start";
      seeker.act({AgentState{*moved, start.yaw, 0.0, {}}, std::nullopt});  // heading for `elsewhere`
      EXPECT_EQ(seeker.plans(), replanned + 1) << "a new goal's plan afresh in the same cell";
      ASSERT_TRUE(seeker.target().has_value());
      EXPECT_TRUE(sight.lineOfSight(*moved, *seeker.target()) || sight.lineOfSight(cell_centre, *seeker.target()))
          << "it heads for (" << seeker.target()->x << ", " << seeker.target()->y << "), out of sight";
    } else {
      EXPECT_EQ(seeker.plans(), plans) << "next_point plans nothing new for the same goal";
      EXPECT_FALSE(sight.lineOfSight(*moved, now)) << "next_point keeps heading for a point out of sight";
    }
  }
}

}  // namespace hideseek_seeker
