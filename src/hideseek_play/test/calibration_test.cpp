// Holds the calibration of the game (docs/calibration.md): over the evaluation seeds 0..99, the
// random hider lives about as long as in the paper, backing away in view does not win, and
// hiding pays. Deterministic given the seeds (no rendering, no timing), so the checks are stable.
// The game file is HIDESEEK_GAME_FILE when set (config/game_v1.yaml must fail these checks),
// else config/game.yaml.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <set>
#include <string>

#include "hideseek_game/arena.h"
#include "hideseek_play/orbit.h"
#include "hideseek_play/scripted_game.h"

namespace hideseek_play {
namespace {

using hideseek_hider::evaderName;
using hideseek_hider::kAllEvaders;
using hideseek_seeker::seekerOptionsFor;
using hideseek_seeker::SeekerPolicy;

const std::string kConfig = HIDESEEK_CONFIG_DIR;

std::string gameFile() {
  const char* game = std::getenv("HIDESEEK_GAME_FILE");
  return game && *game ? game : kConfig + "/game.yaml";
}

hideseek_game::VariantConfig variant(const std::string& name) {
  return hideseek_game::loadVariantConfig(gameFile(), kConfig + "/variants/" + name + ".yaml");
}

std::vector<ScriptedEpisode> play(const std::string& name, EvaderKind evader, uint32_t first = 0, int n = 100,
                                  const EvaderOptions& options = {}) {
  const auto v = variant(name);
  const auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file));
  return playScriptedHider(v, map, evader, first, n, {}, options);
}

std::string describe(const std::string& variant_name, EvaderKind evader, const ScriptedSummary& s) {
  return variant_name + " " + evaderName(evader) + ": " + std::to_string(s.avg_living_steps) + " living steps, " +
         std::to_string(100.0 * s.success_rate) + " % success (game " + gameFile() + ")";
}

}  // namespace

// The random hider within +-20 % of the paper's random column, success at most 2 %. Variants whose
// random hider plays the same game are checked once; visibilityreward_faster shares fasterhider's
// game but the paper's figure is 20 % lower (35 against 42): docs/calibration.md reports it.
TEST(Calibration, RandomHiderLivesAsLongAsInThePaper) {
  const YAML::Node paper = YAML::LoadFile(kConfig + "/paper_reference.yaml")["variants"];
  for (const std::string name : {"basic", "fasterhider", "slowerhider", "stochasticseeker", "stochasticmaps"}) {
    const ScriptedSummary s = summarize(play(name, EvaderKind::kRandom));
    const double reference = paper[name]["living_random"].as<double>();
    EXPECT_NEAR(s.avg_living_steps, reference, 0.2 * reference) << describe(name, EvaderKind::kRandom, s);
    EXPECT_LE(s.success_rate, 0.02) << describe(name, EvaderKind::kRandom, s);
  }
}

// Backing away in view, the strategy every hider of game v1 found, must not win the game.
TEST(Calibration, BackpedalRarelySurvivesOnBasic) {
  const ScriptedSummary s = summarize(play("basic", EvaderKind::kBackpedal));
  RecordProperty("backpedal_avg_living_steps", std::to_string(s.avg_living_steps));
  EXPECT_LE(s.success_rate, 0.15) << describe("basic", EvaderKind::kBackpedal, s);
}

// Lapping the outer ring backward, facing the seeker, was what the first pilot of game v2 learned
// (840 living steps, 83 % success on its first map, where the lap evader survived 97 %). The map's
// third revision cuts that ring twice with bars, into two halves: a lapping hider must turn back
// along a half, and the scripted lap evader, which reads the true state, must not survive more
// often than the pilot's upper bound for a learner (70 %; 46 % on the validation seeds).
TEST(Calibration, LappingTheOuterRingDoesNotWin) {
  const ScriptedSummary s = summarize(play("basic", EvaderKind::kLap));
  RecordProperty("lap_avg_living_steps", std::to_string(s.avg_living_steps));
  EXPECT_LE(s.success_rate, 0.70) << describe("basic", EvaderKind::kLap, s);
}

