#include "hideseek_analysis/step_log.h"

#include <gtest/gtest.h>

namespace hideseek_analysis {
namespace {

// Two arenas; arena 1's episode (seed 11) ends at step 1, and seed 13 starts after it.
DecisionRecord decision(uint64_t d, bool images = false) {
  DecisionRecord r;
  r.decision = d;
  r.arenas.resize(2);
  r.arenas[0].seed = 10;
  r.arenas[0].step = static_cast<uint32_t>(d);
  r.arenas[1].seed = d <= 1 ? 11 : 13;
  r.arenas[1].step = d <= 1 ? static_cast<uint32_t>(d) : static_cast<uint32_t>(d - 2);
  r.arenas[1].outcome = d == 1 ? 1 : 0;
  if (images) {
    r.height = 2;
    r.width = 3;
    r.images.assign(2 * 2 * 3 * 3, static_cast<uint8_t>(d));
  }
  return r;
}

TEST(StepLog, KeepsEveryArenasStepsInDecisionOrderWithTheirImages) {
  StepLog log;
  for (uint64_t d = 5; d < 9; ++d) {
    auto r = decision(d - 5, d % 2 == 0);
    r.decision = d;
    log.append(r);
  }
  EXPECT_EQ(log.decisions(), 4u);
  EXPECT_EQ(log.firstDecision(), 5u);
  ASSERT_EQ(log.records().size(), 8u);
  EXPECT_EQ(log.records()[3].arena, 1);
  EXPECT_EQ(log.records()[3].decision, 6u);
  // Decisions 6 and 8 carry images: arena 0 and 1 of decision 6 are images 0 and 1.
  EXPECT_EQ(log.records()[0].image, -1);
  EXPECT_EQ(log.records()[2].image, 0);
  EXPECT_EQ(log.records()[3].image, 1);
  EXPECT_EQ(log.records()[6].image, 2);
  EXPECT_EQ(log.numImages(), 4);
  EXPECT_EQ(log.images()[2 * 18], 3);  // decision 8 was built as the fourth, d = 3
}

TEST(StepLog, RefusesAJumpInTheDecisionCounterAndSaysWhatIsMissing) {
  StepLog log;
  log.append(decision(0));
  log.append(decision(1));
  auto late = decision(2);
  late.decision = 84;
  try {
    log.append(late);
    FAIL() << "a jump was accepted";
  } catch (const MissingStepsError& e) {
    EXPECT_NE(std::string(e.what()).find("decisions 2 to 83 are missing (82 decision steps of 2 arenas)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(log.decisions(), 2u);
  EXPECT_THROW(log.append(decision(1)), MissingStepsError);  // repeated
}

TEST(StepLog, RefusesAnArenaWhoseStepDoesNotContinueItsEpisode) {
  StepLog log;
  log.append(decision(0));
  auto skipped = decision(1);
  skipped.arenas[0].step = 2;
  EXPECT_THROW(log.append(skipped), MissingStepsError);
  // A new episode may start only after an outcome.
  auto restarted = decision(1);
  restarted.arenas[0].seed = 99;
  restarted.arenas[0].step = 0;
  EXPECT_THROW(log.append(restarted), MissingStepsError);
  log.append(decision(1));
  log.append(decision(2));  // arena 1: seed 13 starts at step 0 after seed 11's capture
  EXPECT_EQ(log.decisions(), 3u);
}

TEST(StepLog, RefusesMalformedDecisions) {
  StepLog log;
  auto bad = decision(0, true);
  bad.images.pop_back();
  EXPECT_THROW(log.append(bad), std::invalid_argument);
  DecisionRecord empty;
  EXPECT_THROW(log.append(empty), std::invalid_argument);
  log.append(decision(0));
  auto fewer = decision(1);
  fewer.arenas.pop_back();
  EXPECT_THROW(log.append(fewer), MissingStepsError);
}

}  // namespace
}  // namespace hideseek_analysis
