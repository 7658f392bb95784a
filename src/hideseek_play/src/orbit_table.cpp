// The orbit table (issue #65): a hider circling in the open on a fixed pattern of its five actions
// against each game's seeker, from start angles evenly round the circle (hideseek_play/orbit.h).
// Usage: orbit_table [--config DIR] [--game GAME|FILE]... [--variant NAME] [--angles N] [--shapes 1,2,4];
// --help lists the options.
// Several --game give one table with a block per game (default: v2 and v3).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hideseek_game/command_line.h"
#include "hideseek_game/config_error.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_play/orbit.h"

namespace {

struct Options {
  std::string config_dir;
  std::vector<std::string> games;
  std::string variant = "basic";
  int angles = 24;
  std::vector<int> shapes{1, 2, 3, 4, 5};  // k = 5: radius 3.2 m, the widest that fits with the 3 m gap
};

// The command line into `o`: std::nullopt to go on, else the exit status (--help: 0; a bad command
// line, named with the options: 2).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  namespace po = boost::program_options;
  hideseek_game::CommandLine line;
  line.tool = "orbit_table";
  line.about =
      "orbit_table: a hider circling in the open (forward k steps, then one left turn) against each game's seeker,\n"
      "from start angles evenly round the circle\n"
      "usage: orbit_table [--config DIR] [--game GAME|FILE]... [--variant NAME] [--angles N] [--shapes 1,2,4]";
  std::string shapes;
  line.options.add_options()                                                                                  //
      ("config", po::value(&o.config_dir), "the config folder (default: hideseek_game's installed config/)")  //
      ("game", po::value(&o.games), "a game name or file; several give a block each (default: v2 and v3)")    //
      ("variant", po::value(&o.variant)->default_value(o.variant), "the variant")                             //
      ("angles", po::value(&o.angles)->default_value(o.angles), "start angles round the circle (1-3600)")     //
      ("shapes", po::value(&shapes), "comma-separated forward steps per turn, each 1-50 (default: 1,2,3,4,5)");
  int exit_code = 0;
  if (!hideseek_game::parseCommandLine(argc, argv, line, &exit_code)) return exit_code;
  auto fail = [](const std::string& why) {
    std::cerr << "orbit_table: " << why << " (--help lists the options)\n";
    return 2;
  };
  if (o.angles < 1 || o.angles > 3600) return fail("--angles must be in [1, 3600]");
  if (!shapes.empty()) {
    o.shapes.clear();
    std::stringstream list(shapes);
    for (std::string k; std::getline(list, k, ',');) {
      const int steps = std::atoi(k.c_str());
      if (steps < 1 || steps > 50) return fail("--shapes: forward steps per turn must be in [1, 50], got '" + k + "'");
      o.shapes.push_back(steps);
    }
  }
  if (o.games.empty()) o.games = {"v2", "v3"};
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto exit_code = parseArgs(argc, argv, o)) return *exit_code;
  try {
    if (o.config_dir.empty()) o.config_dir = hideseek_game::configDirectory();
    std::printf("Orbit evader (forward k steps, then one left turn) against the seeker, %s, %d start angles\n\n",
                o.variant.c_str(), o.angles);
    std::printf(
        "| game | k | radius (m) | hider's mean speed (m/s) | start angles survived | mean living steps | "
        "seeker sees hider | both see each other | mean distance (m) |\n| --- | --- | --- | --- | --- | --- | --- | "
        "--- "
        "| --- |\n");
    for (const auto& game : o.games) {
      const std::string file = hideseek_game::gameArgument(o.config_dir, game);
      const auto v = hideseek_game::loadVariantConfig(file, hideseek_game::variantFile(o.config_dir, o.variant));
      for (const int k : o.shapes) {
        const hideseek_play::OrbitShape shape{k};
        const auto played = hideseek_play::playOrbitAngles(v, shape, o.angles);
        int survived = 0;
        double steps = 0.0, seen = 0.0, mutual = 0.0, dist = 0.0;
        for (const auto& e : played) {
          survived += e.survived;
          steps += e.living_steps;
          seen += e.seen_share * e.living_steps;
          mutual += e.mutual_share * e.living_steps;
          dist += e.mean_distance * e.living_steps;
        }
        std::printf("| %s | %d | %.2f | %.2f | %d / %d | %.1f | %.0f %% | %.0f %% | %.2f |\n", v.game.name.c_str(), k,
                    hideseek_play::orbitRadius(v.game, shape), hideseek_play::orbitSpeed(v.game, shape), survived,
                    o.angles, steps / played.size(), 100.0 * seen / steps, 100.0 * mutual / steps, dist / steps);
        std::fflush(stdout);
      }
    }
  } catch (const hideseek_game::ConfigError& e) {
    std::cerr << "orbit_table: " << e.what() << '\n';
    return 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "orbit_table: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