// The lap evader does lap: on the loop round the central cross (2.5 m), the hider, faster than the
// seeker, survives most episodes (74 % on the map's second revision). Validation seeds
// 1000..1049. Were it to stand still or run into walls, the bound above would hold for nothing.
TEST(Calibration, LapSurvivesOnTheLoopRoundTheCross) {
  EvaderOptions round_the_cross;
  round_the_cross.lap_radius = 2.5;
  const ScriptedSummary s = summarize(play("basic", EvaderKind::kLap, 1000, 50, round_the_cross));
  EXPECT_GE(s.success_rate, 0.5) << describe("basic", EvaderKind::kLap, s) << ", lap radius 2.5 m";
}

// Occlusion pays: hiding outlives backing away on basic, and running on slowerhider.
TEST(Calibration, HidingPays) {
  const ScriptedSummary hide = summarize(play("basic", EvaderKind::kHide));
  const ScriptedSummary backpedal = summarize(play("basic", EvaderKind::kBackpedal));
  EXPECT_GT(hide.avg_living_steps, backpedal.avg_living_steps)
      << describe("basic", EvaderKind::kHide, hide) << " against "
      << describe("basic", EvaderKind::kBackpedal, backpedal);
  const ScriptedSummary slow_hide = summarize(play("slowerhider", EvaderKind::kHide));
  const ScriptedSummary slow_flee = summarize(play("slowerhider", EvaderKind::kFlee));
  EXPECT_GT(slow_hide.avg_living_steps, slow_flee.avg_living_steps)
      << describe("slowerhider", EvaderKind::kHide, slow_hide) << " against "
      << describe("slowerhider", EvaderKind::kFlee, slow_flee);
}

// The paper's state space is in play: over the scripted hiders' episodes on basic, the states
// (S, H, O) occur with and without an obstacle in view (in game v1 O was 1 in every state: its
// corner cuts were obstacles seen from everywhere), and at least half of the 56 transitions
// between distinct states occur.
TEST(Calibration, ThePapersStateSpaceIsInPlay) {
  std::array<long, 8> count{};
  std::set<std::pair<int, int>> transitions;
  for (EvaderKind evader : kAllEvaders) {
    int previous = -1;
    uint32_t previous_seed = 0;
    const auto v = variant("basic");
    const auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file));
    playScriptedHider(v, map, evader, 0, 100, [&](const ScriptedStep& s) {
      const int state = 4 * s.labels.hider_sees_seeker + 2 * s.labels.seeker_sees_hider + s.labels.obstacle_in_view;
      ++count[state];
      if (previous >= 0 && s.seed == previous_seed && previous != state) transitions.insert({previous, state});
      previous = state;
      previous_seed = s.seed;
    });
  }
  int with_obstacle = 0, without_obstacle = 0;
  std::string counts;
  for (int state = 0; state < 8; ++state) {
    (state & 1 ? with_obstacle : without_obstacle) += count[state] > 0;
    counts += " S" + std::to_string(state >> 2) + "H" + std::to_string((state >> 1) & 1) + "O" +
              std::to_string(state & 1) + "=" + std::to_string(count[state]);
  }
  EXPECT_EQ(with_obstacle, 4) << "states seen:" << counts << " (game " << gameFile() << ")";
  EXPECT_GE(without_obstacle, 3) << "states seen:" << counts << " (game " << gameFile() << ")";
  EXPECT_GE(transitions.size(), 28u) << transitions.size() << " of 56 transitions occur (game " << gameFile() << ")";
}

TEST(Calibration, PlayingIsDeterministicGivenTheSeeds) {
  for (EvaderKind evader : kAllEvaders) {
    const auto a = play("stochasticmaps", evader, 40, 10), b = play("stochasticmaps", evader, 40, 10);
    ASSERT_EQ(a.size(), 10u);
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].seed, 40 + i);
      EXPECT_EQ(a[i].living_steps, b[i].living_steps) << evaderName(evader) << " seed " << a[i].seed;
    }
  }
}

