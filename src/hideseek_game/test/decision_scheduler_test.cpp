#include "hideseek_game/decision_scheduler.h"

#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>
#include <vector>

namespace hideseek_game {
namespace {

constexpr uint8_t kForwardId = 1, kLeftId = 3;

TEST(DecisionScheduler, LockstepDecidesOnceBothAgentsAnsweredEveryArenaForItsStep) {
  DecisionScheduler s(ClockMode::kLockstep, 2, 0.5, 1.0);
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 7, 7), Verdict::kAccepted);
  EXPECT_EQ(s.offer(Player::kSeeker, 0, kLeftId, 7, 7), Verdict::kAccepted);
  EXPECT_EQ(s.offer(Player::kHider, 1, kForwardId, 3, 3), Verdict::kAccepted);
  EXPECT_FALSE(s.complete());
  EXPECT_EQ(s.offer(Player::kSeeker, 1, kForwardId, 3, 3), Verdict::kAccepted);
  ASSERT_TRUE(s.complete());
  const DecisionActions d = s.takeDecision();
  EXPECT_EQ(d.hider[0], Action::kForward);
  EXPECT_EQ(d.seeker[0], Action::kTurnLeft);
  EXPECT_FALSE(s.complete());   // the next step needs new answers
  EXPECT_FALSE(s.executing());  // lockstep steps at once
}

TEST(DecisionScheduler, RefusesAnotherStepsAnswerAndAnInvalidAction) {
  DecisionScheduler s(ClockMode::kLockstep, 1, 0.5, 1.0);
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 6, 7), Verdict::kWrongStep);  // one step late
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 8, 7), Verdict::kWrongStep);
  EXPECT_EQ(s.offer(Player::kHider, 0, 5, 7, 7), Verdict::kInvalidAction);
  EXPECT_FALSE(s.answered(Player::kHider, 0));
}

// awaited for two arenas: [hider 0, hider 1, seeker 0, seeker 1].
using Awaited = std::vector<std::optional<uint32_t>>;

TEST(DecisionScheduler, AResetMidEpisodeForgetsTheAnswersToTheOldStep) {
  DecisionScheduler s(ClockMode::kLockstep, 2, 0.5, 1.0);
  s.offer(Player::kHider, 0, kForwardId, 40, 40);
  s.offer(Player::kHider, 1, kForwardId, 12, 12);
  s.reset(0, {40, 12, 40, 12});
  EXPECT_FALSE(s.answered(Player::kHider, 0));
  EXPECT_TRUE(s.answered(Player::kHider, 1));
  // After the reset arena 0 is at step 0: one to step 0 counts.
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 0, 0), Verdict::kAccepted);
  s.reset(-1, {0, 12, 40, 12});
  EXPECT_FALSE(s.answered(Player::kHider, 1));
  EXPECT_THROW(s.reset(-1, {0, 0}), std::invalid_argument);  // one id per player and arena
}

TEST(DecisionScheduler, TheAnswerAResetOvertookIsDroppedOnceNotCountedAsAWrongStep) {
  DecisionScheduler s(ClockMode::kLockstep, 2, 0.5, 1.0);
  // Arena 0 awaited step 40 from both agents, arena 1 awaited step 12; arena 0 is reset to step 0.
  s.reset(0, Awaited{40, 12, 40, 12});
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 40, 0), Verdict::kSupersededByReset);
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 40, 0), Verdict::kWrongStep) << "only one was on its way";
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 39, 0), Verdict::kWrongStep) << "another id is a wrong step";
  EXPECT_EQ(s.offer(Player::kHider, 1, kForwardId, 11, 12), Verdict::kWrongStep) << "arena 1 was not reset";
  // The seeker's own record: its next accepted answer ends it, so a late one after that is wrong.
  EXPECT_EQ(s.offer(Player::kSeeker, 0, kLeftId, 0, 0), Verdict::kAccepted);
  EXPECT_EQ(s.offer(Player::kSeeker, 0, kLeftId, 40, 0), Verdict::kWrongStep);
  // An arena that awaited nothing from a player (the hider inside a step) drops nothing.
  s.reset(1, Awaited{std::nullopt, std::nullopt, 7, 7});
  EXPECT_EQ(s.offer(Player::kHider, 1, kForwardId, 12, 0), Verdict::kWrongStep);
  EXPECT_EQ(s.offer(Player::kSeeker, 1, kLeftId, 7, 0), Verdict::kSupersededByReset);
  EXPECT_FALSE(s.answered(Player::kSeeker, 1)) << "a dropped answer answers nothing";
}

TEST(DecisionScheduler, LockstepResendsAnObservationNobodyAnswered) {
  DecisionScheduler s(ClockMode::kLockstep, 1, 0.5, 1.0);
  s.observationSent(10.0);
  EXPECT_FALSE(s.resendDue(10.9));
  EXPECT_TRUE(s.resendDue(11.1));
  s.observationSent(11.1);  // re-sent
  EXPECT_FALSE(s.resendDue(11.5));
}

