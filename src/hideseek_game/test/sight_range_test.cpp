#include <gtest/gtest.h>

#include <cmath>

#include "hideseek_game/visibility.h"

namespace hideseek_game {
namespace {

Layout emptyArena() {
  Layout l;
  l.half_extent = 7.0;
  return l;
}

TEST(SightRange, StopsAtTheWalls) {
  const Layout l = emptyArena();
  EXPECT_NEAR(sightRange({0, 0}, 0.0, 1.0, l, 50.0), 7.0, 1e-9);
  EXPECT_NEAR(sightRange({2, 1}, M_PI, 1.0, l, 50.0), 9.0, 1e-9);
  EXPECT_NEAR(sightRange({0, 0}, M_PI / 4, 1.0, l, 50.0), 7.0 * std::sqrt(2.0), 1e-9);  // into the corner
  EXPECT_NEAR(sightRange({0, 0}, 0.0, 1.0, l, 3.0), 3.0, 1e-9);
}

TEST(SightRange, StopsAtTheFirstObstacleUnlessItLooksOverIt) {
  Layout l = emptyArena();
  l.obstacles.push_back(Box::make({3.0, 0.0}, {2.0, 2.0}, 1.5, 0.0));  // faces at x = 2 and 4
  l.obstacles.push_back(Box::make({5.5, 0.0}, {1.0, 1.0}, 1.5, 0.0));
  EXPECT_NEAR(sightRange({0, 0}, 0.0, 1.0, l, 50.0), 2.0, 1e-9);
  EXPECT_NEAR(sightRange({0, 0}, M_PI / 2, 1.0, l, 50.0), 7.0, 1e-9);  // beside it
  // A rotated box: a 45-degree square of half-diagonal sqrt(2) centred 4 m ahead meets the ray
  // at its corner, 4 - sqrt(2) m away.
  Layout r = emptyArena();
  r.obstacles.push_back(Box::make({0.0, 4.0}, {2.0, 2.0}, 1.5, M_PI / 4));
  EXPECT_NEAR(sightRange({0, 0}, M_PI / 2, 1.0, r, 50.0), 4.0 - std::sqrt(2.0), 1e-9);
  // A low box does not stop a camera above it.
  Layout low = emptyArena();
  low.obstacles.push_back(Box::make({3.0, 0.0}, {2.0, 2.0}, 0.5, 0.0));
  EXPECT_NEAR(sightRange({0, 0}, 0.0, 1.0, low, 50.0), 7.0, 1e-9);
}

}  // namespace
}  // namespace hideseek_game
