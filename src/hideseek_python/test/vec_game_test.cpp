// The Python environment's C++ core: it plays the game's episodes (the calibration's, for scripted
// hiders), is reproducible from seeds and actions, and refuses bad input without changing anything.
#include "hideseek_python/vec_game.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <vector>

#include "hideseek_game/config_error.h"
#include "hideseek_game/map.h"
#include "hideseek_play/scripted_game.h"

using hideseek_python::VecGame;

namespace {

hideseek_game::VariantConfig variant(const std::string& name) {
  return hideseek_python::loadVariant(HIDESEEK_CONFIG_DIR, "v2", name);
}

// Plays `kind` in every arena until `episodes` episodes of arena 0 ended; their living steps.
std::vector<int> playArena0(VecGame& game, hideseek_hider::EvaderKind kind, int episodes) {
  std::vector<int> steps;
  while (static_cast<int>(steps.size()) < episodes) {
    game.step(game.scriptedActions(kind));
    if (game.finished(0)) steps.push_back(game.finished(0)->steps);
  }
  return steps;
}

}  // namespace

// A scripted hider played through the environment lives exactly as long as in the calibration
// table's in-process game (playScriptedHider), episode by episode: the same game, seeker and evader.
TEST(VecGame, ScriptedHidersPlayTheCalibrationsEpisodes) {
  for (const auto& [name, kind] : {std::pair{"stochasticseeker", hideseek_hider::EvaderKind::kFlee},
                                   std::pair{"basic", hideseek_hider::EvaderKind::kRandom}}) {
    const hideseek_game::VariantConfig v = variant(name);
    VecGame game(v, 1, 0, 1);
    const std::vector<int> got = playArena0(game, kind, 3);
    const auto expected = hideseek_play::playScriptedHider(
        v, std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file)), kind, 0, 3);
    ASSERT_EQ(expected.size(), 3u);
    for (int e = 0; e < 3; ++e) EXPECT_EQ(got[e], expected[e].living_steps) << name << " episode " << e;
  }
}

// The same seeds and actions give the same images, rewards and states; reset(seed) starts over.
TEST(VecGame, SameSeedsAndActionsGiveTheSameSteps) {
  const hideseek_game::VariantConfig v = variant("basic");
  VecGame a(v, 3, 40, 1), b(v, 3, 40, 1);
  const std::vector<uint8_t> first = a.observations();
  for (int t = 0; t < 30; ++t) {
    const std::vector<uint8_t> actions = {uint8_t(t % 5), uint8_t((t / 2) % 5), 1};
    a.step(actions);
    b.step(actions);
    ASSERT_EQ(a.observations(), b.observations()) << "step " << t;
    ASSERT_EQ(a.rewards(), b.rewards());
    ASSERT_EQ(a.info(2).hider_pose[0], b.info(2).hider_pose[0]);
  }
  EXPECT_NE(a.observations(), first);
  a.reset({40});
  EXPECT_EQ(a.observations(), first);
  EXPECT_EQ(a.info(1).seed, 41u);
  EXPECT_EQ(a.info(1).step, 0u);
}

TEST(VecGame, SeedsPerEnvironmentOneSeedOrTheNextOnes) {
  VecGame game(variant("basic"), 2, 0, 1);
  EXPECT_EQ(game.info(0).seed, 0u);
  EXPECT_EQ(game.info(1).seed, 1u);
  game.reset({5, 9});
  EXPECT_EQ(game.info(0).seed, 5u);
  EXPECT_EQ(game.info(1).seed, 9u);
  game.reset({7});
  EXPECT_EQ(game.info(0).seed, 7u);
  EXPECT_EQ(game.info(1).seed, 8u);
  game.reset({});  // episodes not yet stepped are kept: no seed of the sequence is skipped
  EXPECT_EQ(game.info(0).seed, 7u);
  game.step({0, 0});
  game.reset({});  // each arena's next seed: 7 + 2 and 8 + 2
  EXPECT_EQ(game.info(0).seed, 9u);
  EXPECT_EQ(game.info(1).seed, 10u);
}