TEST(DecisionScheduler, RealtimeWaitsForAnswersThenLetsASilentAgentStandStill) {
  DecisionScheduler s(ClockMode::kRealtime, 1, 0.5, 1.0);
  s.offer(Player::kSeeker, 0, kLeftId, 0, 0);
  EXPECT_EQ(s.realtimeStart(100.00, true), RealtimeStart::kWait);
  EXPECT_EQ(s.realtimeStart(100.30, true), RealtimeStart::kWait);
  EXPECT_EQ(s.realtimeStart(100.51, true), RealtimeStart::kStale);
  const DecisionActions d = s.takeDecision();
  EXPECT_EQ(d.hider[0], Action::kStay);  // the silent hider stands still
  EXPECT_EQ(d.seeker[0], Action::kTurnLeft);
  // Its answer, arriving while the step's frames play, is late: it is not applied to the next step.
  EXPECT_TRUE(s.executing());
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 0, 0), Verdict::kLate);
  // An id that answers no step is a wrong step, not a late answer, while the step plays too.
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 9, 0), Verdict::kWrongStep);
  EXPECT_EQ(s.offer(Player::kSeeker, 0, kForwardId, 9, 0), Verdict::kWrongStep);
  s.finishDecision();
  EXPECT_FALSE(s.answered(Player::kHider, 0));
  // The next decision waits its own full timeout.
  EXPECT_EQ(s.realtimeStart(101.00, true), RealtimeStart::kWait);
}

TEST(DecisionScheduler, RealtimeStartsAtOnceWhenAnsweredOrWhenAnAgentIsAbsent) {
  DecisionScheduler s(ClockMode::kRealtime, 1, 0.5, 1.0);
  s.offer(Player::kHider, 0, kForwardId, 0, 0);
  s.offer(Player::kSeeker, 0, kForwardId, 0, 0);
  EXPECT_EQ(s.realtimeStart(5.0, true), RealtimeStart::kReady);
  s.takeDecision();
  s.finishDecision();
  EXPECT_EQ(s.realtimeStart(5.2, false), RealtimeStart::kStale);  // nobody to wait for
}

TEST(DecisionScheduler, TheSeekersLaterDecisionsInAStepNeedTheSeekerAlone) {
  DecisionScheduler s(ClockMode::kLockstep, 2, 0.5, 1.0);
  for (int i = 0; i < 2; ++i) {
    s.offer(Player::kHider, i, kForwardId, 0, 0);
    s.offer(Player::kSeeker, i, kLeftId, 0, 0);
  }
  ASSERT_TRUE(s.complete());
  s.takeDecision();
  // The step goes on: the seeker's decision 1 of the step, with no hider answer.
  EXPECT_FALSE(s.completeFor(Player::kSeeker));
  EXPECT_EQ(s.offer(Player::kSeeker, 0, kForwardId, 0, 1), Verdict::kWrongStep);  // an answer to decision 0
  EXPECT_EQ(s.offer(Player::kSeeker, 0, kForwardId, 1, 1), Verdict::kAccepted);
  EXPECT_FALSE(s.completeFor(Player::kSeeker));
  EXPECT_EQ(s.offer(Player::kSeeker, 1, kLeftId, 1, 1), Verdict::kAccepted);
  ASSERT_TRUE(s.completeFor(Player::kSeeker));
  EXPECT_FALSE(s.complete());  // the hider has not answered a new step
  const std::vector<Action> seeker = s.takeSeekerDecision();
  EXPECT_EQ(seeker, (std::vector<Action>{Action::kForward, Action::kTurnLeft}));
  EXPECT_FALSE(s.completeFor(Player::kSeeker));
}

TEST(DecisionScheduler, RealtimeTakesTheSeekersAnswersWhileTheHidersStepPlays) {
  DecisionScheduler s(ClockMode::kRealtime, 1, 0.5, 1.0);
  s.offer(Player::kHider, 0, kForwardId, 0, 0);
  s.offer(Player::kSeeker, 0, kLeftId, 0, 0);
  ASSERT_EQ(s.realtimeStart(0.0, true), RealtimeStart::kReady);
  s.takeDecision();
  ASSERT_TRUE(s.executing());
  EXPECT_EQ(s.offer(Player::kHider, 0, kForwardId, 0, 0), Verdict::kLate);
  // The seeker's decision 0 plays its frames: an answer to it now is late, not kept for decision 1.
  EXPECT_EQ(s.offer(Player::kSeeker, 0, kForwardId, 0, 0), Verdict::kLate);
  s.finishSeekerDecision();  // its frames played: decision 1 is due
  EXPECT_FALSE(s.answered(Player::kSeeker, 0));
  EXPECT_EQ(s.realtimeSeekerStart(1.0, true), RealtimeStart::kWait);
  EXPECT_EQ(s.offer(Player::kSeeker, 0, kForwardId, 1, 1), Verdict::kAccepted);
  EXPECT_EQ(s.realtimeSeekerStart(1.1, true), RealtimeStart::kReady);
  EXPECT_EQ(s.takeSeekerDecision(), std::vector<Action>{Action::kForward});
  // A silent seeker stands still once stale_action_timeout has passed.
  EXPECT_EQ(s.realtimeSeekerStart(2.0, true), RealtimeStart::kWait);
  EXPECT_EQ(s.realtimeSeekerStart(2.6, true), RealtimeStart::kStale);
  EXPECT_EQ(s.takeSeekerDecision(), std::vector<Action>{Action::kStay});
}

}  // namespace
}  // namespace hideseek_game
