#include "hideseek_game/params.h"

#include <cstdio>
#include <stdexcept>
#include <utility>

#include "hideseek_game/config_error.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"

namespace hideseek_game {

namespace {

std::runtime_error bad(const ros::NodeHandle& nh, const std::string& name, const std::string& problem) {
  return std::runtime_error("parameter " + nh.resolveName(name) + " " + problem);
}

// A bound or a value as a user writes it: 1000000000000, 0.05 and -100, not 1000000000000.000000.
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

}  // namespace

std::string requireString(const ros::NodeHandle& nh, const std::string& name, const std::string& what) {
  std::string value;
  if (!nh.getParam(name, value) || value.empty()) throw bad(nh, name, "is required (" + what + ")");
  return value;
}

std::string readString(const ros::NodeHandle& nh, const std::string& name, const std::string& fallback) {
  std::string value = fallback;
  if (nh.hasParam(name) && !nh.getParam(name, value)) throw bad(nh, name, "must be a string");
  return value;
}

std::string readChoice(const ros::NodeHandle& nh, const std::string& name, const std::string& fallback,
                       const std::vector<std::string>& allowed) {
  const std::string value = readString(nh, name, fallback);
  std::string list;
  for (const auto& a : allowed) {
    if (a == value) return value;
    list += (list.empty() ? "'" : ", '") + a + "'";
  }
  throw bad(nh, name, "must be one of " + list + ", got '" + value + "'");
}

int readInt(const ros::NodeHandle& nh, const std::string& name, int fallback, int min, int max) {
  int value = fallback;
  if (nh.hasParam(name) && !nh.getParam(name, value)) throw bad(nh, name, "must be an integer");
  if (value < min || value > max) {
    throw bad(nh, name,
              "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + std::to_string(value));
  }
  return value;
}

double readDouble(const ros::NodeHandle& nh, const std::string& name, double fallback, double min, double max) {
  double value = fallback;
  if (nh.hasParam(name) && !nh.getParam(name, value)) throw bad(nh, name, "must be a number");
  if (!(value >= min && value <= max)) {
    throw bad(nh, name, "must be in [" + number(min) + ", " + number(max) + "], got " + number(value));
  }
  return value;
}

bool readBool(const ros::NodeHandle& nh, const std::string& name, bool fallback) {
  bool value = fallback;
  if (nh.hasParam(name) && !nh.getParam(name, value)) throw bad(nh, name, "must be true or false");
  return value;
}

VariantConfig loadVariantParams(const ros::NodeHandle& nh) {
  const std::string game_file = readString(nh, "game_config", ""), variant_file = readString(nh, "variant_config", "");
  // ~game empty or unset: the default game (config/games.yaml), as the launch files' game:= does.
  const std::string game = readString(nh, "game", ""), variant = readString(nh, "variant", "");
  if (variant.empty() && variant_file.empty()) {
    throw bad(
        nh, "variant",
        "is required (a variant's name, such as basic; or " + nh.resolveName("variant_config") + ", a variant file)");
  }
  const std::string config = configDirectory();
  if (game_file.empty()) {
    try {
      gameFile(config, game);  // the resolver's refusal, under the parameter's name
    } catch (const ConfigError& e) {
      throw bad(nh, "game", "names no game: " + std::string(e.what()));
    }
  }
  // ~game left empty plays config/games.yaml's default: the parameter then says which game that was.
  const auto played = [&](VariantConfig v) {
    if (game.empty()) nh.setParam("game", v.game.name);
    return v;
  };
  if (game_file.empty() && variant_file.empty()) return played(selectGame(config, game, variant).config);
  VariantConfig v = loadVariantConfig(game_file.empty() ? gameFile(config, game) : game_file,
                                      variant_file.empty() ? variantFile(config, variant) : variant_file);
  // The variant's name labels what the nodes write (evaluations, logs, checkpoints): a file of one's
  // own is played under its own name.
  if (variant_file.empty() && v.name != variant) {
    throw bad(nh, "variant",
              "is '" + variant + "', but its file " + variantFile(config, variant) + " says variant '" + v.name +
                  "': give the variant as the file names it, or change the file's variant field");
  }
  if (!variant_file.empty() && !variant.empty() && v.name != variant) {
    throw bad(nh, "variant_config",
              "is variant '" + v.name + "' (" + variant_file + "), but " + nh.resolveName("variant") + " is '" +
                  variant + "': give the variant as the file names it (variant.launch.xml variant:=" + v.name +
                  "), or change the file's variant field");
  }
  return played(std::move(v));
}

}  // namespace hideseek_game
