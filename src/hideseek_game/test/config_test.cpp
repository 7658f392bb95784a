#include <dirent.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <memory>

#include "hideseek_game/arena.h"
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

// seeker.path_following (docs/calibration.md, "The scripted seeker's stalls"): next_point in every
// shipped game, which replays as it was trained; a variant or game file of one's own asks for no_backtrack.
TEST(ShippedConfig, TheSeekerNeverBacktracksOnlyWhereAFileAsksForIt) {
  for (const std::string game : {"game_v1.yaml", "game.yaml", "game_v3.yaml"}) {
    EXPECT_EQ(loadVariantConfig(test::configPath(game), test::configPath("variants/stochasticseeker.yaml"))
                  .game.seeker_path_following,
              SeekerPathFollowing::kNextPoint)
        << game;
  }
  const std::string own =
      writeTemp("no_backtrack.yaml",
                "variant: x\nmap: deterministic.yaml\nseeker: {policy: stochastic, path_following: no_backtrack}\n");
  EXPECT_EQ(loadVariantConfig(test::configPath("game_v3.yaml"), own).game.seeker_path_following,
            SeekerPathFollowing::kNoBacktrack);
  const std::string bad =
      writeTemp("following_bad.yaml", "variant: x\nmap: deterministic.yaml\nseeker: {path_following: onward}\n");
  const std::string e = errorOf([&] { loadVariantConfig(test::configPath("game_v3.yaml"), bad); });
  EXPECT_NE(e.find("following_bad.yaml: field 'seeker.path_following': must be one of {next_point, no_backtrack}, got "
                   "'onward'"),
            std::string::npos)
      << e;
}

TEST(BadConfig, ErrorsNameTheFileAndTheField) {
  const std::string game = test::configPath("game.yaml");
  const std::string typo = writeTemp("typo.yaml", "variant: x\nmap: deterministic.yaml\nhider: {sped: 2.0}\n");
  EXPECT_NE(errorOf([&] { loadVariantConfig(game, typo); }).find("typo.yaml: field 'hider.sped': unknown field"),
            std::string::npos);
  const std::string range = writeTemp("range.yaml", "variant: x\nmap: deterministic.yaml\nhider: {speed: -1}\n");
  const std::string e = errorOf([&] { loadVariantConfig(game, range); });
  EXPECT_NE(e.find("range.yaml: field 'hider.speed': must be in [0, 20], got -1"), std::string::npos) << e;
  // Found by config_fuzz: a capture distance beyond the spawn distance let episodes end at their spawn.
  const std::string reach =
      writeTemp("reach.yaml", "variant: x\nmap: deterministic.yaml\nepisode: {capture_distance: 5.8}\n");
  const std::string r = errorOf([&] { loadVariantConfig(game, reach); });
  EXPECT_NE(
      r.find("reach.yaml: field 'episode.min_spawn_distance': (3 m) must exceed episode.capture_distance (5.8 m)"),
      std::string::npos)
      << r;
  const std::string map =
      writeTemp("badmap.yaml", "name: m\nobstacles:\n  - {center: [0, 0], size: [1]}\nwaypoints: [[1, 1]]\n");
  EXPECT_NE(errorOf([&] { loadMapFile(map); }).find("badmap.yaml: field 'obstacles[0].size'"), std::string::npos);
  const std::string inside =
      writeTemp("inside.yaml", "name: m\nobstacles:\n  - {center: [0, 0], size: [2, 2]}\nwaypoints: [[0.5, 0]]\n");
  EXPECT_NE(errorOf([&] { loadMapFile(inside); }).find("'waypoints[0]': lies inside an obstacle"), std::string::npos);
  const std::string missing = errorOf([&] { loadMapFile("/nonexistent/map.yaml"); });
  EXPECT_NE(missing.find("/nonexistent/map.yaml: field '<file>': no such file (a variant file's relative map name is "
                         "taken from its game's maps folder"),
            std::string::npos)
      << missing;
  const std::string syntax = writeTemp("syntax.yaml", "name: [unclosed\n");
  EXPECT_NE(errorOf([&] { loadMapFile(syntax); }).find("not valid YAML"), std::string::npos);
}

