#include <gtest/gtest.h>

#include "hideseek_hider/episode_tally.h"

namespace hideseek_hider {

TEST(EpisodeTally, CountsEachSeededEpisodeOnceWithItsLength) {
  EpisodeTally tally(3);
  // Arena 0 plays seeds 0 then 2; arena 1 plays seed 1 then 3 (not wanted).
  for (uint32_t s = 0; s < 5; ++s) {
    tally.observe(0, false, false, s, 0);
    tally.observe(1, false, false, s, 1);
  }
  tally.observe(0, true, false, 0, 2);  // seed 0 captured after 5 steps
  for (uint32_t s = 1; s < 10; ++s) tally.observe(0, false, false, s, 2);
  tally.observe(1, true, true, 0, 3);  // seed 1 survived (5 steps here)
  EXPECT_FALSE(tally.complete());
  tally.observe(0, true, false, 0, 4);  // seed 2 after 10 steps
  ASSERT_TRUE(tally.complete());
  EXPECT_EQ(tally.records().at(0).living_steps, 5u);
  EXPECT_EQ(tally.records().at(2).living_steps, 10u);
  EXPECT_TRUE(tally.records().at(1).survived);
  const auto s = tally.summary();
  EXPECT_EQ(s.episodes, 3);
  EXPECT_NEAR(s.avg_living_steps, 20.0 / 3, 1e-12);
  EXPECT_NEAR(s.success_rate, 1.0 / 3, 1e-12);
}

TEST(EpisodeTally, IgnoresTheEpisodeUnderWayWhenListeningStarts) {
  EpisodeTally tally(5);
  tally.observe(0, false, false, 37, 0);  // joined mid-episode
  tally.observe(0, true, false, 0, 4);
  EXPECT_EQ(tally.collected(), 0u);
}

// A validation set of other seeds (first_seed 1000) counts only its own episodes.
TEST(EpisodeTally, CountsOnlyTheSeedsFromFirstSeedOn) {
  EpisodeTally tally(2, 1000);
  for (uint32_t seed : {3u, 999u, 1000u, 1002u, 1001u}) {
    tally.observe(0, false, false, 0, seed);
    tally.observe(0, false, false, 1, seed);
    tally.observe(0, true, false, 0, seed + 5000);
  }
  ASSERT_TRUE(tally.complete());
  EXPECT_EQ(tally.collected(), 2u);
  EXPECT_EQ(tally.records().count(1000), 1u);
  EXPECT_EQ(tally.records().count(1001), 1u);
  EXPECT_EQ(tally.records().at(1000).living_steps, 2u);
}

TEST(EpisodeTally, WritesTheCsvColumnsTheIssueNames) {
  const std::string csv = evaluationCsv("basic", "random", {100, 123.456, 0.05});
  EXPECT_EQ(csv, "variant,policy,episodes,avg_living_steps,success_rate\nbasic,random,100,123.46,0.0500\n");
}

TEST(EpisodeTally, WritesOneRowPerEpisodeInSeedOrder) {
  EpisodeTally tally(2, 10);
  // Arena 1 ends seed 11 (captured at its third step) before arena 0 ends seed 10 (survives 2 steps).
  tally.observe(0, false, false, 0, 10);
  tally.observe(1, false, false, 0, 11);
  tally.observe(0, false, false, 1, 10);
  tally.observe(1, false, false, 1, 11);
  tally.observe(1, false, false, 2, 11);
  tally.observe(1, true, false, 0, 13);
  tally.observe(0, true, true, 0, 12);
  ASSERT_TRUE(tally.complete());
  EXPECT_EQ(episodesCsv(tally.records()), "seed,living_steps,outcome\n10,2,survived\n11,3,captured\n");
}

}  // namespace hideseek_hider
