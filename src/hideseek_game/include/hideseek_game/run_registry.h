// The run registry, policies/policies.yaml: one entry per training run (its variant, network,
// game, training seed, steps, precision, the commit it trained with, its log). The run whose
// exported weights are committed names them in `weights`; that is the policy a variant's launch
// file plays by default (policy:=shipped). src/hideseek_analysis/scripts/hideseek_registry.py reads the same file.
#pragma once

#include <string>
#include <vector>

namespace hideseek_game {

// The policy name that means "the weights the registry ships for this variant, network and game".
inline constexpr char kShippedPolicy[] = "shipped";

struct RunEntry {
  std::string name;     // the run's key, e.g. basic_v2pilot_seed0
  std::string variant;  // a config/variants/*.yaml name
  std::string network;  // ff | gru
  std::string game;     // the game it trained on (game.yaml's `game`: v2, v1)
  int training_seed = 0;
  long long steps = 0;
  std::string weights;  // absolute path of the committed weights, or "" (not shipped)
  // first: the first training of its variant and seed, the draw tables and claims count; retrain:
  // the same variant and seed trained again (only to recover weights to ship), named in retrain_of.
  std::string draw = "first";
  std::string retrain_of;  // the first draw a retrain repeats; "" for a first draw
  // hider (the default: every run before the seeker learned) or seeker. Table 2, the claims,
  // shipping for the hider's launch files and every hider tool take hider runs only.
  std::string role = "hider";
};

// Reads the registry; throws ConfigError naming the run and field at fault, also where two runs
// ship weights for the same variant, network, game and role, or where shipped weights are missing.
std::vector<RunEntry> loadRunRegistry(const std::string& registry_file);

// The variants: the names of variants_dir's *.yaml files, sorted; each file's `variant` field must be
// its name (throws ConfigError naming the file otherwise). src/hideseek_analysis/scripts/hideseek_registry.py's
// `variants` reads the same folder under the same rule.
std::vector<std::string> variantNames(const std::string& variants_dir);

// The weights shipped for variant, network, game and role (a hider's unless said), or "" when no run
// ships any.
std::string shippedPolicyFile(const std::string& registry_file, const std::string& variant, const std::string& network,
                              const std::string& game, const std::string& role = "hider");

}  // namespace hideseek_game
