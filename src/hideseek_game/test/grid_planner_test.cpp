#include "hideseek_game/grid_planner.h"

#include <gtest/gtest.h>

#include <random>

#include "hideseek_game/map.h"

namespace hideseek_game {

namespace {

Layout deterministicLayout() {
  const auto spec = hideseek_game::loadMapFile(std::string(HIDESEEK_CONFIG_DIR) + "/maps/deterministic.yaml");
  std::mt19937 unused;
  return hideseek_game::makeLayout(spec, unused);
}

double clearance(const Layout& layout, Vec2 p) {
  double d = layout.half_extent - std::max(std::abs(p.x), std::abs(p.y));
  for (const auto& b : layout.obstacles) d = std::min(d, hideseek_game::footprintDistance(b, p));
  return d;
}

}  // namespace

TEST(GridPlanner, PathsNeverCrossInflatedObstacles) {
  const Layout layout = deterministicLayout();
  const GridPlanner planner(layout, 0.4, 0.1);
  std::mt19937 rng(3);
  int planned = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec2 a = planner.randomReachablePoint({0.0, -3.0}, rng), b = planner.randomReachablePoint({0.0, -3.0}, rng);
    const std::vector<Vec2> path = planner.plan(a, b);
    ASSERT_FALSE(path.empty()) << "free space of the fixed map is connected";
    ++planned;
    Vec2 from = a;
    for (const Vec2& to : path) {
      for (int k = 0; k <= 50; ++k) {
        const Vec2 p{from.x + k / 50.0 * (to.x - from.x), from.y + k / 50.0 * (to.y - from.y)};
        // Cell centres are free with the full radius; points between them within half a diagonal cell.
        ASSERT_GE(clearance(layout, p), 0.4 - 0.075) << "trial " << trial;
      }
      from = to;
    }
    EXPECT_LT(hideseek_game::distance(path.back(), b), 0.1);
  }
  EXPECT_EQ(planned, 200);
}

TEST(GridPlanner, GoesAroundTheCrossNotThroughIt) {
  const Layout layout = deterministicLayout();
  const GridPlanner planner(layout, 0.4, 0.1);
  // Either side of the cross's east arm (which spans x in [-1, 1], y in [-0.3, 0.3]).
  const Vec2 south{0.6, -1.2}, north{0.6, 1.2};
  EXPECT_FALSE(planner.lineOfSight(south, north));
  const auto path = planner.plan(south, north);
  ASSERT_GE(path.size(), 2u);
  double length = hideseek_game::distance(south, path.front());
  for (size_t i = 1; i < path.size(); ++i) length += hideseek_game::distance(path[i - 1], path[i]);
  // Around the arm tip (1 m out, plus 0.4 m radius: about 2 x 1.44 m): longer than the straight
  // 2.4 m, far shorter than a loop round the whole cross.
  EXPECT_GT(length, 2.4 + 0.3);
  EXPECT_LT(length, 4.5);
}

TEST(GridPlanner, UnreachableGoalGivesNoPath) {
  Layout layout;
  layout.half_extent = 7.0;
  // A wall across the arena splits it in two.
  layout.obstacles.push_back(hideseek_game::Box::make({0.0, 0.0}, {0.5, 14.0}, 1.5, 0.0));
  const GridPlanner planner(layout, 0.4, 0.1);
  EXPECT_TRUE(planner.plan({-3.0, 0.0}, {3.0, 0.0}).empty());
  EXPECT_FALSE(planner.plan({-3.0, 0.0}, {-3.0, 5.0}).empty());
}

}  // namespace hideseek_game
