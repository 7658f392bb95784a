// The run registry (policies/policies.yaml) as the nodes read it: the shipped policy of a variant,
// network and game, and registries that must be refused with the run and field named.
#include "hideseek_game/run_registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hideseek_game/config_error.h"
#include "hideseek_game/game_options.h"

namespace hideseek_game {
namespace {

class RunRegistryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("hideseek_registry_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "basic.pt") << "weights";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& text) {
    const std::string path = (dir_ / "policies.yaml").string();
    std::ofstream(path) << text;
    return path;
  }
  std::string errorOf(const std::string& text) {
    try {
      loadRunRegistry(write(text));
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  }
  std::filesystem::path dir_;
};

constexpr char kTwoRuns[] =
    "basic_seed0: {variant: basic, network: ff, game: v2, training_seed: 0, steps: 2000896, commit: abc}\n"
    "basic_seed1: {variant: basic, network: ff, game: v2, training_seed: 1, steps: 2000896, weights: basic.pt}\n";

TEST_F(RunRegistryTest, TheShippedRunOfAVariantNamesItsWeights) {
  const std::string registry = write(kTwoRuns);
  EXPECT_EQ(shippedPolicyFile(registry, "basic", "ff", "v2"), (dir_ / "basic.pt").string());
  const auto runs = loadRunRegistry(registry);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].name, "basic_seed0");
  EXPECT_EQ(runs[0].weights, "");
  EXPECT_EQ(runs[1].training_seed, 1);
  EXPECT_EQ(runs[1].steps, 2000896);
}

TEST_F(RunRegistryTest, NoPolicyIsShippedForAnotherVariantNetworkOrGame) {
  const std::string registry = write(kTwoRuns);
  EXPECT_EQ(shippedPolicyFile(registry, "fasterhider", "ff", "v2"), "");
  EXPECT_EQ(shippedPolicyFile(registry, "basic", "gru", "v2"), "");
  EXPECT_EQ(shippedPolicyFile(registry, "basic", "ff", "v1"), "");
  EXPECT_EQ(shippedPolicyFile(write("# no run yet\n"), "basic", "ff", "v2"), "");
}

// A run says whose policy it trained; the hider's launch files play a hider's shipped weights, never
// a seeker's of the same variant, and a role other than hider or seeker is refused by name.
TEST_F(RunRegistryTest, ASeekersShippedRunIsNotTheHidersPolicy) {
  std::ofstream(dir_ / "basic_seeker.pt") << "weights";
  const std::string registry =
      write(std::string(kTwoRuns) +
            "basic_seeker_seed0: {variant: basic, network: ff, game: v2, role: seeker, weights: basic_seeker.pt}\n");
  const auto runs = loadRunRegistry(registry);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].role, "hider");
  EXPECT_EQ(runs[2].role, "seeker");
  EXPECT_EQ(shippedPolicyFile(registry, "basic", "ff", "v2"), (dir_ / "basic.pt").string());
  EXPECT_EQ(shippedPolicyFile(registry, "basic", "ff", "v2", "seeker"), (dir_ / "basic_seeker.pt").string());
  const std::string e = errorOf("x: {variant: basic, network: ff, game: v2, role: referee}\n");
  EXPECT_NE(e.find("role"), std::string::npos) << e;
  EXPECT_NE(e.find("referee"), std::string::npos) << e;
}

TEST_F(RunRegistryTest, TwoShippedRunsOfOneVariantAreRefusedNamingBoth) {
  std::ofstream(dir_ / "other.pt") << "weights";
  const std::string error =
      errorOf(std::string(kTwoRuns) + "basic_seed2: {variant: basic, network: ff, game: v2, weights: other.pt}\n");
  EXPECT_NE(error.find("basic_seed2.weights"), std::string::npos) << error;
  EXPECT_NE(error.find("run basic_seed1 already ships"), std::string::npos) << error;
}

TEST_F(RunRegistryTest, MissingWeightsUnknownFieldsAndMissingFieldsAreRefused) {
  EXPECT_NE(errorOf("r: {variant: basic, network: ff, game: v2, weights: gone.pt}\n").find("r.weights"),
            std::string::npos);
  EXPECT_NE(errorOf("r: {variant: basic, network: ff, game: v2, stpes: 3}\n").find("'r.stpes': unknown field"),
            std::string::npos);
  EXPECT_NE(errorOf("r: {variant: basic, game: v2}\n").find("r.network"), std::string::npos);
  EXPECT_NE(errorOf("r: {variant: basic, network: lstm, game: v2}\n").find("r.network"), std::string::npos);
  EXPECT_NE(errorOf("r: {network: ff, game: v2}\n").find("'r.variant': is required"), std::string::npos);
  EXPECT_NE(errorOf("r: {variant: basic, network: ff}\n").find("'r.game': is required"), std::string::npos);
}

