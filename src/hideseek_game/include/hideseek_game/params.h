// Node parameters, read one way in every node: each helper returns the value or throws
// std::runtime_error naming the parameter (fully resolved) and what it must be. Nodes read them
// once, into their options struct, before they publish anything.
#pragma once

#include <ros/node_handle.h>

#include <string>
#include <vector>

#include "hideseek_game/game_options.h"

namespace hideseek_game {

// A non-empty string that has no default; `what` says what it is ("a file path").
std::string requireString(const ros::NodeHandle& nh, const std::string& name, const std::string& what = "a file path");
std::string readString(const ros::NodeHandle& nh, const std::string& name, const std::string& fallback);
// One of `allowed`.
std::string readChoice(const ros::NodeHandle& nh, const std::string& name, const std::string& fallback,
                       const std::vector<std::string>& allowed);
int readInt(const ros::NodeHandle& nh, const std::string& name, int fallback, int min, int max);
double readDouble(const ros::NodeHandle& nh, const std::string& name, double fallback, double min, double max);
bool readBool(const ros::NodeHandle& nh, const std::string& name, bool fallback);

// The game and variant a node plays, as game_selection.h resolves them: ~game (a game's name;
// unset or empty: config/games.yaml's default) and ~variant (a variant's name) in the installed
// config/. A file of one's own replaces either: ~game_config (a game file), ~variant_config (a
// variant file). Throws naming the parameter, or the file and field at fault. Where ~game was
// left empty, writes the game it played into ~game (with ~game_config, that file's game field), so
// that rosparam says which one it was.
VariantConfig loadVariantParams(const ros::NodeHandle& private_nh);

}  // namespace hideseek_game