TEST(Calibration, SummaryCountsMedianAndRates) {
  const ScriptedSummary s =
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
  for (const std::string v : {"basic", "slowerhider", "stochasticseeker"}) {
    const auto config = variant(v);
    const auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(config.map_file));
    hideseek_game::Arena arena(config.game, map);
    SeekerPolicy seeker(seekerOptionsFor(config));
    const hideseek_game::SeekerDecide decide = [&](const hideseek_game::SeekerPerception& p) { return seeker.act(p); };
    int seen_episodes = 0;
    for (uint32_t seed = 1000; seed < 1200; ++seed) {
      arena.reset(seed);
      seeker.reset(arena.layout(), seed);
      int first_seen = -1;
      hideseek_game::StepResult r;
      do {
        if (first_seen < 0 && arena.stepCount() >= static_cast<int>(seed % 60) && arena.labels().seeker_sees_hider)
          first_seen = arena.stepCount();
        const int run = static_cast<int>(seed % 60);
        const auto hider_action = arena.stepCount() < run ? hideseek_game::Action::kForward
                                  : arena.stepCount() % 2 ? hideseek_game::Action::kBackward
                                                          : hideseek_game::Action::kForward;
        r = hideseek_game::playDecisionStep(arena, hider_action, decide);
      } while (!r.done());
      if (first_seen < 0) continue;
      ++seen_episodes;
      EXPECT_EQ(r.outcome, hideseek_game::Outcome::kCaptured)
          << v << " seed " << seed << ": seen at step " << first_seen << ", seeker left at ("
          << arena.seeker().position.x << ", " << arena.seeker().position.y << "), hider at ("
          << arena.hider().position.x << ", " << arena.hider().position.y << "), "
          << hideseek_game::distance(arena.seeker().position, arena.hider().position) << " m apart, mode "
          << modeName(seeker.mode()) << ", path of " << seeker.path().size() << " points";
    }
    EXPECT_GE(seen_episodes, 50) << v;
  }
}

}  // namespace hideseek_play

// The orbit study (hideseek_play/orbit.h), independent of HIDESEEK_GAME_FILE: game v3's seeker,
// which moves while it turns, catches a hider circling in the open no faster than itself, from
// every start angle; game v2's turn-or-move seeker, slowed by its turns, trails such an orbit for
// good once it is wide enough that the capture distance does not reach across (k = 3, radius
// 1.92 m). Wider orbits, where the hider's mean speed exceeds the seeker's, may survive in either
// game: the hider is the faster agent.
namespace hideseek_play {
namespace {

hideseek_game::VariantConfig gameVariant(const std::string& game, const std::string& name) {
  return hideseek_game::loadVariantConfig(kConfig + "/game" + (game == "v2" ? "" : "_" + game) + ".yaml",
                                          kConfig + "/variants/" + name + ".yaml");
}

}  // namespace

TEST(Orbit, GameV3sSeekerCatchesTheTightOrbitsFromEveryStartAngle) {
  const auto v3 = gameVariant("v3", "basic");
  for (const int k : {1, 2, 3}) {
    const OrbitShape shape{k};
    ASSERT_LE(orbitSpeed(v3.game, shape), v3.game.seeker.speed) << "a tight orbit is no faster than the seeker";
    for (const auto& e : playOrbitAngles(v3, shape, 12)) {
      EXPECT_FALSE(e.survived) << "k " << k << " (radius " << orbitRadius(v3.game, shape) << " m), start angle "
                               << e.start_angle_deg << ": the v3 seeker never caught the circling hider";
    }
  }
}

// A circle that, with the seeker's start gap, would not fit in the arena is refused, not played
// with the seeker started inside a wall.
TEST(Orbit, ACircleThatDoesNotFitIsRefused) {
  const auto v3 = gameVariant("v3", "basic");
  EXPECT_NO_THROW(playOrbit(v3, OrbitShape{5}, 0.0));
  EXPECT_THROW(playOrbit(v3, OrbitShape{6}, 0.0), std::invalid_argument);
}

// The same orbit against game v2's seeker: the figure the exploit rested on, and what makes the
// v3 check above meaningful (an orbit no seeker could survive would prove nothing).
TEST(Orbit, GameV2sSeekerLetsATightOrbitSurvive) {
  const auto v2 = gameVariant("v2", "basic");
  int survived = 0;
  for (const auto& e : playOrbitAngles(v2, OrbitShape{3}, 12)) survived += e.survived;
  EXPECT_GT(survived, 0) << "game v2's seeker caught the k = 3 orbit from all 12 start angles";
}

}  // namespace hideseek_play

