#include "hideseek_game/geometry.h"

#include <gtest/gtest.h>

namespace hideseek_game {

TEST(Geometry, WrapAngleStaysInHalfOpenRange) {
  EXPECT_NEAR(wrapAngle(3.0 * kPi), kPi, 1e-12);
  EXPECT_NEAR(wrapAngle(-kPi), kPi, 1e-12);
  EXPECT_NEAR(wrapAngle(0.5), 0.5, 1e-12);
  EXPECT_NEAR(wrapAngle(-2.0 * kPi - 0.25), -0.25, 1e-12);
}

TEST(Geometry, CirclePushedOutOfRotatedBoxToItsSurface) {
  const Box box = Box::make({1.0, 1.0}, {2.0, 1.0}, 1.5, kPi / 4);
  Vec2 c{1.0, 1.0 + 0.3 * std::sqrt(2.0)};
  EXPECT_TRUE(pushCircleOut(box, 0.4, c));
  EXPECT_NEAR(footprintDistance(box, c), 0.4, 1e-9);
  Vec2 far{5.0, 5.0};
  EXPECT_FALSE(pushCircleOut(box, 0.4, far));
}

TEST(Geometry, SegmentThroughBoxHitsAndAboveItMisses) {
  const Box box = Box::make({0.0, 0.0}, {1.0, 1.0}, 1.5, 0.3);
  EXPECT_TRUE(segmentHitsBox(box, {-2.0, 0.0, 1.0}, {2.0, 0.0, 1.0}));
  EXPECT_FALSE(segmentHitsBox(box, {-2.0, 0.0, 1.6}, {2.0, 0.0, 1.7}));
  EXPECT_FALSE(segmentHitsBox(box, {-2.0, 2.0, 1.0}, {2.0, 2.0, 1.0}));
  EXPECT_NEAR(segmentEntry(Box::make({0.0, 0.0}, {1.0, 1.0}, 1.5, 0.0), {-2.5, 0.0, 1.0}, {2.5, 0.0, 1.0}), 0.4, 1e-9);
}

}  // namespace hideseek_game
