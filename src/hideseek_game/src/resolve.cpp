// What a game name and a variant resolve to, for scripts: the files, the map and the shipped
// policy, as every node resolves ~game and ~variant (hideseek_game/game_selection.h).
// usage: resolve [--game GAME] [--network ff|gru] [--registry FILE] VARIANT [KEY]
//   (no --game: the default game, config/games.yaml's; `resolve VARIANT game` prints its name)
//   prints game, variant, game_file, variant_file, map_file and shipped_policy ("" where none is
//   shipped) as YAML; with KEY, that value alone. The registry defaults to hideseek_world's
//   policies/policies.yaml. --variant-config FILE: a variant file of one's own, whose variant field
//   must be VARIANT, in place of config/variants/VARIANT.yaml. --help lists the options.
#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "hideseek_game/command_line.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"

namespace {

int usage(const std::string& why) {
  std::fprintf(stderr, "resolve: %s (--help lists the options)\n", why.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  namespace po = boost::program_options;
  std::string game, network, registry, variant, key, variant_file;  // no --game: config/games.yaml's default
  hideseek_game::CommandLine line;
  line.tool = "resolve";
  line.about =
      "resolve: what a game name and a variant resolve to, as every node resolves ~game and ~variant\n"
      "usage: resolve [--game GAME] [--network ff|gru] [--registry FILE] [--variant-config FILE] VARIANT "
      "[game|variant|game_file|variant_file|map_file|shipped_policy]";
  line.options.add_options()                                                                                     //
      ("game", po::value(&game), "v2, v1 or v3 (none: config/games.yaml's default)")                             //
      ("network", po::value(&network)->default_value("ff"), "the shipped policy's network: ff or gru")           //
      ("registry", po::value(&registry), "the run registry (default: hideseek_world's policies/policies.yaml)")  //
      ("variant-config", po::value(&variant_file), "a variant file of one's own, its variant field VARIANT")     //
      ("variant", po::value(&variant)->required(), "the variant")                                                //
      ("key", po::value(&key), "print this value alone (default: all of them, as YAML)");
  line.positional.add("variant", 1).add("key", 1);
  int exit_code = 0;
  if (!hideseek_game::parseCommandLine(argc, argv, line, &exit_code)) return exit_code;
  if (network != "ff" && network != "gru") return usage("--network is ff or gru, got '" + network + "'");
  std::vector<std::string> args{variant};
  if (!key.empty()) args.push_back(key);
  try {
    const auto s = hideseek_game::selectGame(hideseek_game::configDirectory(), game, args[0], variant_file);
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
