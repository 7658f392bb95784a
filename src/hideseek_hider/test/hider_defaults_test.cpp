#include "hideseek_hider/hider_defaults.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "hideseek_game/config_error.h"

namespace hideseek_hider {

namespace {

std::string shipped() { return std::string(HIDESEEK_CONFIG_DIR) + "/hider.yaml"; }

// The shipped file with one line replaced (or dropped, when `with` is empty).
std::string shippedWith(const std::string& key, const std::string& with) {
  std::ifstream in(shipped());
  const std::string path = testing::TempDir() + "/hider_" + key + ".yaml";
  std::ofstream out(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key + ":", 0) == 0) {
      if (!with.empty()) out << with << '\n';
    } else {
      out << line << '\n';
    }
  }
  return path;
}

std::string errorOf(const std::string& path) {
  try {
    loadHiderDefaults(path);
  } catch (const hideseek_game::ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// The node starts from the shipped file, so it must load; and what it gives is the file's, not
// values of the code's: a file that changes two keys changes what is read.
TEST(HiderDefaults, TheShippedFileLoadsAndItsValuesAreWhatIsRead) {
  const HiderDefaults shipped_defaults = loadHiderDefaults(shipped());
  const HiderDefaults changed = loadHiderDefaults(shippedWith("threads", "threads: 7"));
  EXPECT_EQ(changed.threads, 7);
  EXPECT_EQ(loadHiderDefaults(shippedWith("precision", "precision: bf16")).precision, "bf16");
  EXPECT_EQ(changed.precision, shipped_defaults.precision);  // the other keys as shipped
  EXPECT_EQ(changed.checkpoint_interval_s, shipped_defaults.checkpoint_interval_s);
}

// A deleted key, a misspelt one and a bad value each stop the node with the file and the field.
TEST(HiderDefaults, AMissingKeyATypoOrABadValueNamesTheField) {
  const std::string missing = errorOf(shippedWith("checkpoint_interval", ""));
  EXPECT_NE(missing.find("checkpoint_interval"), std::string::npos) << missing;
  EXPECT_NE(missing.find("hider_checkpoint_interval.yaml"), std::string::npos) << missing;
  // A misspelt key: the key it replaced is missing; beside the right one, it is unknown.
  const std::string misspelt = errorOf(shippedWith("greedy", "gready: true"));
  EXPECT_NE(misspelt.find("'greedy'"), std::string::npos) << misspelt;
  const std::string unknown = errorOf(shippedWith("greedy", "greedy: true\ngready: true"));
  EXPECT_NE(unknown.find("gready"), std::string::npos) << unknown;
  const std::string bad = errorOf(shippedWith("precision", "precision: fp16"));
  EXPECT_NE(bad.find("precision"), std::string::npos) << bad;
  EXPECT_NE(bad.find("fp16"), std::string::npos) << bad;
  const std::string threads = errorOf(shippedWith("threads", "threads: 0"));
  EXPECT_NE(threads.find("threads"), std::string::npos) << threads;
}

}  // namespace hideseek_hider
