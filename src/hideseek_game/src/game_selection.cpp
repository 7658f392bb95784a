#include "hideseek_game/game_selection.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "hideseek_game/config_error.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_game/yaml_fields.h"

namespace hideseek_game {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

}  // namespace

std::vector<std::string> gameNames(const std::string& config_dir) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(config_dir, error)) {
    const std::string file = entry.path().filename().string();
    if (file == "game.yaml") {
      names.push_back(kBaseGame);
    } else if (file.size() > 10 && file.compare(0, 5, "game_") == 0 && entry.path().extension() == ".yaml") {
      names.push_back(file.substr(5, file.size() - 10));
    }
  }
  std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    if ((a == kBaseGame) != (b == kBaseGame)) return a == kBaseGame;
    return a < b;
  });
  return names;
}

std::string defaultGame(const std::string& config_dir) {
  const std::string file = config_dir + "/games.yaml";
  const YAML::Node root = loadYamlFile(file);
  if (!root.IsMap()) throw ConfigError(file, "(top level)", "must be a mapping with the key 'default'");
  YamlFields f(root, file, "");
  f.require("default");
  const std::string game = f.text("default", "", {});
  f.rejectUnknown();
  const std::vector<std::string> names = gameNames(config_dir);
  if (std::find(names.begin(), names.end(), game) == names.end()) {
    throw ConfigError(file, "default", "'" + game + "' is not a game here (" + joined(names) + ")");
  }
  return game;
}

std::string gameFile(const std::string& config_dir, const std::string& named) {
  const std::string game = named.empty() ? defaultGame(config_dir) : named;
  const std::string file = config_dir + (game == kBaseGame ? "/game.yaml" : "/game_" + game + ".yaml");
  const bool plain = !game.empty() && game.find('/') == std::string::npos;
  if (!plain || !std::filesystem::is_regular_file(file)) {
    throw ConfigError(config_dir, "game", "'" + game + "' is not a game here (" + joined(gameNames(config_dir)) + ")");
  }
  return file;
}

std::string gameArgument(const std::string& config_dir, const std::string& value) {
  if (value.empty()) return gameFile(config_dir, defaultGame(config_dir));
  const bool file =
      value.find('/') != std::string::npos || (value.size() > 5 && value.compare(value.size() - 5, 5, ".yaml") == 0);
  return file ? value : gameFile(config_dir, value);
}

std::string variantFile(const std::string& config_dir, const std::string& variant) {
  const std::string file = config_dir + "/variants/" + variant + ".yaml";
  const bool plain = !variant.empty() && variant.find('/') == std::string::npos;
  if (!plain || !std::filesystem::is_regular_file(file)) {
    throw ConfigError(
        config_dir + "/variants", "variant",
        "'" + variant + "' is not a variant here (" + joined(variantNames(config_dir + "/variants")) + ")");
  }
  return file;
}

GameSelection selectGame(const std::string& config_dir, const std::string& named, const std::string& variant,
                         const std::string& variant_file) {
  const std::string game = named.empty() ? defaultGame(config_dir) : named;
  GameSelection s;
  s.game = game;
  s.variant = variant;
  s.game_file = gameFile(config_dir, game);
  s.variant_file = variant_file.empty() ? variantFile(config_dir, variant) : variant_file;
  s.config = loadVariantConfig(s.game_file, s.variant_file);
  // A file names its variant: one that says otherwise (a copy renamed, or a slip) is refused before
  // anything is labelled with the wrong name.
  if (s.config.name != variant) {
    throw ConfigError(s.variant_file, "variant",
                      "is '" + s.config.name + "', but the file was given as variant '" + variant +
                          "': give the variant as the file names it, or change the file's variant field");
  }
  if (s.config.game.name != game) {
    throw ConfigError(s.game_file, "game",
                      "is '" + s.config.game.name + "', but the file was selected as game '" + game + "'");
  }
  return s;
}

std::string shippedPolicy(const std::string& registry_file, const GameSelection& selection,
                          const std::string& network) {
  return shippedPolicyFile(registry_file, selection.variant, network, selection.game);
}

}  // namespace hideseek_game
