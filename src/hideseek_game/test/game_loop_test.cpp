// The game loop: the exchange the world node serves (offers, decisions, frames) and the in-process
// loop the tools use play the same episodes as arenas stepped one by one; what a decision returns,
// episode bookkeeping, resets, and the rules on answers.
#include "hideseek_game/game_loop.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "test_util.h"

namespace hideseek_game {
namespace {

using test::loadMap;
using test::loadVariant;

// A seeker that acts on its perception and decision index alone, deterministically: it chases a
// hider it sees and otherwise wanders, enough to catch some hiders and to tell two orders of play apart.
Action probeSeeker(const SeekerPerception& p, uint32_t decision) {
  if (p.hider_position) {
    const Vec2 d = *p.hider_position - p.pose.position;
    double turn = std::atan2(d.y, d.x) - p.pose.yaw;
    turn = std::remainder(turn, 2 * M_PI);
    if (std::abs(turn) < 0.3) return Action::kForward;
    return turn > 0 ? Action::kTurnLeft : Action::kTurnRight;
  }
  return decision % 4 == 0 ? Action::kTurnLeft : Action::kForward;
}

GameLoopOptions unrendered(int arenas, uint32_t seed, ClockMode mode = ClockMode::kLockstep) {
  GameLoopOptions o;
  o.mode = mode;
  o.num_arenas = arenas;
  o.seed = seed;
  o.render = false;
  return o;
}

std::vector<Action> randomActions(std::mt19937& rng, int n) {
  std::vector<Action> a(n);
  for (auto& x : a) x = static_cast<Action>(rng() % kNumActions);
  return a;
}

// Answers every arena's pending decision as the seeker node would, from the observation the world
// publishes (the arena's state now) and the step id it must carry.
void answerSeeker(GameLoop& game) {
  for (int i = 0; i < game.numArenas(); ++i) {
    const uint32_t id = game.expectedStepId(Player::kSeeker, i);
    const Action a = probeSeeker(seekerPerception(game.world().arena(i)), id);
    ASSERT_EQ(game.offer(Player::kSeeker, i, static_cast<uint8_t>(a), id), Verdict::kAccepted);
  }
}

// One decision step through the exchange, lockstep: the hider and the seeker answer, the seeker
// again at each of its later decisions.
Decision exchangeStep(GameLoop& game, const std::vector<Action>& hider) {
  for (int i = 0; i < game.numArenas(); ++i) {
    EXPECT_EQ(game.offer(Player::kHider, i, static_cast<uint8_t>(hider[i]), game.expectedStepId(Player::kHider, i)),
              Verdict::kAccepted);
  }
  for (;;) {
    answerSeeker(game);
    EXPECT_TRUE(game.decisionReady());
    game.takeDecision();
    if (std::optional<Decision> d = game.playToNextDecision()) return *d;
    EXPECT_FALSE(game.atStepStart());  // paused inside the step for the seeker's next decision
  }
}

}  // namespace

// The in-process loop (play_episodes, calibration, analysis) and the world node's exchange are
// the same game: equal to each arena stepped alone with the seeker asked at each of its decisions.
TEST(GameLoop, InProcessAndExchangePlayTheEpisodesOfArenasSteppedAlone) {
  VariantConfig v = loadVariant("stochasticmaps");
  v.game.max_steps = 50;
  v.game.seeker_decision_frames = 2;  // three seeker decisions per step
  const auto map = loadMap("stochastic");
  constexpr int kArenas = 3;
  GameLoop in_process(v.game, map, unrendered(kArenas, 20)), exchange(v.game, map, unrendered(kArenas, 20));
  World alone(v.game, map, kArenas, 20, false);
  const ArenaSeekerDecide decide = [&](int i, const SeekerPerception& p) {
    return probeSeeker(p, in_process.world().arena(i).seekerDecisionIndex());
  };
  std::mt19937 rng(5);
  int finished = 0, captured = 0;
  for (int step = 0; step < 300; ++step) {
    const std::vector<Action> hider = randomActions(rng, kArenas);
    const Decision a = in_process.step(hider, decide);
    const Decision b = exchangeStep(exchange, hider);
    EXPECT_EQ(a.index, static_cast<uint64_t>(step));
    EXPECT_EQ(b.index, static_cast<uint64_t>(step));
    EXPECT_EQ(a.hider, hider);
    EXPECT_EQ(a.seeker, b.seeker) << "step " << step;
    for (int i = 0; i < kArenas; ++i) {
      const ArenaStep c = alone.stepArena(
          i, hider[i], [&](const SeekerPerception& p) { return probeSeeker(p, alone.arena(i).seekerDecisionIndex()); });
      for (const Decision* d : {&a, &b}) {
        ASSERT_EQ(d->steps[i].result.outcome, c.result.outcome) << "step " << step << " arena " << i;
        ASSERT_EQ(d->steps[i].result.reward, c.result.reward);
        ASSERT_EQ(d->steps[i].finished.has_value(), c.finished.has_value());
        if (c.finished) {
          ASSERT_EQ(d->steps[i].finished->steps, c.finished->steps);
          ASSERT_EQ(d->steps[i].finished->seed, c.finished->seed);
        }
      }
      if (c.finished) {
        ++finished;
        captured += c.finished->outcome == Outcome::kCaptured;
      }
      for (const GameLoop* g : {&in_process, &exchange}) {
        ASSERT_EQ(g->world().arena(i).seeker().position.x, alone.arena(i).seeker().position.x);
        ASSERT_EQ(g->world().arena(i).hider().yaw, alone.arena(i).hider().yaw);
        ASSERT_EQ(g->world().arena(i).seed(), alone.arena(i).seed());
      }
      EXPECT_EQ(in_process.rewards()[i], static_cast<float>(c.result.reward));
      EXPECT_EQ(in_process.done()[i], c.result.done());
    }
  }
  // Both endings happen, so both paths through a step's end were compared.
  EXPECT_GT(captured, 3);
  EXPECT_GT(finished - captured, 3);
  EXPECT_EQ(in_process.decisions(), 300u);
}

TEST(GameLoop, ArenasPlayTheirSeedSequencesAndReportEachFinishedEpisode) {
  VariantConfig v = loadVariant("basic");
  v.game.max_steps = 5;  // every episode survives after 5 steps unless caught
  GameLoop game(v.game, loadMap("deterministic"), unrendered(2, 100));
  const ArenaSeekerDecide stay = [](int, const SeekerPerception&) { return Action::kStay; };
  std::vector<uint32_t> seeds[2];
  for (int step = 0; step < 15; ++step) {
    const Decision d = game.step({Action::kStay, Action::kStay}, stay);
    for (int i = 0; i < 2; ++i) {
      if (!d.steps[i].finished) continue;
      EXPECT_EQ(d.steps[i].finished->outcome, Outcome::kSurvived);
      EXPECT_EQ(d.steps[i].finished->steps, 5);
      seeds[i].push_back(d.steps[i].finished->seed);
      EXPECT_EQ(game.world().arena(i).stepCount(), 0);  // the next episode has begun
    }
  }
  EXPECT_EQ(seeds[0], (std::vector<uint32_t>{100, 102, 104}));
  EXPECT_EQ(seeds[1], (std::vector<uint32_t>{101, 103, 105}));
  EXPECT_EQ(game.outcomes()[0], static_cast<uint8_t>(Outcome::kSurvived));
  EXPECT_EQ(game.done()[1], 1);
}

TEST(GameLoop, RefusesAnswersToAnotherStepAndTheHiderInsideAStep) {
  VariantConfig v = loadVariant("basic");
  GameLoop game(v.game, loadMap("deterministic"), unrendered(1, 0));
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, 3), Verdict::kWrongStep);
  EXPECT_EQ(game.offer(Player::kHider, 0, kNumActions, 0), Verdict::kInvalidAction);
  EXPECT_FALSE(game.decisionReady());
  ASSERT_EQ(game.offer(Player::kHider, 0, 1, 0), Verdict::kAccepted);
  EXPECT_FALSE(game.decisionReady());  // the seeker has not answered
  answerSeeker(game);
  ASSERT_TRUE(game.decisionReady());
  game.takeDecision();
  EXPECT_THROW(game.takeDecision(), std::logic_error);
  EXPECT_FALSE(game.playToNextDecision());  // the seeker decides every frame: paused after one
  EXPECT_EQ(game.expectedStepId(Player::kHider, 0), kNoStep);
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, 1), Verdict::kWrongStep);
  EXPECT_EQ(game.expectedStepId(Player::kSeeker, 0), 1u);  // its second decision of the episode
  EXPECT_FALSE(game.decisionReady());
}

