#include <dirent.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <functional>

#include "hideseek_game/config_error.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"
#include "hideseek_game/run_registry.h"
#include "test_util.h"

namespace hideseek_game {

namespace {

using test::errorOf;

std::vector<std::string> filesIn(const std::string& dir, const std::string& suffix) {
  std::vector<std::string> out;
  DIR* d = opendir(dir.c_str());
  if (!d) return out;
  while (dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      out.push_back(dir + "/" + name);
    }
  }
  closedir(d);
  return out;
}

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

// The game file that extends none (config/game.yaml) is the one source of the game's defaults:
// without any one of its keys it is refused, naming the file and the key, never filled in from
// elsewhere. A variant file gives only what it changes.
TEST(ShippedConfig, TheBaseGameFileMustGiveEveryKeyAndAVariantOnlyWhatItChanges) {
  const YAML::Node full = YAML::LoadFile(test::configPath("game.yaml"));
  const std::string variant = test::configPath("variants/basic.yaml");
  int keys = 0;
  auto refused = [&](const YAML::Node& cut, const std::string& field) {
    const std::string path = writeTemp("game_without_" + field + ".yaml", YAML::Dump(cut));
    EXPECT_NE(errorOf([&] { loadVariantConfig(path, variant); }).find(path + ": field '" + field + "': is missing"),
              std::string::npos)
        << field;
    ++keys;
  };
  for (const auto& top : full) {
    const std::string key = top.first.as<std::string>();
    YAML::Node cut = YAML::Clone(full);
    cut.remove(key);
    refused(cut, key);
    if (!top.second.IsMap()) continue;
    for (const auto& inner : top.second) {
      const std::string sub = inner.first.as<std::string>();
      YAML::Node cut_inner = YAML::Clone(full);
      cut_inner[key].remove(sub);
      refused(cut_inner, key + "." + sub);
    }
  }
  EXPECT_GE(keys, 30);
  // A variant that sets one field loads, the rest from game.yaml.
  const std::string small =
      writeTemp("one_field_variant.yaml", "variant: basic\nmap: deterministic.yaml\nhider:\n  speed: 2.5\n");
  const VariantConfig v = loadVariantConfig(test::configPath("game.yaml"), small);
  EXPECT_DOUBLE_EQ(v.game.hider.speed, 2.5);
  EXPECT_EQ(v.game.max_steps, full["episode"]["max_steps"].as<int>());
}

TEST(ShippedConfig, EveryVariantAndMapLoads) {
  // Every variant of the paper has its file (more may be added), named by its `variant` field.
  const std::vector<std::string> names = variantNames(test::configPath("variants"));
  for (const auto& kv : YAML::LoadFile(test::configPath("paper_reference.yaml"))["variants"]) {
    const std::string paper_variant = kv.first.as<std::string>();
    EXPECT_NE(std::find(names.begin(), names.end(), paper_variant), names.end()) << paper_variant;
  }
  const auto variants = filesIn(test::configPath("variants"), ".yaml");
  EXPECT_EQ(variants.size(), names.size());
  for (const std::string& f : variants) {
    SCOPED_TRACE(f);
    const VariantConfig v = loadVariantConfig(test::configPath("game.yaml"), f);
    const MapSpec map = loadMapFile(v.map_file);
    EXPECT_FALSE(map.name.empty());
  }
  const auto maps = filesIn(test::configPath("maps"), ".yaml");
  EXPECT_GE(maps.size(), 2u);
  for (const std::string& f : maps) EXPECT_NO_THROW(loadMapFile(f)) << f;
}

TEST(ShippedConfig, VariantsMatchSpecTable) {
  auto v = [](const std::string& n) { return test::loadVariant(n); };
  EXPECT_EQ(v("basic").game.hider.speed, 2.0);
  EXPECT_EQ(v("slowerhider").game.hider.speed, 1.0);
  EXPECT_EQ(v("fasterhider").game.hider.mode, SpeedMode::kAccelerate);
  EXPECT_EQ(v("visibilityreward_faster").game.hider.mode, SpeedMode::kAccelerate);
  EXPECT_TRUE(v("visibilityreward_faster").game.rewards.visibility);
  EXPECT_TRUE(v("visibilityreward").game.rewards.visibility);
  EXPECT_FALSE(v("basic").game.rewards.visibility);
  EXPECT_EQ(v("stochasticseeker").seeker_policy, "stochastic");
  EXPECT_EQ(v("stochasticmaps").seeker_policy, "stochastic");
  EXPECT_EQ(v("basic").seeker_policy, "deterministic");
  EXPECT_TRUE(loadMapFile(v("stochasticmaps").map_file).stochastic);
  EXPECT_EQ(v("basic").game.seeker.speed, 1.5);
  EXPECT_EQ(v("basic").game.max_steps, 1000);
  EXPECT_EQ(v("basic").game.action_repeat, 6);
}

TEST(BadConfig, ErrorsNameTheFileAndTheField) {
  const std::string game = test::configPath("game.yaml");
  const std::string typo = writeTemp("typo.yaml", "variant: x\nmap: deterministic.yaml\nhider: {sped: 2.0}\n");
  EXPECT_NE(errorOf([&] { loadVariantConfig(game, typo); }).find("typo.yaml: field 'hider.sped': unknown field"),
            std::string::npos);
  const std::string range = writeTemp("range.yaml", "variant: x\nmap: deterministic.yaml\nhider: {speed: -1}\n");
  const std::string e = errorOf([&] { loadVariantConfig(game, range); });
  EXPECT_NE(e.find("range.yaml: field 'hider.speed': must be in [0, 20], got -1"), std::string::npos) << e;
  const std::string map =
      writeTemp("badmap.yaml", "name: m\nobstacles:\n  - {center: [0, 0], size: [1]}\nwaypoints: [[1, 1]]\n");
  EXPECT_NE(errorOf([&] { loadMapFile(map); }).find("badmap.yaml: field 'obstacles[0].size'"), std::string::npos);
  const std::string inside =
      writeTemp("inside.yaml", "name: m\nobstacles:\n  - {center: [0, 0], size: [2, 2]}\nwaypoints: [[0.5, 0]]\n");
  EXPECT_NE(errorOf([&] { loadMapFile(inside); }).find("'waypoints[0]': lies inside an obstacle"), std::string::npos);
  EXPECT_NE(errorOf([&] { loadMapFile("/nonexistent/map.yaml"); }).find("/nonexistent/map.yaml"), std::string::npos);
  const std::string syntax = writeTemp("syntax.yaml", "name: [unclosed\n");
  EXPECT_NE(errorOf([&] { loadMapFile(syntax); }).find("not valid YAML"), std::string::npos);
}

}  // namespace hideseek_game
