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

namespace hideseek_game {

namespace {

// Game v3's accelerating hider: the momentum model of config/game_v3.yaml over the fasterhider variant.
MotionOptions momentumHider() {
  MotionOptions m = test::loadVariant("fasterhider", "v3").game.hider;
  EXPECT_EQ(m.mode, SpeedMode::kAccelerate);
  EXPECT_EQ(m.accelerate_model, AccelerateModel::kMomentum);
  return m;
}

}  // namespace

// A user steering the v3 fasterhider: it keeps its speed and direction of travel through a turn
// and a stay, where v2's brakes (AccelerateModeRampsUpCapsAndCoastsToRest).
TEST(MomentumModel, ATurnOrAStayKeepsTheVelocityInTheMapFrame) {
  MotionOptions m = momentumHider();
  m.drag = 0.0;
  m.acceleration = 2.0;  // the model, not v3's calibration: a round figure, under the cap after 1 s
  AgentState a;
  a.position = {-6.0, 0.0};
  step(a, Action::kForward, m, emptyArena(), 50);  // 1 s of pushing along +x
  const double speed = norm(a.velocity);
  EXPECT_NEAR(speed, m.acceleration * 1.0, 1e-9);
  EXPECT_NEAR(a.velocity.y, 0.0, 1e-12);
  const Vec2 before = a.position;
  step(a, Action::kTurnLeft, m, emptyArena(), 25);  // half a second: a quarter turn of the body
  EXPECT_NEAR(a.yaw, 0.5 * kPi, 1e-9);
  EXPECT_NEAR(norm(a.velocity), speed, 1e-12) << "a turn pushes nothing: the speed is kept";
  EXPECT_NEAR(a.velocity.y, 0.0, 1e-12) << "the velocity does not turn with the body";
  EXPECT_NEAR(a.position.x - before.x, speed * 0.5, 1e-9) << "it travels on along +x while it turns";
  EXPECT_NEAR(a.speed, 0.0, 1e-9) << "speed is the velocity's part along the heading, now across it";
  step(a, Action::kStay, m, emptyArena(), 10);
  EXPECT_NEAR(norm(a.velocity), speed, 1e-12) << "no drag: a stay keeps the speed";
  // Pushing forward now (heading +y) adds across the old motion.
  step(a, Action::kForward, m, emptyArena(), 50);
  EXPECT_NEAR(a.velocity.x, speed, 1e-9);
  EXPECT_NEAR(a.velocity.y, m.acceleration * 1.0, 1e-9);
}

TEST(MomentumModel, DragSlowsOnlyTheFramesThatPushNothingAndTheSpeedIsCapped) {
  MotionOptions m = momentumHider();
  m.drag = 1.0;
  Layout wide = emptyArena();
  wide.half_extent = 100.0;  // room for 8 s of pushing
  AgentState a;
  step(a, Action::kForward, m, wide, 400);  // 8 s: well past the cap
  EXPECT_NEAR(norm(a.velocity), m.max_speed, 1e-9);
  a.position = {0.0, 0.0};
  step(a, Action::kStay, m, emptyArena(), 1);
  EXPECT_NEAR(norm(a.velocity), m.max_speed * (1.0 - m.drag * kDt), 1e-9);
  step(a, Action::kTurnRight, m, emptyArena(), 1);
  EXPECT_NEAR(norm(a.velocity), m.max_speed * std::pow(1.0 - m.drag * kDt, 2), 1e-9);
  // Backward pushes against the heading: from rest it moves backwards.
  AgentState b;
  step(b, Action::kBackward, m, emptyArena(), 10);
  EXPECT_LT(b.velocity.x, 0.0);
  EXPECT_LT(b.position.x, 0.0);
}

// A wall stops only the part of the velocity that points into it: the agent slides along it.
TEST(MomentumModel, AWallRemovesOnlyThePartIntoIt) {
  MotionOptions m = momentumHider();
  m.drag = 0.0;
  m.acceleration = 2.0;  // under the cap after 1 s of pushing
  AgentState a;
  a.position = {6.0, 0.0};
  a.yaw = 0.25 * kPi;
  step(a, Action::kForward, m, emptyArena(), 50);  // 1 s diagonally into the east wall
  const double limit = 7.0 - 0.4;
  EXPECT_NEAR(a.position.x, limit, 1e-9) << "it stops at the wall";
  EXPECT_NEAR(a.velocity.x, 0.0, 1e-12) << "the part into the wall is gone";
  EXPECT_NEAR(a.velocity.y, m.acceleration * std::sin(0.25 * kPi), 1e-9) << "the part along the wall is kept";
  const double y = a.position.y;
  step(a, Action::kStay, m, emptyArena(), 25);
  EXPECT_NEAR(a.position.y - y, a.velocity.y * 0.5, 1e-9) << "it slides on along the wall";
  EXPECT_NEAR(a.position.x, limit, 1e-9);
  // Into a box's face head-on: the speed is gone, nothing is left to slide with.
  Layout l = emptyArena();
  l.obstacles.push_back(Box::make({2.0, 0.0}, {1.0, 4.0}, 1.5, 0.0));
  AgentState b;
  step(b, Action::kForward, m, l, 100);
  EXPECT_NEAR(b.position.x, 1.5 - 0.4, 1e-9);
  EXPECT_NEAR(norm(b.velocity), 0.0, 1e-9);
}

// Game v3's seeker may turn and move in one frame; the hider may not (the world refuses it).
TEST(MomentumModel, AForwardTurnTurnsAndMovesInOneFrame) {
  MotionOptions m = test::loadVariant("basic", "v3").game.seeker;
  AgentState a;
  step(a, Action::kForwardLeft, m, emptyArena(), 1);
  EXPECT_NEAR(a.yaw, m.turn_rate * kDt, 1e-12);
  EXPECT_NEAR(norm(a.position), m.speed * kDt, 1e-12);
  EXPECT_GT(a.position.y, 0.0);
  const GameOptions v3 = test::loadVariant("basic", "v3").game, v2 = test::loadVariant("basic").game;
  EXPECT_EQ(actionCount(v3, true), kNumSeekerActions);
  EXPECT_EQ(actionCount(v3, false), kNumActions);
  EXPECT_EQ(actionCount(v2, true), kNumActions) << "v2's seeker turns or moves";
}

}  // namespace hideseek_game
