// Helpers shared by the world core tests.
#pragma once

#include <memory>
#include <string>

#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"
#include "hideseek_game/renderer.h"

namespace hideseek_game::test {

inline std::string configPath(const std::string& relative) { return std::string(HIDESEEK_CONFIG_DIR) + "/" + relative; }

inline VariantConfig loadVariant(const std::string& name) {
  return loadVariantConfig(configPath("game.yaml"), configPath("variants/" + name + ".yaml"));
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