// The scripted seeker's stalls (docs/calibration.md, "The scripted seeker's stalls"). The seeker
// drops only its path's next point once within reach of it; a point it passed further off stays on
// its path, with every point after it, and the target can flip between a point inside its turning
// circle and a later one as a 3 cm step gives or takes the later one's straight line. Game v3's
// wandering seeker, which turns while it moves, then spins on the spot for the rest of the episode
// (seed 46 of stochasticseeker against scripted/hide: 8 cm from a point it cannot reach), and a
// hider that is nowhere near survives. seeker.path_following: no_backtrack drops every point up to
// the last one reached and every point before the one it heads for; games v1-v3 keep next_point, so
// that what was trained and recorded on them replays.
namespace hideseek_play {
namespace {

// The first step of a window of `window` steps in which the seeker never sees the hider and its
// positions span less than `still` metres on each axis (a stall), or -1.
int stallStart(const hideseek_game::VariantConfig& v, uint32_t seed, int window = 200, double still = 0.05) {
  const auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file));
  std::vector<ScriptedStep> steps;
  playScriptedHider(v, map, EvaderKind::kHide, seed, 1, [&](const ScriptedStep& s) { steps.push_back(s); });
  for (size_t i = 0; i + window < steps.size(); ++i) {
    double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9;
    bool seen = false;
    for (size_t j = i; j <= i + window; ++j) {
      const auto& p = steps[j].seeker.position;
      min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
      seen = seen || steps[j].labels.seeker_sees_hider;
    }
    if (!seen && max_x - min_x < still && max_y - min_y < still) return steps[i].step;
  }
  return -1;
}

}  // namespace

TEST(SeekerStall, GameV3sWanderingSeekerCirclesAPassedPathPointUnlessItNeverBacktracks) {
  auto v = gameVariant("v3", "stochasticseeker");
  ASSERT_EQ(v.game.seeker_path_following, hideseek_game::SeekerPathFollowing::kNextPoint)
      << "game v3 must replay as it was trained";
  const int before = stallStart(v, 46);
  EXPECT_GE(before, 0) << "seed 46 no longer stalls in game v3: the game changed, or this seed "
                          "no longer shows the stall and the test needs another";
  v.game.seeker_path_following = hideseek_game::SeekerPathFollowing::kNoBacktrack;
  const int after = stallStart(v, 46);
  EXPECT_LT(after, 0) << "the seeker stands still from step " << after << " although it never backtracks";
}

// The other face of the same rule: the patrolling seeker on a maze passes round a wall's end within
// reach of a later path point but not of the first, which stays its target once the later ones
// are out of sight, behind the wall it has just gone round: it drives against that wall for the
// rest of the episode (seed 8 of scripted/hide from step 119).
TEST(SeekerStall, GameV3sPatrollingSeekerPressesAgainstAWallOnAMazeUnlessItNeverBacktracks) {
  auto v = gameVariant("v3", "basic");
  v.map_file = std::string(HIDESEEK_TEST_DATA_DIR) + "/serpentine_map.yaml";
  const int before = stallStart(v, 8);
  EXPECT_GE(before, 0) << "seed 8 no longer stalls on the maze in game v3";
  v.game.seeker_path_following = hideseek_game::SeekerPathFollowing::kNoBacktrack;
  const int after = stallStart(v, 8);
  EXPECT_LT(after, 0) << "the seeker stands still from step " << after << " although it never backtracks";
}

}  // namespace hideseek_play