TEST(GameLoop, RealtimeRefusesTheHidersAnswerWhileAStepPlaysAndStartsWithoutASilentAgent) {
  VariantConfig v = loadVariant("basic");
  GameLoopOptions o = unrendered(1, 0, ClockMode::kRealtime);
  o.stale_action_timeout = 0.5;
  GameLoop game(v.game, loadMap("deterministic"), o);
  ASSERT_EQ(game.offer(Player::kHider, 0, 1, 0), Verdict::kAccepted);
  EXPECT_EQ(game.realtimeStart(10.0, true, true), RealtimeStart::kWait);  // the seeker may still answer
  EXPECT_EQ(game.realtimeStart(10.6, true, true), RealtimeStart::kStale);
  game.takeDecision();
  EXPECT_FALSE(game.playFrame());
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, 0), Verdict::kLate);       // an answer to the step playing
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, 1), Verdict::kWrongStep);  // step 1 was never asked
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, 77), Verdict::kWrongStep);
  // Inside the step only the seeker is waited for, and an absent seeker not at all.
  EXPECT_EQ(game.realtimeStart(11.0, false, false), RealtimeStart::kStale);
  std::optional<Decision> d;
  for (int frame = 1; frame < v.game.action_repeat; ++frame) {
    ASSERT_TRUE(game.decisionDue());
    game.takeDecision();
    d = game.playFrame();
  }
  ASSERT_TRUE(d);
  EXPECT_EQ(d->hider[0], Action::kForward);
  EXPECT_EQ(d->seeker[0], Action::kStay);  // the silent seeker stood still
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, 1), Verdict::kAccepted);
}