// An ended episode's terminal state is rendered exactly as the batch shows that state: a twin game
// whose episodes last longer observes the same state one step later, arena by arena (8 arenas: the
// tiles differ), on the ended episode's layout (stochasticmaps draws one each episode), on both
// sides; the observation itself is already the next episode's first image.
TEST(VecGame, AnEndedEpisodesTerminalStateIsTheImageTheBatchShows) {
  namespace hg = hideseek_game;
  const hg::VariantConfig v = hideseek_python::loadVariant(HIDESEEK_CONFIG_DIR, "v3", "stochasticmaps");
  hg::VariantConfig short_episodes = v;
  short_episodes.game.max_steps = 7;
  for (const bool seeker_side : {false, true}) {
    VecGame ended(short_episodes, 8, 1000, 1, seeker_side), going(v, 8, 1000, 1, seeker_side);
    ended.keepTerminalViews(seeker_side);
    for (int t = 0; t < 7; ++t) {
      const std::vector<uint8_t> hider = going.scriptedActions(hideseek_hider::EvaderKind::kRandom);
      if (seeker_side) {
        const std::vector<uint8_t> seeker = going.randomSeekerActions();
        ended.step(hider, seeker);
        going.step(hider, seeker);
      } else {
        ended.step(hider);
        going.step(hider);
      }
    }
    const std::vector<uint8_t>& shown = seeker_side ? going.seekerObservations() : going.observations();
    const std::vector<uint8_t>& next = seeker_side ? ended.seekerObservations() : ended.observations();
    const size_t bytes = shown.size() / 8;
    int compared = 0;
    for (int i = 0; i < 8; ++i) {
      if (!ended.finished(i) || ended.finished(i)->steps != 7) continue;  // caught earlier in both
      ASSERT_EQ(going.info(i).step, 7u);
      ++compared;
      const auto at = [&](const std::vector<uint8_t>& images) { return images.begin() + bytes * i; };
      EXPECT_TRUE(std::equal(at(shown), at(shown) + bytes, at(ended.terminalObservations())))
          << "arena " << i << (seeker_side ? ", seeker's camera" : ", hider's camera");
      EXPECT_FALSE(std::equal(at(shown), at(shown) + bytes, at(next))) << "the next episode's first image";
    }
    EXPECT_GE(compared, 6) << (seeker_side ? "seeker" : "hider");
  }
  EXPECT_THROW(VecGame(v, 1, 0, 1).keepTerminalViews(true), std::invalid_argument);  // no seeker camera
}

TEST(VecGame, BadInputIsRefusedAndChangesNothing) {
  VecGame game(variant("basic"), 2, 0, 1);
  const std::vector<uint8_t> before = game.observations();
  EXPECT_THROW(game.step({1}), std::invalid_argument);
  EXPECT_THROW(game.step({1, 5}), std::invalid_argument);
  EXPECT_THROW(game.reset({1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(game.reset({-1}), std::invalid_argument);
  EXPECT_THROW(game.reset({int64_t{UINT32_MAX}}), std::invalid_argument);  // the second arena's seed overflows
  EXPECT_THROW(game.resetEnv(2, 0), std::invalid_argument);
  EXPECT_EQ(game.decisions(), 0u);
  EXPECT_EQ(game.observations(), before);
  EXPECT_EQ(game.info(1).seed, 1u);
  EXPECT_THROW(VecGame(variant("basic"), 0, 0, 1), std::invalid_argument);
  EXPECT_THROW(VecGame(variant("basic"), 65, 0, 1), std::invalid_argument);
  EXPECT_THROW(hideseek_python::loadVariant(HIDESEEK_CONFIG_DIR, "v9", "basic"), hideseek_game::ConfigError);
  EXPECT_THROW(hideseek_python::loadVariant(HIDESEEK_CONFIG_DIR, "v2", "../game"), hideseek_game::ConfigError);
  EXPECT_THROW(hideseek_python::loadVariant(HIDESEEK_CONFIG_DIR, "v2", "nosuchvariant"), hideseek_game::ConfigError);
}
