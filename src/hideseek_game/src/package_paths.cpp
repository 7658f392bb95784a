#include "hideseek_game/package_paths.h"

#include <ros/package.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace hideseek_game {

std::string packageDirectory(const std::string& package) {
  const std::string path = ros::package::getPath(package);
  if (path.empty()) {
    throw std::runtime_error("cannot find the ROS package '" + package +
                             "': source the setup.bash of the workspace or install prefix that holds it");
  }
  return path;
}

std::string packageExecutable(const std::string& package, const std::string& name) {
  const char* prefixes = std::getenv("CMAKE_PREFIX_PATH");
  std::stringstream list(prefixes ? prefixes : "");
  for (std::string prefix; std::getline(list, prefix, ':');) {
    if (prefix.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(prefix) / "lib" / package / name;
    if (std::filesystem::is_regular_file(candidate)) return candidate.string();
  }
  throw std::runtime_error("cannot find " + name + " of the ROS package '" + package + "' in lib/" + package +
                           "/ of any prefix on CMAKE_PREFIX_PATH ('" + (prefixes ? prefixes : "") +
                           "'): source the setup.bash that holds it");
}

std::string configDirectory() { return packageDirectory("hideseek_game") + "/config"; }

}  // namespace hideseek_game