// A capture ends an arena's step early while the step's frames play on (here: a capture distance
// that catches every arena in the step's first frame): the step it was playing still counts as
// playing, so the hider's answer to it is late and one to the next step a wrong step.
TEST(GameLoop, RealtimeCountsAnAnswerToAStepACaptureEndedEarlyAsLate) {
  VariantConfig v = loadVariant("basic");
  v.game.capture_distance = 1000.0;  // every arena is caught in its first frame
  GameLoopOptions o = unrendered(2, 0, ClockMode::kRealtime);
  GameLoop game(v.game, loadMap("deterministic"), o);
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(game.offer(Player::kHider, i, 1, 0), Verdict::kAccepted);
  }
  ASSERT_EQ(game.realtimeStart(0.0, true, false), RealtimeStart::kStale);  // no seeker node
  game.takeDecision();
  ASSERT_FALSE(game.playFrame());  // caught, but the step's frames play on
  ASSERT_EQ(game.world().arena(0).stepCount(), 1);
  EXPECT_EQ(game.world().stepPlaying(0), 0);
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, 0), Verdict::kLate);
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, 1), Verdict::kWrongStep);
}

// A seeker that decides once a step (a learned one, or one of your own with seeker_decides:=step)
// and answers after stale_action_timeout: its answer is late, as the hider's is, and is not played
// in the next step in place of the answer to that step.
TEST(GameLoop, RealtimeRefusesALateAnswerOfASeekerThatDecidesOnceAStep) {
  VariantConfig v = loadVariant("basic");
  GameLoopOptions o = unrendered(1, 0, ClockMode::kRealtime);
  o.stale_action_timeout = 0.5;
  GameLoop game(withLearnedSeeker(v.game), loadMap("deterministic"), o);
  ASSERT_EQ(game.offer(Player::kHider, 0, 1, 0), Verdict::kAccepted);
  EXPECT_EQ(game.realtimeStart(10.0, true, true), RealtimeStart::kWait);
  EXPECT_EQ(game.realtimeStart(10.6, true, true), RealtimeStart::kStale);  // the seeker is slow
  game.takeDecision();
  EXPECT_FALSE(game.playFrame());
  EXPECT_EQ(game.offer(Player::kSeeker, 0, 3, 0), Verdict::kLate);  // its answer to step 0, too late
  std::optional<Decision> d;
  while (!(d = game.playFrame())) ASSERT_FALSE(game.decisionDue());  // one decision for the whole step
  EXPECT_EQ(d->seeker[0], Action::kStay);
  EXPECT_FALSE(game.answered(Player::kSeeker, 0));  // nothing kept for step 1
  EXPECT_EQ(game.offer(Player::kSeeker, 0, 4, 1), Verdict::kAccepted);
}