// hideseek_pipeline train --variant-config records a variant file of one's own and its map, with
// their sha256: a registry holding such a run still gives the nodes their shipped policy.
TEST_F(RunRegistryTest, ARunOnAVariantFileOfItsOwnIsReadWithItsFiles) {
  const std::string registry = write(
      std::string(kTwoRuns) +
      "mine_seed0: {variant: mine, network: ff, game: v3, training_seed: 0, steps: 4096, variant_config: /v/mine.yaml, "
      "variant_sha256: ab12, map_file: /v/map.yaml, map_sha256: cd34}\n");
  const std::vector<RunEntry> runs = loadRunRegistry(registry);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[2].variant, "mine");
  EXPECT_EQ(shippedPolicyFile(registry, "basic", "ff", "v2"), (dir_ / "basic.pt").string());
  EXPECT_NE(errorOf("r: {variant: mine, network: ff, game: v3, map_sha: cd34}\n").find("'r.map_sha': unknown field"),
            std::string::npos);
  EXPECT_NE(errorOf("r: {variant: mine, network: ff, game: v3, variant_config: /v/mine.yaml}\n").find("together"),
            std::string::npos);
  EXPECT_NE(errorOf("r: {variant: mine, network: ff, game: v3, variant_config: /v/mine.yaml, variant_sha256: ab, "
                    "map_file: /v/map.yaml, map_sha256: cd, weights: basic.pt}\n")
                .find("'r.weights': a run on a variant file of its own ships no weights"),
            std::string::npos);
}

TEST_F(RunRegistryTest, ARetrainNamesTheFirstDrawItRepeats) {
  const auto runs = loadRunRegistry(
      write("basic_seed0: {variant: basic, network: ff, game: v2}\n"
            "basic_seed0_retrain: {variant: basic, network: ff, game: v2, draw: retrain, retrain_of: basic_seed0}\n"));
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].draw, "first");
  EXPECT_EQ(runs[1].draw, "retrain");
  EXPECT_EQ(runs[1].retrain_of, "basic_seed0");
  EXPECT_NE(errorOf("r: {variant: basic, network: ff, game: v2, draw: retrain}\n").find("'r.retrain_of': is required"),
            std::string::npos);
  EXPECT_NE(errorOf("r: {variant: basic, network: ff, game: v2, draw: second}\n").find("r.draw"), std::string::npos);
  EXPECT_NE(errorOf("r: {variant: basic, network: ff, game: v2, retrain_of: q}\n").find("only for a retrain"),
            std::string::npos);
}

TEST_F(RunRegistryTest, TheShippedRegistryIsReadable) {
  // The committed registry: every run well formed, every shipped file present.
  EXPECT_NO_THROW(loadRunRegistry(std::string(HIDESEEK_POLICY_DIR) + "/policies.yaml"));
}

// What hideseek_registry.py (hideseek_analysis) prints for `command` (one name per line), run on /usr/bin/python3.
std::vector<std::string> pythonRegistry(const std::string& args) {
  const std::string command = "/usr/bin/python3 " HIDESEEK_REGISTRY_SCRIPT " " + args + " 2>&1";
  std::vector<std::string> lines;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {"popen failed: " + command};
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) {
    std::string line(buf);
    if (!line.empty() && line.back() == '\n') line.pop_back();
    if (!line.empty()) lines.push_back(line);
  }
  const int status = pclose(pipe);
  if (status != 0) lines.push_back("exit status " + std::to_string(status));
  return lines;
}

// The C++ readers and the Python module (CMake, the scripts, the report) see the same variants
// and the same runs: in the tree, and in a tree where one was added.
TEST_F(RunRegistryTest, TheCppAndPythonReadersAgree) {
  const std::string config = HIDESEEK_CONFIG_DIR, registry = std::string(HIDESEEK_POLICY_DIR) + "/policies.yaml";
  EXPECT_EQ(variantNames(config + "/variants"), pythonRegistry("--variants-dir " + config + "/variants variants"));
  std::vector<std::string> runs;
  for (const RunEntry& r : loadRunRegistry(registry)) runs.push_back(r.name);
  EXPECT_EQ(runs, pythonRegistry("--registry " + registry + " runs"));
  EXPECT_FALSE(runs.empty());

  std::filesystem::create_directories(dir_ / "variants");
  for (const auto& name : variantNames(config + "/variants")) {
    std::filesystem::copy_file(config + "/variants/" + name + ".yaml", dir_ / "variants" / (name + ".yaml"));
  }
  std::ofstream(dir_ / "variants" / "tinyarena.yaml") << "variant: tinyarena\nmap: deterministic.yaml\n";
  const std::vector<std::string> added = variantNames((dir_ / "variants").string());
  EXPECT_NE(std::find(added.begin(), added.end(), "tinyarena"), added.end());
  EXPECT_EQ(added, pythonRegistry("--variants-dir " + (dir_ / "variants").string() + " variants"));
}

TEST_F(RunRegistryTest, AVariantFileNamedOtherwiseThanItsVariantIsRefusedByBothReaders) {
  std::filesystem::create_directories(dir_ / "variants");
  std::ofstream(dir_ / "variants" / "fast.yaml") << "variant: faster\nmap: deterministic.yaml\n";
  try {
    variantNames((dir_ / "variants").string());
    FAIL() << "fast.yaml naming variant faster was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("it must be the file's name, 'fast'"), std::string::npos) << e.what();
  }
  const std::vector<std::string> python =
      pythonRegistry("--variants-dir " + (dir_ / "variants").string() + " variants");
  ASSERT_FALSE(python.empty());
  EXPECT_NE(python.back().find("exit status"), std::string::npos);
  EXPECT_NE(python.front().find("it must be the file's name, 'fast'"), std::string::npos) << python.front();
}

TEST(GameName, GameFilesNameTheirGame) {
  // The registry matches a policy to a game by these names.
  const std::string config = HIDESEEK_CONFIG_DIR;
  EXPECT_EQ(loadVariantConfig(config + "/game.yaml", config + "/variants/basic.yaml").game.name, "v2");
  EXPECT_EQ(loadVariantConfig(config + "/game_v1.yaml", config + "/variants/basic.yaml").game.name, "v1");
}

}  // namespace
}  // namespace hideseek_game
