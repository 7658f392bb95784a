// Helpers shared by the world core tests.
#pragma once

#include <memory>
#include <string>

#include "hideseek_world/game_options.h"
#include "hideseek_world/map.h"

namespace hideseek_world::test {

inline std::string configPath(const std::string& relative) { return std::string(HIDESEEK_CONFIG_DIR) + "/" + relative; }

inline VariantConfig loadVariant(const std::string& name) {
  return loadVariantConfig(configPath("game.yaml"), configPath("variants/" + name + ".yaml"));
}

inline std::shared_ptr<const MapSpec> loadMap(const std::string& name) {
  return std::make_shared<const MapSpec>(loadMapFile(configPath("maps/" + name + ".yaml")));
}

}  // namespace hideseek_world::test
