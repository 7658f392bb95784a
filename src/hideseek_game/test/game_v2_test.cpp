// Game v2's rules in the world core: the seeker deciding inside a decision step, what it knows at
// spawn, walls that are not obstacles, and agents whose heading shows in the image.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "hideseek_game/arena.h"
#include "hideseek_game/config_error.h"
#include "hideseek_game/visibility.h"
#include "hideseek_game/world.h"
#include "test_util.h"

namespace hideseek_game {
namespace {

using test::configPath;
using test::loadMap;
using test::loadVariant;

// A seeker that acts on its perception alone, deterministically: enough to tell two exchanges apart.
Action probeSeeker(const SeekerPerception& p, uint32_t decision) {
  if (p.hider_position) return (decision % 3 == 0) ? Action::kTurnLeft : Action::kForward;
  return static_cast<Action>(decision % kNumActions);
}

}  // namespace

TEST(GameV2, DefaultsLetTheSeekerDecideEveryFrameKnowingTheSpawn) {
  const VariantConfig v = loadVariant("basic");
  EXPECT_EQ(v.game.seeker_decision_frames, 1);
  EXPECT_TRUE(v.game.seeker_knows_spawn);
  EXPECT_EQ(v.game.seekerDecisionsPerStep(), 6);
  const VariantConfig v1 = loadVariantConfig(configPath("game_v1.yaml"), configPath("variants/basic.yaml"));
  EXPECT_EQ(v1.game.seeker_decision_frames, 6);
  EXPECT_FALSE(v1.game.seeker_knows_spawn);
  EXPECT_NE(v1.map_file, v.map_file);
  EXPECT_NE(v1.map_file.find("maps/v1/deterministic.yaml"), std::string::npos) << v1.map_file;
  EXPECT_EQ(v1.game.hider.speed, v.game.hider.speed);  // everything else is game.yaml's
}

TEST(GameV2, ADecisionPeriodThatDoesNotDivideTheActionRepeatIsRefused) {
  const std::string dir = ::testing::TempDir();
  {
    std::ofstream f(dir + "/game_bad.yaml");
    f << "extends: " << configPath("game.yaml") << "\nmaps_dir: " << configPath("maps")
      << "\nseeker:\n  decision_frames: 4\n";
  }
  try {
    loadVariantConfig(dir + "/game_bad.yaml", configPath("variants/basic.yaml"));
    FAIL() << "decision_frames 4 with action_repeat 6 was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("seeker.decision_frames"), std::string::npos) << e.what();
  }
}

TEST(GameV2, TheSeekerIsToldTheSpawnAtItsFirstDecisionOnly) {
  const VariantConfig v = loadVariant("basic");
  Arena arena(v.game, loadMap("deterministic"));
  int told = 0;
  for (uint32_t seed = 1000; seed < 1100; ++seed) {
    arena.reset(seed);
    const SeekerPerception first = seekerPerception(arena);
    ASSERT_TRUE(first.hider_position) << "seed " << seed;
    EXPECT_EQ(first.hider_position->x, arena.hider().position.x);
    told += !arena.labels().seeker_sees_hider;
    arena.advanceFrame(Action::kStay, Action::kStay);
    const SeekerPerception second = seekerPerception(arena);
    EXPECT_EQ(second.hider_position.has_value(), agentSeesAgent(arena.seeker(), arena.hider(), arena.layout(), v.game))
        << "seed " << seed;
  }
  EXPECT_GT(told, 10) << "the map hides the hider at spawn in too few episodes to test the rule";
}

TEST(GameV2, SeekerDecisionIdsCountFramesOverTheDecisionPeriod) {
  VariantConfig v = loadVariant("basic");
  v.game.seeker_decision_frames = 2;
  Arena arena(v.game, loadMap("deterministic"));
  arena.reset(1000);
  std::vector<uint32_t> ids;
  for (int f = 0; f < 12; ++f) {
    if (arena.seekerDecisionDue()) ids.push_back(arena.seekerDecisionIndex());
    arena.advanceFrame(Action::kStay, Action::kStay);
  }
  EXPECT_EQ(ids, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(arena.stepCount(), 2);
}

// The world node's exchange (World::advanceFrame, the seeker asked before each of its decisions
// for every arena in phase) plays exactly the episodes of in-process play (World::stepArena with
// the seeker asked inside the step), captures and episode changes included.
TEST(GameV2, TheWorldNodesFrameExchangeEqualsInProcessPlay) {
  VariantConfig v = loadVariant("stochasticmaps");
  v.game.max_steps = 60;
  auto map = loadMap("stochastic");
  constexpr int kArenas = 3;
  World node(v.game, map, kArenas, 50, false), in_process(v.game, map, kArenas, 50, false);
  std::mt19937 rng(3);
  int finished = 0;
  for (int step = 0; step < 400; ++step) {
    std::vector<Action> hider(kArenas);
    for (auto& a : hider) a = static_cast<Action>(rng() % kNumActions);
    std::vector<ArenaStep> expected;
    for (int i = 0; i < kArenas; ++i) {
      expected.push_back(in_process.stepArena(i, hider[i], [&](const SeekerPerception& p) {
        return probeSeeker(p, in_process.arena(i).seekerDecisionIndex());
      }));
    }
    std::optional<std::vector<ArenaStep>> got;
    std::vector<Action> seeker(kArenas);
    while (!got) {
      if (node.seekerDecisionDue()) {
        for (int i = 0; i < kArenas; ++i)
          seeker[i] = probeSeeker(seekerPerception(node.arena(i)), node.seekerDecisionId(i));
      }
      got = node.advanceFrame(hider, seeker);
    }
    for (int i = 0; i < kArenas; ++i) {
      ASSERT_EQ((*got)[i].result.outcome, expected[i].result.outcome) << "step " << step << " arena " << i;
      ASSERT_EQ((*got)[i].result.reward, expected[i].result.reward);
      ASSERT_EQ((*got)[i].finished.has_value(), expected[i].finished.has_value());
      if (expected[i].finished) {
        ++finished;
        ASSERT_EQ((*got)[i].finished->steps, expected[i].finished->steps);
      }
      ASSERT_EQ(node.arena(i).seeker().position.x, in_process.arena(i).seeker().position.x);
      ASSERT_EQ(node.arena(i).hider().yaw, in_process.arena(i).hider().yaw);
    }
  }
  EXPECT_GT(finished, 10);
}

TEST(GameV2, BoxesMarkedAsWallsBlockButAreNotObstaclesInView) {
  const VariantConfig v = loadVariant("basic");
  const auto map = loadMap("deterministic");
  int walls = 0;
  for (const Box& b : map->obstacles) walls += b.wall;
  EXPECT_EQ(walls, 4);
  Arena arena(v.game, map);
  arena.reset(1000);
  // Standing in the north-east part of the arena, looking into the corner wall: no obstacle.
  AgentState viewer{{5.0, 2.0}, 0.25 * kPi, 0.0, {}};
  EXPECT_FALSE(obstacleInView(viewer, arena.layout(), v.game));
  // The same spot looking at the centre sees the cross.
  viewer.yaw = std::atan2(-2.0, -5.0);
  EXPECT_TRUE(obstacleInView(viewer, arena.layout(), v.game));
  // And the corner wall stops an agent like any obstacle.
  AgentState walker{{5.0, 2.0}, 0.25 * kPi, 0.0, {}};
  for (int f = 0; f < 200; ++f)
    advanceAgent(walker, Action::kForward, v.game.hider, v.game.physics_dt, arena.layout(), v.game.agent_radius);
  EXPECT_LT(walker.position.x + walker.position.y, 14.0 - 4.0 * std::sqrt(2.0) - 0.4 * std::sqrt(2.0) + 1e-6);
}

// Whether the seeker faces the hider is in the hider's 84 x 84 image: its front colour covers most
// of its silhouette (about 20 pixels) when it looks at the hider from 5 m, none when it looks away.
TEST(GameV2, TheSeekersFrontColourShowsWhetherItFacesTheHider) {
  const VariantConfig v = loadVariant("basic");
  const auto map = loadMap("deterministic");
  ASSERT_TRUE(map->colors.seeker_front.has_value());
  Renderer renderer(test::rendererOptions(v, *map));
  Layout empty;
  renderer.setScene(0, empty);
  std::vector<uint8_t> image(static_cast<size_t>(v.game.camera.width) * v.game.camera.height * 3);
  auto frontPixels = [&](double seeker_yaw) {
    const AgentState hider{{-2.5, 0.0}, 0.0, 0.0, {}}, seeker{{2.5, 0.0}, seeker_yaw, 0.0, {}};
    renderer.render({{0, hider, seeker, false}}, RenderMode::kColor, image.data());
    int n = 0;
    for (size_t p = 0; p < image.size(); p += 3) {
      // Yellow: strong red and green, little blue (fog greys it a little at 5 m).
      n += image[p] > 150 && image[p + 1] > 130 && image[p + 2] < 110;
    }
    return n;
  };
  const int facing = frontPixels(kPi), away = frontPixels(0.0);
  EXPECT_GE(facing, 10) << "front pixels when the seeker faces the hider";
  EXPECT_EQ(away, 0) << "front pixels when it looks away";
}

}  // namespace hideseek_game
