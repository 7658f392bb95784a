// Helpers shared by the world core tests.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "hideseek_game/config_error.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/map.h"
#include "hideseek_game/renderer.h"

namespace hideseek_game::test {

inline std::string configPath(const std::string& relative) { return std::string(HIDESEEK_CONFIG_DIR) + "/" + relative; }

// A variant of the default game, or of the game named, as the nodes resolve it.
inline VariantConfig loadVariant(const std::string& name, const std::string& game = kBaseGame) {
  return selectGame(HIDESEEK_CONFIG_DIR, game, name).config;
}

// What the ConfigError that f throws says, or "" when it throws none.
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

inline std::shared_ptr<const MapSpec> loadMap(const std::string& name) {
  return std::make_shared<const MapSpec>(loadMapFile(configPath("maps/" + name + ".yaml")));
}

// A one-view, one-thread renderer of a variant's camera with a map's colours.
inline RendererOptions rendererOptions(const VariantConfig& v, const MapSpec& map) {
  RendererOptions r = rendererOptionsFor(v.game, map.colors, 1);
  r.render_threads = 1;
  return r;
}

}  // namespace hideseek_game::test