TEST(GameLoop, AResetInsideAStepPlaysItToItsEndFirst) {
  VariantConfig v = loadVariant("basic");
  GameLoop game(v.game, loadMap("deterministic"), unrendered(2, 7));
  for (int i = 0; i < 2; ++i) ASSERT_EQ(game.offer(Player::kHider, i, 1, 0), Verdict::kAccepted);
  answerSeeker(game);
  game.takeDecision();
  ASSERT_FALSE(game.playToNextDecision());
  ASSERT_FALSE(game.atStepStart());
  const Vec2 before = game.world().arena(1).hider().position;
  const std::optional<Decision> d = game.reset(0, 500);
  ASSERT_TRUE(d);  // the step in progress, played to its end
  EXPECT_EQ(d->index, 0u);
  EXPECT_EQ(game.decisions(), 1u);
  EXPECT_TRUE(game.atStepStart());
  EXPECT_EQ(game.world().arena(0).seed(), 500u);
  EXPECT_EQ(game.world().arena(0).stepCount(), 0);
  EXPECT_EQ(game.world().arena(1).stepCount(), 1);                           // the other arena keeps its episode
  EXPECT_GT(distance(game.world().arena(1).hider().position, before), 0.0);  // moved the whole step
  EXPECT_FALSE(game.reset(-1, -1));                                          // nothing in progress now
  EXPECT_EQ(game.world().arena(0).seed(), 502u);  // the sequence continues from the seed used
  EXPECT_EQ(game.world().arena(1).seed(), 10u);   // 8, then 8 + 2 arenas
}

// The world node's world/reset: an agent may have answered the step the reset arena awaited
// before it sees the reset. That one answer is dropped as overtaken, not refused as a wrong step.
TEST(GameLoop, AnAnswerToTheStepAResetOvertookIsDroppedAsSuperseded) {
  VariantConfig v = loadVariant("basic");
  GameLoop game(v.game, loadMap("deterministic"), unrendered(2, 7));
  exchangeStep(game, {Action::kForward, Action::kForward});
  const uint32_t hider_id = game.expectedStepId(Player::kHider, 0);
  const uint32_t seeker_id = game.expectedStepId(Player::kSeeker, 0);
  ASSERT_EQ(hider_id, 1u);
  EXPECT_FALSE(game.reset(0, 500));
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, hider_id), Verdict::kSupersededByReset);
  EXPECT_EQ(game.offer(Player::kSeeker, 0, 1, seeker_id), Verdict::kSupersededByReset);
  EXPECT_EQ(game.offer(Player::kHider, 0, 1, hider_id), Verdict::kWrongStep) << "a second answer is a fault";
  EXPECT_EQ(game.offer(Player::kHider, 1, 1, 0), Verdict::kWrongStep) << "arena 1 was not reset";
  // Inside a step the hider awaits nothing, so a reset there drops none of its answers.
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(game.offer(Player::kHider, i, 1, game.expectedStepId(Player::kHider, i)), Verdict::kAccepted);
  }
  answerSeeker(game);
  game.takeDecision();
  ASSERT_FALSE(game.playToNextDecision());
  ASSERT_EQ(game.expectedStepId(Player::kHider, 1), kNoStep);
  ASSERT_TRUE(game.reset(1, 600));  // plays arena 1's step 1 to its end first: it would next await step 2
  EXPECT_EQ(game.offer(Player::kHider, 1, 1, 2), Verdict::kWrongStep) << "awaited is taken before the step ends";
}

