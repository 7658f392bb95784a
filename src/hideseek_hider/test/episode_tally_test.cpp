#include "hideseek_hider/episode_tally.h"

#include <gtest/gtest.h>

namespace hideseek_hider {

TEST(EpisodeTally, CountsEachSeededEpisodeOnceWithItsLength) {
  EpisodeTally tally(3);
  tally.record(1, 5, true);
  tally.record(0, 5, false);
  tally.record(3, 7, false);  // not wanted
  tally.record(1, 9, false);  // seed 1 again (a reset replayed it): the first result stands
  EXPECT_FALSE(tally.complete());
  tally.record(2, 10, false);
  ASSERT_TRUE(tally.complete());
  EXPECT_EQ(tally.records().at(0).living_steps, 5u);
  EXPECT_EQ(tally.records().at(2).living_steps, 10u);
  EXPECT_TRUE(tally.records().at(1).survived);
  const auto s = tally.summary();
  EXPECT_EQ(s.episodes, 3);
  EXPECT_NEAR(s.avg_living_steps, 20.0 / 3, 1e-12);
  EXPECT_NEAR(s.success_rate, 1.0 / 3, 1e-12);
}

// A validation set of other seeds (first_seed 1000) counts only its own episodes.
TEST(EpisodeTally, CountsOnlyTheSeedsFromFirstSeedOn) {
  EpisodeTally tally(2, 1000);
  for (uint32_t seed : {3u, 999u, 1000u, 1002u, 1001u}) tally.record(seed, 2, false);
  ASSERT_TRUE(tally.complete());
  EXPECT_EQ(tally.collected(), 2u);
  EXPECT_EQ(tally.records().count(1000), 1u);
  EXPECT_EQ(tally.records().count(1001), 1u);
}

TEST(EpisodeTally, WritesTheCsvColumnsTheIssueNamesThenTheGame) {
  const std::string csv = evaluationCsv("basic", "random", "v3", {100, 123.456, 0.05});
  EXPECT_EQ(csv, "variant,policy,episodes,avg_living_steps,success_rate,game\nbasic,random,100,123.46,0.0500,v3\n");
  // However long the policy's name (a deep path, a seeker's beside it), the row keeps every column.
  const std::string long_policy = "/home/me/" + std::string(900, 'p') + ".pt (greedy) against the seeker random";
  EXPECT_EQ(
      evaluationCsv("basic", long_policy, "v3", {100, 1.0, 0.0}),
      "variant,policy,episodes,avg_living_steps,success_rate,game\nbasic," + long_policy + ",100,1.00,0.0000,v3\n");
}

// The table a person reads names the game beside the variant: v2's and v3's basic are other games.
TEST(EpisodeTally, WritesTheMarkdownTableWithTheGameBesideTheVariant) {
  const std::string md = evaluationMarkdown("basic", "basic_v3_seed0 (greedy)", "v3", {100, 218.79, 0.17});
  EXPECT_EQ(md,
            "| variant | game | policy | episodes | average living steps | success rate |\n"
            "| --- | --- | --- | --- | --- | --- |\n"
            "| basic | v3 | basic_v3_seed0 (greedy) | 100 | 218.8 | 17.00 % |\n");
}

TEST(EpisodeTally, WritesOneRowPerEpisodeInSeedOrder) {
  EpisodeTally tally(2, 10);
  tally.record(11, 3, false);
  tally.record(10, 2, true);
  EXPECT_EQ(episodesCsv(tally.records()), "seed,living_steps,outcome\n10,2,survived\n11,3,captured\n");
}

}  // namespace hideseek_hider
