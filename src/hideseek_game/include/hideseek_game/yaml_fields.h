// Strict YAML field readers: every error names the file and the field path.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <set>
#include <string>

#include "hideseek_game/config_error.h"
#include "hideseek_game/geometry.h"
#include "hideseek_game/map.h"

namespace hideseek_game {

// Reads fields of one YAML mapping, remembering which keys were used.
class YamlFields {
 public:
  YamlFields(const YAML::Node& node, std::string source, std::string path);

  bool has(const std::string& key) const { return node_[key].IsDefined(); }
  double number(const std::string& key, double fallback, double min, double max);
  int integer(const std::string& key, int fallback, int min, int max);
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback, const std::set<std::string>& allowed);
  Vec2 vec2(const YAML::Node& node, const std::string& field) const;
  Rgb rgb(const std::string& key, Rgb fallback);
  YAML::Node child(const std::string& key);
  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& source() const { return source_; }
  // Throws when the mapping holds a key nobody read (a typo would otherwise be ignored).
  void rejectUnknown() const;

 private:
  YAML::Node node_;
  std::string source_;
  std::string path_;
  std::set<std::string> used_;
};

// The largest configuration file read (a game, variant or map file is a few kB).
constexpr uintmax_t kMaxConfigFileBytes = 1 << 20;
// Parses a file, turning syntax errors into ConfigError; refuses what is not a regular file of at
// most kMaxConfigFileBytes.
YAML::Node loadYamlFile(const std::string& path);

}  // namespace hideseek_game
