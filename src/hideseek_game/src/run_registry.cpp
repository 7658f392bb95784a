#include "hideseek_game/run_registry.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include "hideseek_game/config_error.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/yaml_fields.h"

namespace hideseek_game {

namespace {

constexpr long long kMaxSteps = 1000000000000LL;

}  // namespace

std::vector<std::string> variantNames(const std::string& variants_dir) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(variants_dir, error)) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string file = entry.path().string(), stem = entry.path().stem().string();
    const YAML::Node root = loadYamlFile(file);
    const std::string named = root.IsMap() && root["variant"] ? root["variant"].as<std::string>() : "";
    if (named != stem)
      throw ConfigError(file, "variant", "is '" + named + "'; it must be the file's name, '" + stem + "'");
    names.push_back(stem);
  }
  if (error) throw ConfigError(variants_dir, "(folder)", "cannot be read: " + error.message());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<RunEntry> loadRunRegistry(const std::string& registry_file) {
  const YAML::Node root = loadYamlFile(registry_file);
  std::vector<RunEntry> runs;
  if (root.IsNull()) return runs;  // no run yet
  if (!root.IsMap()) throw ConfigError(registry_file, "(top level)", "must map run names to runs");
  std::map<std::tuple<std::string, std::string, std::string, std::string>, std::string> shipped;
  for (const auto& kv : root) {
    RunEntry r;
    r.name = kv.first.as<std::string>();
    if (!kv.second.IsMap()) throw ConfigError(registry_file, r.name, "must be a mapping of the run's fields");
    YamlFields f(kv.second, registry_file, r.name);
    r.variant = f.text("variant", "", {});
    if (r.variant.empty()) throw ConfigError(registry_file, f.field("variant"), "is required");
    r.network = f.text("network", "", {"ff", "gru"});
    if (r.network.empty()) throw ConfigError(registry_file, f.field("network"), "is required (ff, gru)");
    r.game = f.text("game", "", {});
    if (r.game.empty()) throw ConfigError(registry_file, f.field("game"), "is required (v2, v1)");
    r.training_seed = f.integer("training_seed", 0, 0, kMaxSeed);
    r.steps = static_cast<long long>(f.number("steps", 0, 0, static_cast<double>(kMaxSteps)));
    const std::string weights = f.text("weights", "", {});
    r.role = f.text("role", "hider", {"hider", "seeker"});
    r.draw = f.text("draw", "first", {"first", "retrain"});
    r.retrain_of = f.text("retrain_of", "", {});
    if (r.draw == "retrain" && r.retrain_of.empty()) {
      throw ConfigError(registry_file, f.field("retrain_of"), "is required for a retrain: the run it trains again");
    }
    if (r.draw == "first" && !r.retrain_of.empty()) {
      throw ConfigError(registry_file, f.field("retrain_of"), "is only for a retrain (draw: retrain)");
    }
    // Recorded for people and the scripts; read here so that a typo in a key is still refused.
    for (const char* key : {"wall_s", "paused_s", "precision", "commit", "log", "curve", "command", "note"}) {
      if (f.has(key)) f.child(key);
    }
    // A run on a variant file of its own records the file and its map with their sha256, all four
    // together, and ships no weights (a shipped policy is played under its variant's name).
    int own = 0;
    for (const char* key : {"variant_config", "variant_sha256", "map_file", "map_sha256"}) {
      if (!f.text(key, "", {}).empty()) ++own;
    }
    if (own != 0 && own != 4) {
      throw ConfigError(registry_file, f.field("variant_config"),
                        "a run on a variant file of its own records variant_config, variant_sha256, map_file and "
                        "map_sha256 together");
    }
    if (own == 4 && !weights.empty()) {
      throw ConfigError(registry_file, f.field("weights"), "a run on a variant file of its own ships no weights");
    }
    f.rejectUnknown();
    if (!weights.empty()) {
      r.weights =
          weights.front() == '/' ? weights : (std::filesystem::path(registry_file).parent_path() / weights).string();
      if (!std::ifstream(r.weights).good()) {
        throw ConfigError(registry_file, f.field("weights"), "names " + r.weights + ", which cannot be read");
      }
      const auto key = std::make_tuple(r.variant, r.network, r.game, r.role);
      const auto [it, fresh] = shipped.emplace(key, r.name);
      if (!fresh) {
        throw ConfigError(registry_file, f.field("weights"),
                          "run " + it->second + " already ships weights for variant " + r.variant + ", network " +
                              r.network + ", game " + r.game + ", role " + r.role + ": one shipped policy per variant");
      }
    }
    runs.push_back(r);
  }
  return runs;
}

std::string shippedPolicyFile(const std::string& registry_file, const std::string& variant, const std::string& network,
                              const std::string& game, const std::string& role) {
  for (const RunEntry& r : loadRunRegistry(registry_file)) {
    if (r.variant == variant && r.network == network && r.game == game && r.role == role && !r.weights.empty()) {
      return r.weights;
    }
  }
  return "";
}

}  // namespace hideseek_game
