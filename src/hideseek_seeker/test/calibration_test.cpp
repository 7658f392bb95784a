// Holds the calibration of the deterministic map: over the evaluation seeds 0..99 the uniformly
// random hider on basic lives within +-25 % of the paper's 41 steps and almost never survives.
// Deterministic given the seeds (no rendering, no timing), so the check is stable.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "hideseek_seeker/random_hider_game.h"
#include "hideseek_world/arena.h"

namespace hideseek_seeker {

TEST(Calibration, RandomHiderOnBasicLivesAsLongAsInThePaper) {
  const std::string config = HIDESEEK_CONFIG_DIR;
  const double paper = YAML::LoadFile(config + "/paper_reference.yaml")["variants"]["basic"]["living_random"].as<double>();
  const auto variant = hideseek_world::loadVariantConfig(config + "/game.yaml", config + "/variants/basic.yaml");
  const auto map = std::make_shared<const hideseek_world::MapSpec>(hideseek_world::loadMapFile(variant.map_file));
  const RandomHiderSummary s = summarize(playRandomHider(variant, map, 0, 100));
  RecordProperty("avg_living_steps", std::to_string(s.avg_living_steps));
  EXPECT_EQ(s.episodes, 100);
  EXPECT_GE(s.avg_living_steps, 0.75 * paper);
  EXPECT_LE(s.avg_living_steps, 1.25 * paper);
  EXPECT_LE(s.success_rate, 0.02);
  // The seeker sees the hider at step 0 in most episodes, as in an open arena.
  EXPECT_GE(s.seen_at_start_rate, 0.7);
}

TEST(Calibration, PlayingIsDeterministicGivenTheSeeds) {
  const std::string config = HIDESEEK_CONFIG_DIR;
  const auto variant = hideseek_world::loadVariantConfig(config + "/game.yaml", config + "/variants/stochasticseeker.yaml");
  const auto map = std::make_shared<const hideseek_world::MapSpec>(hideseek_world::loadMapFile(variant.map_file));
  const auto a = playRandomHider(variant, map, 40, 10), b = playRandomHider(variant, map, 40, 10);
  ASSERT_EQ(a.size(), 10u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].seed, 40 + i);
    EXPECT_EQ(a[i].living_steps, b[i].living_steps);
  }
}

TEST(Calibration, SummaryCountsMedianAndRates) {
  const RandomHiderSummary s =
      summarize({{0, 10, false, true}, {1, 30, false, false}, {2, 1000, true, true}, {3, 20, false, true}});
  EXPECT_DOUBLE_EQ(s.avg_living_steps, 265.0);
  EXPECT_DOUBLE_EQ(s.median_living_steps, 25.0);
  EXPECT_DOUBLE_EQ(s.success_rate, 0.25);
  EXPECT_DOUBLE_EQ(s.seen_at_start_rate, 0.75);
}

// A hider that runs a few steps, then stays put by stepping forward and back, on the real map:
// once the seeker has seen it, it must be caught. Such a hider shifts the seeker's target by a
// few centimetres each step, which once kept the seeker turning left and right on the spot for
// the rest of the episode (a trained slowerhider found this). Validation seeds 1000..1199, never
// the evaluation seeds 0..99. Reports each stalled episode.
TEST(Calibration, SeekerCatchesAHiderThatStaysPutOnceItHasSeenIt) {
  const std::string config = HIDESEEK_CONFIG_DIR;
  for (const std::string v : {"basic", "slowerhider", "stochasticseeker"}) {
    const auto variant = hideseek_world::loadVariantConfig(config + "/game.yaml", config + "/variants/" + v + ".yaml");
    const auto map = std::make_shared<const hideseek_world::MapSpec>(hideseek_world::loadMapFile(variant.map_file));
    hideseek_world::Arena arena(variant.game, map);
    SeekerPolicy seeker(seekerOptionsFor(variant));
    int seen_episodes = 0;
    for (uint32_t seed = 1000; seed < 1200; ++seed) {
      arena.reset(seed);
      seeker.reset(arena.layout(), seed);
      int first_seen = -1;
      hideseek_world::StepResult r;
      do {
        if (first_seen < 0 && arena.stepCount() >= static_cast<int>(seed % 60) && arena.labels().seeker_sees_hider) first_seen = arena.stepCount();
        const int run = static_cast<int>(seed % 60);
        const auto hider_action = arena.stepCount() < run                 ? hideseek_world::Action::kForward
                                 : arena.stepCount() % 2 ? hideseek_world::Action::kBackward : hideseek_world::Action::kForward;
        r = arena.step(hider_action, seeker.act(hideseek_world::seekerPerception(arena)));
      } while (!r.done());
      if (first_seen < 0) continue;
      ++seen_episodes;
      EXPECT_EQ(r.outcome, hideseek_world::Outcome::kCaptured)
          << v << " seed " << seed << ": seen at step " << first_seen << ", seeker left at ("
          << arena.seeker().position.x << ", " << arena.seeker().position.y << "), hider at ("
          << arena.hider().position.x << ", " << arena.hider().position.y << "), "
          << hideseek_world::distance(arena.seeker().position, arena.hider().position) << " m apart, mode "
          << modeName(seeker.mode()) << ", path of " << seeker.path().size() << " points";
    }
    EXPECT_GE(seen_episodes, 50) << v;
  }
}

}  // namespace hideseek_seeker