// Hand-edited map files with numbers no arena can hold are refused like a bad scalar, naming the
// field (issue #63): every vector field finite and in its stated range, every obstacle on the floor.
TEST(BadConfig, MapVectorsAreCheckedLikeScalarsAndObstaclesMustMeetTheArena) {
  const auto refusal = [](const std::string& name, const std::string& obstacles, const std::string& waypoints) {
    return errorOf(
        [&] { loadMapFile(writeTemp(name, "name: m\nobstacles:\n" + obstacles + "waypoints: " + waypoints + "\n")); });
  };
  const std::string box = "  - {center: [3, 3], size: [1, 1]}\n";
  std::string e = refusal("nan_center.yaml", "  - {center: [.nan, 0], size: [1, 1]}\n", "[[1, 1]]");
  EXPECT_NE(e.find("nan_center.yaml: field 'obstacles[0].center': must hold two numbers in [-21, 21], got [nan, 0]"),
            std::string::npos)
      << e;
  e = refusal("inf_size.yaml", "  - {center: [0, 0], size: [1, .inf]}\n", "[[3, 3]]");
  EXPECT_NE(e.find("field 'obstacles[0].size': must hold two numbers in [0.01, 28]"), std::string::npos) << e;
  e = refusal("zero_size.yaml", "  - {center: [0, 0], size: [0, 1]}\n", "[[3, 3]]");
  EXPECT_NE(e.find("field 'obstacles[0].size': must hold two numbers in [0.01, 28], got [0, 1]"), std::string::npos)
      << e;
  e = refusal("far_center.yaml", "  - {center: [1e9, 0], size: [1, 1]}\n", "[[3, 3]]");
  EXPECT_NE(e.find("field 'obstacles[0].center': must hold two numbers in [-21, 21], got [1e+09, 0]"),
            std::string::npos)
      << e;
  // In range, yet wholly beyond the wall: refused, and so is a rotated box that misses the corner.
  e = refusal("outside.yaml", box + "  - {center: [9, 0], size: [2, 2]}\n", "[[1, 1]]");
  EXPECT_NE(e.find("field 'obstacles[1]': lies wholly outside the arena, whose floor spans [-7, 7] m on both axes"),
            std::string::npos)
      << e;
  e = refusal("corner.yaml", "  - {center: [8.3, 8.3], size: [2, 2], yaw: 0.785398}\n", "[[1, 1]]");
  EXPECT_NE(e.find("field 'obstacles[0]': lies wholly outside"), std::string::npos) << e;
  // A misspelt key: the missing field is named, and the unknown one beside it.
  e = refusal("centre.yaml", "  - {centre: [3, 3], size: [1, 1]}\n", "[[1, 1]]");
  EXPECT_NE(e.find("field 'obstacles[0].center': is required (the box has an unknown field 'centre')"),
            std::string::npos)
      << e;
  e = refusal("nan_waypoint.yaml", box, "[[.nan, 1]]");
  EXPECT_NE(e.find("field 'waypoints[0]': must hold two numbers in [-7, 7], got [nan, 1]"), std::string::npos) << e;
  // A generator whose largest draw could cover more than half the floor.
  e = errorOf([] {
    loadMapFile(writeTemp("full.yaml", "name: m\ntype: stochastic\ngenerator: {max_boxes: 20, max_size: 5}\n"));
  });
  EXPECT_NE(e.find("field 'generator': max_boxes x max_size^2 (500 m^2) must be at most half the floor (98 m^2)"),
            std::string::npos)
      << e;
  // A box that pokes into the floor, rotated or straddling a wall, is part of the arena.
  EXPECT_NO_THROW(loadMapFile(writeTemp("straddles.yaml",
                                        "name: m\nobstacles:\n  - {center: [7.5, 0], size: [2, 2]}\n"
                                        "  - {center: [8.3, 8.3], size: [4, 4], yaw: 0.785398}\n"
                                        "waypoints: [[1, 1]]\n")));
}

// A fixed map whose obstacles leave no two free points min_spawn_distance apart is refused when the
// arena is built, naming the map's obstacles; one with room plays.
TEST(BadConfig, AFixedMapWithoutRoomForTheSpawnsIsRefused) {
  const VariantConfig v = test::loadVariant("basic");
  const auto arena = [&](const std::string& name, const std::string& obstacles) {
    auto map = std::make_shared<const MapSpec>(
        loadMapFile(writeTemp(name, "name: m\nobstacles:\n" + obstacles + "waypoints: [[-6.5, -6.5]]\n")));
    return Arena(v.game, map);
  };
  // Everything but a 1.5 m square corner is filled: no two spawns can be min_spawn_distance apart.
  const std::string e = errorOf([&] {
    arena("cramped.yaml",
          "  - {center: [0.75, 0], size: [12.5, 14]}\n  - {center: [-6.25, 0.75], size: [1.5, 12.5]}\n");
  });
  EXPECT_NE(e.find("cramped.yaml: field 'obstacles': leave no room for the spawns"), std::string::npos) << e;
  // A waypoint outside the box but closer to it than an agent's radius: the seeker could not stand there.
  const std::string near = errorOf([&] {
    const std::string path =
        writeTemp("near.yaml", "name: m\nobstacles:\n  - {center: [0, 0], size: [2, 2]}\nwaypoints: [[1.2, 0]]\n");
    Arena(v.game, std::make_shared<const MapSpec>(loadMapFile(path)));
  });
  EXPECT_NE(near.find("near.yaml: field 'waypoints[0]': lies closer than the agent radius (0.4 m)"), std::string::npos)
      << near;
  // The same box a little smaller leaves an L-shaped corridor, which is room enough.
  Arena roomy = arena("roomy.yaml", "  - {center: [1.5, 1.5], size: [10, 10]}\n");
  roomy.reset(3);
  EXPECT_GE(distance(roomy.hider().position, roomy.seeker().position), v.game.min_spawn_distance);
}

}  // namespace hideseek_game
