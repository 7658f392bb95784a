// Files the game's packages ship, found through the ROS package path: the same call works in a
// workspace's devel space and in an install prefix, never through a path into a source checkout.
#pragma once

#include <string>

namespace hideseek_game {

// The directory of a ROS package (its share directory once installed). Throws
// std::runtime_error naming the package when ROS_PACKAGE_PATH does not hold it.
std::string packageDirectory(const std::string& package);

// An executable a package installs into its lib/PACKAGE/ (catkin_install_python, add_executable),
// found as catkin_find --libexec finds it: the first workspace or prefix on CMAKE_PREFIX_PATH that
// holds lib/PACKAGE/NAME. Throws std::runtime_error naming both when none does.
std::string packageExecutable(const std::string& package, const std::string& name);

// The game's configuration: variants, maps, game and PPO settings (hideseek_game's config/).
std::string configDirectory();

}  // namespace hideseek_game
