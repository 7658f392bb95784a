// What a game name and a variant resolve to, for scripts: the files, the map and the shipped
// policy, as every node resolves ~game and ~variant (hideseek_game/game_selection.h).
// usage: resolve [--game GAME] [--network ff|gru] [--registry FILE] VARIANT [KEY]
//   (no --game: the default game, config/games.yaml's; `resolve VARIANT game` prints its name)
//   prints game, variant, game_file, variant_file, map_file and shipped_policy ("" where none is
//   shipped) as YAML; with KEY, that value alone. The registry defaults to hideseek_world's
//   policies/policies.yaml.
#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"

namespace {

int usage(const std::string& why) {
  std::fprintf(stderr,
               "resolve: %s\nusage: resolve [--game GAME] [--network ff|gru] [--registry FILE] VARIANT "
               "[game|variant|game_file|variant_file|map_file|shipped_policy]\n",
               why.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string game, network = "ff", registry;  // no --game: config/games.yaml's default
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--game" && has_value) {
      game = argv[++i];
    } else if (a == "--network" && has_value) {
      network = argv[++i];
    } else if (a == "--registry" && has_value) {
      registry = argv[++i];
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option or missing value: " + a);
    } else {
      args.push_back(a);
    }
  }
  if (args.empty() || args.size() > 2) return usage("give one variant, and at most one key");
  if (network != "ff" && network != "gru") return usage("--network is ff or gru, got '" + network + "'");
  try {
    const auto s = hideseek_game::selectGame(hideseek_game::configDirectory(), game, args[0]);
    if (registry.empty()) registry = hideseek_game::packageDirectory("hideseek_world") + "/policies/policies.yaml";
    const std::vector<std::pair<std::string, std::string>> values = {
        {"game", s.game},
        {"variant", s.variant},
        {"game_file", s.game_file},
        {"variant_file", s.variant_file},
        {"map_file", s.config.map_file},
        {"shipped_policy", hideseek_game::shippedPolicy(registry, s, network)}};
    for (const auto& [key, value] : values) {
      if (args.size() == 2 && key == args[1]) {
        std::printf("%s\n", value.c_str());
        return 0;
      }
      if (args.size() == 1) std::printf("%s: \"%s\"\n", key.c_str(), value.c_str());
    }
    if (args.size() == 2) return usage("unknown key '" + args[1] + "'");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "resolve: %s\n", e.what());
    return 1;
  }
  return 0;
}
