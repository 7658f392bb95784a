#include <gtest/gtest.h>

#include <cmath>

#include "hideseek_game/agent.h"
#include "test_util.h"

namespace hideseek_game {

namespace {

constexpr double kDt = 0.02;
constexpr int kRepeat = 6;

Layout emptyArena() {
  Layout l;
  l.half_extent = 7.0;
  return l;
}

// The hider's motion as the shipped game file gives it (2 m/s, 180 deg/s; accelerate mode 2 m/s^2
// up to 4 m/s): the structs themselves hold zeros until a game file is loaded.
MotionOptions shippedHider() { return test::loadVariant("basic").game.hider; }

void step(AgentState& a, Action act, const MotionOptions& m, const Layout& l, int frames = kRepeat) {
  for (int i = 0; i < frames; ++i) advanceAgent(a, act, m, kDt, l, 0.4);
}

}  // namespace

TEST(Kinematics, ConstantModeMovesAtItsSpeedBothWays) {
  for (double speed : {2.0, 1.0, 1.5}) {
    MotionOptions m = shippedHider();
    m.speed = speed;
    AgentState a;
    step(a, Action::kForward, m, emptyArena());
    EXPECT_NEAR(a.position.x, speed * 0.12, 1e-9);
    step(a, Action::kBackward, m, emptyArena());
    EXPECT_NEAR(a.position.x, 0.0, 1e-9);
    step(a, Action::kStay, m, emptyArena());
    EXPECT_NEAR(a.position.x, 0.0, 1e-9);
  }
}

TEST(Kinematics, TurnsAt180DegreesPerSecondWithoutMoving) {
  MotionOptions m = shippedHider();
  AgentState a;
  step(a, Action::kTurnLeft, m, emptyArena());
  EXPECT_NEAR(a.yaw, kPi * 0.12, 1e-9);
  step(a, Action::kTurnRight, m, emptyArena(), 2 * kRepeat);
  EXPECT_NEAR(a.yaw, -kPi * 0.12, 1e-9);
  EXPECT_NEAR(norm(a.position), 0.0, 1e-12);
}

TEST(Kinematics, AccelerateModeRampsUpCapsAndCoastsToRest) {
  MotionOptions m = shippedHider();
  m.mode = SpeedMode::kAccelerate;
  AgentState a;
  a.position = {-6.0, 0.0};
  step(a, Action::kForward, m, emptyArena(), 50);  // 1 s at 2 m/s^2
  EXPECT_NEAR(a.speed, 2.0, 1e-9);
  step(a, Action::kForward, m, emptyArena(), 100);  // would reach 6 m/s
  EXPECT_NEAR(a.speed, 4.0, 1e-9);
  step(a, Action::kTurnLeft, m, emptyArena(), 50);  // any other action decelerates
  EXPECT_NEAR(a.speed, 2.0, 1e-9);
  step(a, Action::kStay, m, emptyArena(), 100);
  EXPECT_EQ(a.speed, 0.0);
  step(a, Action::kBackward, m, emptyArena(), 25);
  EXPECT_NEAR(a.speed, -1.0, 1e-9);
}

TEST(Kinematics, SlidesAlongWallWithoutPassingThrough) {
  MotionOptions m = shippedHider();
  AgentState a;
  a.position = {6.5, 0.0};
  a.yaw = kPi / 4;  // into the +x wall at 45 degrees
  step(a, Action::kForward, m, emptyArena(), 50);
  EXPECT_NEAR(a.position.x, 7.0 - 0.4, 1e-9);
  EXPECT_NEAR(a.position.y, 2.0 * std::sin(kPi / 4) * 1.0, 1e-6);  // the tangential part survives
}

TEST(Kinematics, SlidesAlongRotatedBoxAndNeverEntersIt) {
  Layout l = emptyArena();
  const Box box = Box::make({0.0, 0.0}, {4.0, 1.0}, 1.5, kPi / 6);
  l.obstacles.push_back(box);
  MotionOptions m = shippedHider();
  AgentState a;
  a.position = {0.0, -2.0};
  a.yaw = kPi / 2;  // straight at the box's long side
  for (int i = 0; i < 300; ++i) {
    advanceAgent(a, Action::kForward, m, kDt, l, 0.4);
    ASSERT_GE(footprintDistance(box, a.position), 0.4 - 1e-9) << "frame " << i;
  }
  // Pushed along the slanted face: it moved sideways, not stuck where it hit.
  EXPECT_GT(std::abs(a.position.x), 1.0);
}

TEST(Kinematics, AccelerateModeLosesSpeedIntoAWall) {
  MotionOptions m = shippedHider();
  m.mode = SpeedMode::kAccelerate;
  AgentState a;
  a.position = {6.4, 0.0};
  a.speed = 4.0;
  step(a, Action::kForward, m, emptyArena());
  EXPECT_NEAR(a.position.x, 6.6, 1e-9);
  EXPECT_NEAR(a.speed, 0.0, 1e-9);
}

}  // namespace hideseek_game