TEST(GameLoop, AResetOfAnArenaOrSeedOutOfRangeIsRefusedAndChangesNothing) {
  VariantConfig v = loadVariant("basic");
  GameLoop game(v.game, loadMap("deterministic"), unrendered(2, 7));
  game.step({Action::kForward, Action::kForward}, [](int, const SeekerPerception&) { return Action::kStay; });
  for (int i = 0; i < 2; ++i) ASSERT_EQ(game.offer(Player::kHider, i, 1, 1), Verdict::kAccepted);
  try {
    game.reset(2, -1);
    FAIL() << "arena 2 of 2 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "arena 2 does not exist (0..1, or -1 for all)");
  }
  EXPECT_THROW(game.reset(0, int64_t{1} << 32), std::invalid_argument);
  EXPECT_EQ(game.world().arena(0).stepCount(), 1);
  EXPECT_TRUE(game.answered(Player::kHider, 1));
}

TEST(GameLoop, RendersTheHiderViewsAfterEveryDecision) {
  VariantConfig v = loadVariant("basic");
  GameLoopOptions o = unrendered(2, 3);
  o.render = true;
  o.render_threads = 1;
  GameLoop game(v.game, loadMap("deterministic"), o);
  ASSERT_EQ(game.hiderImages().size(), 2 * game.world().imageBytes());
  const std::vector<uint8_t> first = game.hiderImages();
  game.step({Action::kTurnLeft, Action::kTurnLeft}, [](int, const SeekerPerception&) { return Action::kStay; });
  EXPECT_NE(game.hiderImages(), first);  // the hiders turned: their views changed
  std::vector<uint8_t> expected(2 * game.world().imageBytes());
  game.world().renderHiderViews(expected.data());
  EXPECT_EQ(game.hiderImages(), expected);
}

namespace {

// A learning seeker plays: every arena's seeker view is rendered after each decision (its input),
// with its rewards, the hider's mirrored: -0.001 a step, +1 on capture. A game whose seeker
// decides inside a step is refused (a learning seeker decides once a step: withLearnedSeeker).
TEST(GameLoop, ALearningSeekerGetsItsViewsAndRewards) {
  VariantConfig v = loadVariant("basic");
  GameLoopOptions o = unrendered(2, 3);
  o.render = true;
  o.render_seeker = true;
  o.render_threads = 1;
  EXPECT_THROW(GameLoop(v.game, loadMap("deterministic"), o), std::invalid_argument);
  const GameOptions game_options = withLearnedSeeker(v.game);
  EXPECT_EQ(game_options.seekerDecisionsPerStep(), 1);
  GameLoop game(game_options, loadMap("deterministic"), o);
  ASSERT_EQ(game.seekerImages().size(), 2 * game.world().imageBytes());
  int asked = 0;
  game.step({Action::kStay, Action::kStay}, [&](int, const SeekerPerception&) {
    ++asked;
    return Action::kTurnLeft;
  });
  EXPECT_EQ(asked, 2);  // once per arena and step
  std::vector<uint8_t> expected(2 * game.world().imageBytes());
  game.world().renderSeekerViews(expected.data());
  EXPECT_EQ(game.seekerImages(), expected);
  std::vector<uint8_t> one(game.world().imageBytes());
  game.world().renderSeekerView(1, one.data());
  EXPECT_TRUE(std::equal(one.begin(), one.end(), game.seekerImages().begin() + one.size()));
  for (int i = 0; i < 2; ++i) {
    EXPECT_FLOAT_EQ(game.seekerRewards()[i], -0.001f);
    EXPECT_FLOAT_EQ(game.rewards()[i], 0.001f);
  }
  // Chase the standing hiders: the capture pays +1.
  std::vector<bool> captured(2, false);
  for (uint32_t step = 1; step < 400 && !(captured[0] && captured[1]); ++step) {
    game.step({Action::kStay, Action::kStay}, [&](int, const SeekerPerception& p) { return probeSeeker(p, step); });
    for (int i = 0; i < 2; ++i) {
      if (game.outcomes()[i] != static_cast<uint8_t>(Outcome::kCaptured) || captured[i]) continue;
      captured[i] = true;
      EXPECT_FLOAT_EQ(game.seekerRewards()[i], 1.0f);
      EXPECT_FLOAT_EQ(game.rewards()[i], -1.0f);
    }
  }
  EXPECT_TRUE(captured[0] && captured[1]);
}

}  // namespace
}  // namespace hideseek_game
