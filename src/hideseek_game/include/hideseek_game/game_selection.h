// The one resolver of what a user selects by name: a game (v2, v1) and a variant (basic, ...)
// become the files, the loaded options and the shipped policy. Every node, tool and script asks
// it (the scripts through `rosrun hideseek_game resolve`), so the rule is written once:
//   no game named -> CONFIG/games.yaml's `default`, the one place the default game is written;
//   game v2 -> CONFIG/game.yaml, game N -> CONFIG/game_N.yaml (v1: game_v1.yaml, the first game);
//   variant V -> CONFIG/variants/V.yaml, whose `map` is a file in CONFIG/maps/;
//   the shipped policy -> what the run registry ships for (variant, network, game).
#pragma once

#include <string>
#include <vector>

#include "hideseek_game/game_options.h"

namespace hideseek_game {

// The game whose file is CONFIG/game.yaml, the base the other game files extend. Not the default
// game: that is CONFIG/games.yaml's `default` (defaultGame()).
inline constexpr char kBaseGame[] = "v2";

// How many arenas a game steps together. Watching a game (the variant launch files, the world and
// hider nodes when nobody says) plays one; training and evaluation (train.launch, evaluate.launch,
// analyze.launch) play kTrainingArenas, the batch PPO was tuned with.
inline constexpr int kWatchingArenas = 1;
inline constexpr int kTrainingArenas = 16;
inline constexpr int kMaxArenas = 64;

// The game played where none is named: config_dir/games.yaml's `default`; throws ConfigError
// naming that file where it is missing, malformed or names no game of config_dir.
std::string defaultGame(const std::string& config_dir);
// The game file of `game` (empty: the default game); throws ConfigError naming the game and the
// games config_dir has.
std::string gameFile(const std::string& config_dir, const std::string& game);
// A tool's --game: a game's name (gameFile), or a game file of one's own (a path, or a name that
// ends in .yaml), returned as it is; empty: the default game.
std::string gameArgument(const std::string& config_dir, const std::string& value);
// The games config_dir has (v2, v1, ...), the base game first, then in name order.
std::vector<std::string> gameNames(const std::string& config_dir);
// The variant file of `variant`; throws ConfigError naming the variant and the variants there.
std::string variantFile(const std::string& config_dir, const std::string& variant);

// A variant of a game, read and checked.
struct GameSelection {
  std::string game;
  std::string variant;
  std::string game_file, variant_file;  // absolute or as config_dir gives them
  VariantConfig config;                 // config.map_file: the variant's map
};
// A non-empty `variant_file` (a variant file of one's own) replaces config_dir's file of `variant`.
// ConfigError where the file's variant field (either file's) is not `variant`, the name everything
// it plays is labelled with.
GameSelection selectGame(const std::string& config_dir, const std::string& game, const std::string& variant,
                         const std::string& variant_file = "");

// The weights the registry ships for the selection's variant, `network` (ff, gru) and game, or "".
std::string shippedPolicy(const std::string& registry_file, const GameSelection& selection,
                          const std::string& network = "ff");

}  // namespace hideseek_game
