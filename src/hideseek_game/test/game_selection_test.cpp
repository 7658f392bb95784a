// The one resolver of game and variant names (game_selection.h): what the nodes, tools and scripts
// all get for `game:=`, `variant:=` and `--game`.
#include "hideseek_game/game_selection.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "hideseek_game/config_error.h"
#include "test_util.h"

namespace hideseek_game {
namespace {

const std::string kConfig = HIDESEEK_CONFIG_DIR;
using test::errorOf;

TEST(GameSelection, NamesResolveToTheirFiles) {
  EXPECT_EQ(gameFile(kConfig, "v2"), kConfig + "/game.yaml");
  EXPECT_EQ(gameFile(kConfig, "v1"), kConfig + "/game_v1.yaml");
  EXPECT_EQ(variantFile(kConfig, "basic"), kConfig + "/variants/basic.yaml");
  EXPECT_EQ(gameFile(kConfig, "v3"), kConfig + "/game_v3.yaml");
  EXPECT_EQ(gameNames(kConfig), (std::vector<std::string>{"v2", "v1", "v3"}));
}

TEST(GameSelection, AVariantOfTheFirstGamePlaysTheFirstGamesMap) {
  const GameSelection v1 = selectGame(kConfig, "v1", "basic");
  EXPECT_EQ(v1.config.game.name, "v1");
  EXPECT_NE(v1.config.map_file.find("maps/v1/"), std::string::npos) << v1.config.map_file;
  const GameSelection v2 = selectGame(kConfig, kBaseGame, "basic");
  EXPECT_EQ(v2.config.game.name, "v2");
  EXPECT_EQ(v2.config.map_file.find("maps/v1/"), std::string::npos) << v2.config.map_file;
}

TEST(GameSelection, AnUnknownNameIsRefusedWithTheNamesThere) {
  const std::string game = errorOf([] { gameFile(kConfig, "v9"); });
  EXPECT_NE(game.find("'v9' is not a game here (v2, v1, v3)"), std::string::npos) << game;
  const std::string variant = errorOf([] { variantFile(kConfig, "nosuch"); });
  EXPECT_NE(variant.find("'nosuch' is not a variant here (basic, "), std::string::npos) << variant;
  // A path is no name: the resolver never reads outside config/.
  EXPECT_NE(errorOf([] { variantFile(kConfig, "../game"); }), "");
  EXPECT_NE(errorOf([] { gameFile(kConfig, "../config/game"); }), "");
}

// No game named: config/games.yaml's `default`, the one place the default game is written.
TEST(GameSelection, NoGameNamedIsTheDefaultOfGamesYaml) {
  EXPECT_EQ(defaultGame(kConfig), "v3");
  EXPECT_EQ(gameFile(kConfig, ""), kConfig + "/game_v3.yaml");
  EXPECT_EQ(selectGame(kConfig, "", "basic").game, "v3");
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "default_game";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "game.yaml") << "game: v2\n";
  std::ofstream(dir / "game_v3.yaml") << "game: v3\n";
  const std::string d = dir.string();
  std::ofstream(dir / "games.yaml") << "default: v3\n";
  EXPECT_EQ(defaultGame(d), "v3");
  EXPECT_EQ(gameArgument(d, ""), d + "/game_v3.yaml");
  std::ofstream(dir / "games.yaml") << "default: v9\n";
  std::string e = errorOf([&] { defaultGame(d); });
  EXPECT_NE(e.find("games.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("'v9' is not a game here (v2, v3)"), std::string::npos) << e;
  std::ofstream(dir / "games.yaml") << "default: v3\ndefualt: v2\n";
  EXPECT_NE(errorOf([&] { defaultGame(d); }).find("defualt"), std::string::npos);
  std::filesystem::remove(dir / "games.yaml");
  EXPECT_NE(errorOf([&] { gameFile(d, ""); }).find("games.yaml"), std::string::npos);
}

TEST(GameSelection, AToolsGameArgumentIsANameOrAFile) {
  EXPECT_EQ(gameArgument(kConfig, ""), kConfig + "/game_v3.yaml");
  EXPECT_EQ(gameArgument(kConfig, "v1"), kConfig + "/game_v1.yaml");
  EXPECT_EQ(gameArgument(kConfig, "/somewhere/mine.yaml"), "/somewhere/mine.yaml");
  EXPECT_EQ(gameArgument(kConfig, "mine.yaml"), "mine.yaml");
  EXPECT_EQ(gameArgument(kConfig, "v3"), kConfig + "/game_v3.yaml");
  EXPECT_NE(errorOf([] { gameArgument(kConfig, "v9"); }), "");
}

// A game file named by a relative path that extends another finds its maps (the extended file's
// maps_dir was once prefixed with the relative folder twice: config/config/maps).
TEST(GameSelection, ARelativeGameFileThatExtendsAnotherFindsItsMaps) {
  const std::filesystem::path here = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::path(kConfig).parent_path());
  const VariantConfig v = loadVariantConfig("config/game_v1.yaml", "config/variants/basic.yaml");
  std::filesystem::current_path(here);
  EXPECT_TRUE(std::filesystem::is_regular_file(v.map_file)) << v.map_file;
  EXPECT_NE(v.map_file.find("maps/v1/"), std::string::npos) << v.map_file;
}

// A game file selected under one name that calls itself another is refused: the run registry
// records the game's own name beside each policy.
TEST(GameSelection, AGameFileMustCallItselfByItsName) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("hideseek_selection_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "variants");
  std::filesystem::copy(kConfig + "/maps", dir / "maps", std::filesystem::copy_options::recursive);
  std::filesystem::copy_file(kConfig + "/game.yaml", dir / "game.yaml");
  std::filesystem::copy_file(kConfig + "/variants/basic.yaml", dir / "variants" / "basic.yaml");
  std::ofstream(dir / "game_v9.yaml") << "extends: game.yaml\n";  // still calls itself v2
  EXPECT_EQ(gameNames(dir.string()), (std::vector<std::string>{"v2", "v9"}));
  const std::string e = errorOf([&] { selectGame(dir.string(), "v9", "basic"); });
  EXPECT_NE(e.find("is 'v2', but the file was selected as game 'v9'"), std::string::npos) << e;
  std::filesystem::remove_all(dir);
}

// A variant file of one's own (resolve --variant-config, hideseek_pipeline train --variant-config)
// replaces the variant's file; it is played under its own name, so a file named otherwise is refused.
TEST(GameSelection, AVariantFileOfOnesOwnIsSelectedUnderItsOwnName) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("hideseek_own_variant_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "mine.yaml").string();
  std::ofstream(file) << "variant: mine\nmap: " << kConfig << "/maps/stochastic.yaml\nseeker: {policy: stochastic}\n";
  const GameSelection s = selectGame(kConfig, "v2", "mine", file);
  EXPECT_EQ(s.variant, "mine");
  EXPECT_EQ(s.variant_file, file);
  EXPECT_EQ(s.config.map_file, kConfig + "/maps/stochastic.yaml");
  EXPECT_EQ(s.config.seeker_policy, "stochastic");
  const std::string e = errorOf([&] { selectGame(kConfig, "v2", "yours", file); });
  EXPECT_NE(e.find("is 'mine', but the file was given as variant 'yours'"), std::string::npos) << e;
  EXPECT_NE(e.find(file), std::string::npos) << e;
  std::filesystem::remove_all(dir);
}

// A config folder's own variant file is held to its name too (a copy renamed without its field).
TEST(GameSelection, AConfigFoldersVariantFileNamedOtherwiseIsRefused) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("hideseek_misnamed_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::remove_all(dir);
  std::filesystem::copy(kConfig, dir, std::filesystem::copy_options::recursive);
  std::filesystem::copy_file(dir / "variants" / "basic.yaml", dir / "variants" / "renamed.yaml");
  const std::string e = errorOf([&] { selectGame(dir.string(), "v2", "renamed"); });
  EXPECT_NE(e.find("is 'basic', but the file was given as variant 'renamed'"), std::string::npos) << e;
  EXPECT_NE(e.find((dir / "variants" / "renamed.yaml").string()), std::string::npos) << e;
  EXPECT_EQ(selectGame(dir.string(), "v2", "basic").config.name, "basic");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace hideseek_game
