#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <set>

#include "hideseek_game/world.h"
#include "test_util.h"

namespace hideseek_game {

using test::loadMap;
using test::loadVariant;

TEST(Arena, CaptureWhenCentresComeWithinCaptureDistance) {
  const VariantConfig v = loadVariant("basic");
  Arena arena(v.game, loadMap("deterministic"));
  arena.reset(3);
  // Drive the seeker straight at the hider (they start facing each other) while the hider stays.
  StepResult r;
  int steps = 0;
  double closest = 1e9;
  while (!r.done() && steps < 200) {
    closest = std::min(closest, distance(arena.hider().position, arena.seeker().position));
    r = arena.step(Action::kStay, Action::kForward);
    ++steps;
  }
  if (r.outcome == Outcome::kCaptured) {
    EXPECT_LE(distance(arena.hider().position, arena.seeker().position), v.game.capture_distance + 1e-9);
    EXPECT_GT(closest, v.game.capture_distance);
    EXPECT_DOUBLE_EQ(r.reward, -1.0);
  } else {
    // An obstacle between them: the seeker slid along it, still never closer than capture.
    EXPECT_GT(distance(arena.hider().position, arena.seeker().position), v.game.capture_distance);
  }
}

TEST(Arena, SpawnsAreValidForTenThousandSeedsOnBothMapKinds) {
  for (const std::string variant : {"basic", "stochasticmaps"}) {
    const VariantConfig v = loadVariant(variant);
    auto map = std::make_shared<const MapSpec>(loadMapFile(v.map_file));
    Arena arena(v.game, map);
    for (uint32_t seed = 0; seed < 10000; ++seed) {
      arena.reset(seed);
      const AgentState& h = arena.hider();
      const AgentState& s = arena.seeker();
      const Layout& l = arena.layout();
      ASSERT_GE(distance(h.position, s.position), 3.0) << variant << " seed " << seed;
      for (const AgentState* a : {&h, &s}) {
        ASSERT_LE(std::abs(a->position.x), l.half_extent - v.game.agent_radius) << variant << " seed " << seed;
        ASSERT_LE(std::abs(a->position.y), l.half_extent - v.game.agent_radius) << variant << " seed " << seed;
        for (const Box& b : l.obstacles) ASSERT_GE(footprintDistance(b, a->position), v.game.agent_radius);
      }
      const FreeSpaceGrid grid(l, v.game.agent_radius, kSpawnGridResolution);
      ASSERT_TRUE(grid.connected(h.position, s.position)) << variant << " seed " << seed;
      ASSERT_NEAR(wrapAngle(h.yaw - std::atan2(s.position.y - h.position.y, s.position.x - h.position.x)), 0.0, 1e-9);
      ASSERT_NEAR(wrapAngle(s.yaw - std::atan2(h.position.y - s.position.y, h.position.x - s.position.x)), 0.0, 1e-9);
    }
  }
}

TEST(Arena, StochasticMapsDrawZeroToEightBoxesOfBoundedSize) {
  const VariantConfig v = loadVariant("stochasticmaps");
  Arena arena(v.game, loadMap("stochastic"));
  std::set<size_t> counts;
  for (uint32_t seed = 0; seed < 500; ++seed) {
    arena.reset(seed);
    counts.insert(arena.layout().obstacles.size());
    for (const Box& b : arena.layout().obstacles) {
      ASSERT_GE(std::min(b.size.x, b.size.y), 0.5);
      ASSERT_LE(std::max(b.size.x, b.size.y), 3.0);
    }
  }
  EXPECT_EQ(*counts.begin(), 0u);
  EXPECT_EQ(*counts.rbegin(), 8u);
}

TEST(Arena, SurvivalRewardPerStepAndEpisodeEndsAtStepLimit) {
  VariantConfig v = loadVariant("basic");
  v.game.max_steps = 20;
  Arena arena(v.game, loadMap("deterministic"));
  arena.reset(11);
  StepResult r;
  for (int i = 0; i < 20; ++i) {
    ASSERT_FALSE(r.done());
    r = arena.step(Action::kStay, Action::kStay);  // nobody moves: nobody is captured
    EXPECT_DOUBLE_EQ(r.reward, 0.001);
  }
  EXPECT_EQ(r.outcome, Outcome::kSurvived);
  EXPECT_NEAR(arena.episodeReturn(), 0.02, 1e-12);
}

TEST(Arena, VisibilityRewardFollowsWhetherTheSeekerSeesTheHider) {
  const VariantConfig v = loadVariant("visibilityreward");
  ASSERT_TRUE(v.game.rewards.visibility);
  Arena arena(v.game, loadMap("deterministic"));
  int seen = 0, unseen = 0;
  std::mt19937 rng(5);
  for (uint32_t seed = 0; seed < 40; ++seed) {
    arena.reset(seed);
    for (int i = 0; i < 30; ++i) {
      const StepResult r = arena.step(Action(rng() % 5), Action(rng() % 5));
      if (r.done()) {
        EXPECT_DOUBLE_EQ(r.reward, -1.0);
        break;
      }
      const double expected = arena.labels().seeker_sees_hider ? 0.0 : 0.002;
      EXPECT_NEAR(r.reward, expected, 1e-12);
      (arena.labels().seeker_sees_hider ? seen : unseen)++;
    }
  }
  EXPECT_GT(seen, 0);
  EXPECT_GT(unseen, 0);
}

TEST(Arena, FrameByFrameStepsMatchWholeDecisionSteps) {
  // Realtime mode advances single physics frames; lockstep whole steps. Both must agree.
  const VariantConfig v = loadVariant("fasterhider");
  auto map = loadMap("deterministic");
  Arena whole(v.game, map), frames(v.game, map);
  whole.reset(21);
  frames.reset(21);
  std::mt19937 rng(4);
  for (int step = 0; step < 200; ++step) {
    const Action h = Action(rng() % 5), s = Action(rng() % 5);
    const StepResult a = whole.step(h, s);
    std::optional<StepResult> b;
    int n = 0;
    while (!b) {
      b = frames.advanceFrame(h, s);
      ++n;
    }
    ASSERT_LE(n, v.game.action_repeat);
    ASSERT_EQ(a.reward, b->reward);
    ASSERT_EQ(a.outcome, b->outcome);
    ASSERT_EQ(whole.hider().position.x, frames.hider().position.x);
    ASSERT_EQ(whole.seeker().position.y, frames.seeker().position.y);
    if (a.done()) {
      EXPECT_TRUE(a.outcome == Outcome::kCaptured || step + 1 == v.game.max_steps);
      return;
    }
  }
}

TEST(World, SameSeedAndActionsGiveBitIdenticalEpisodes) {
  const VariantConfig v = loadVariant("stochasticmaps");
  auto map = loadMap("stochastic");
  World a(v.game, map, 4, 7, true), b(v.game, map, 4, 7, true);
  std::vector<uint8_t> ia(a.imageBytes() * 4), ib(b.imageBytes() * 4);
  std::mt19937 rng(1);
  for (int step = 0; step < 300; ++step) {
    for (int i = 0; i < 4; ++i) {
      const Action h = Action(rng() % 5), s = Action(rng() % 5);
      const ArenaStep ra = a.stepArena(i, h, s), rb = b.stepArena(i, h, s);
      ASSERT_EQ(ra.result.reward, rb.result.reward);
      ASSERT_EQ(ra.result.outcome, rb.result.outcome);
      const Arena &xa = a.arena(i), &xb = b.arena(i);
      ASSERT_EQ(xa.hider().position.x, xb.hider().position.x);
      ASSERT_EQ(xa.hider().position.y, xb.hider().position.y);
      ASSERT_EQ(xa.seeker().yaw, xb.seeker().yaw);
      ASSERT_EQ(xa.labels().seeker_sees_hider, xb.labels().seeker_sees_hider);
      ASSERT_EQ(xa.labels().hider_sees_seeker, xb.labels().hider_sees_seeker);
      ASSERT_EQ(xa.labels().obstacle_in_view, xb.labels().obstacle_in_view);
      ASSERT_EQ(xa.seed(), xb.seed());
    }
    a.renderHiderViews(ia.data());
    b.renderHiderViews(ib.data());
    ASSERT_EQ(ia, ib) << "images differ at step " << step;
  }
}

TEST(World, ArenaSeedsInterleaveSoFirstEpisodesCoverConsecutiveSeeds) {
  VariantConfig v = loadVariant("basic");
  v.game.max_steps = 1;
  World w(v.game, loadMap("deterministic"), 3, 10, false);
  std::set<uint32_t> seeds;
  for (int round = 0; round < 4; ++round) {
    for (int i = 0; i < 3; ++i) {
      seeds.insert(w.arena(i).seed());
      const ArenaStep s = w.stepArena(i, Action::kStay, Action::kStay);
      ASSERT_TRUE(s.finished.has_value());
    }
  }
  EXPECT_EQ(seeds, (std::set<uint32_t>{10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21}));
  w.resetArena(1, 100u);
  EXPECT_EQ(w.arena(1).seed(), 100u);
}

// Two ranks of a data-parallel training, each a world of 2 arenas with seed stride 4 (rank r
// starting at seed + 2r), play exactly the seeds one world of 4 arenas plays, and never the same.
TEST(World, RanksWithASeedStrideShareOutTheSeedsOfOneLargerWorld) {
  VariantConfig v = loadVariant("basic");
  v.game.max_steps = 1;
  auto seedsOf = [&](int arenas, uint32_t seed, uint32_t stride, int rounds) {
    World w(v.game, loadMap("deterministic"), arenas, seed, false, 2, stride);
    std::multiset<uint32_t> seeds;
    for (int round = 0; round < rounds; ++round) {
      for (int i = 0; i < arenas; ++i) {
        seeds.insert(w.arena(i).seed());
        EXPECT_TRUE(w.stepArena(i, Action::kStay, Action::kStay).finished.has_value());
      }
    }
    return seeds;
  };
  const std::multiset<uint32_t> rank0 = seedsOf(2, 10, 4, 3), rank1 = seedsOf(2, 12, 4, 3);
  std::multiset<uint32_t> both = rank0;
  both.insert(rank1.begin(), rank1.end());
  EXPECT_EQ(both, seedsOf(4, 10, 0, 3));
  EXPECT_EQ(both.size(), std::set<uint32_t>(both.begin(), both.end()).size()) << "a seed was played twice";
  EXPECT_EQ(rank0, (std::multiset<uint32_t>{10, 11, 14, 15, 18, 19}));
}

}  // namespace hideseek_game
