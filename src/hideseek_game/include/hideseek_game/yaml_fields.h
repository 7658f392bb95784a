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
  // The same fields without a fallback: the key is required, and a file without it is refused
  // ("is missing"). For files that are the one source of their settings' defaults (config/ppo.yaml).
  double number(const std::string& key, double min, double max);
  int integer(const std::string& key, int min, int max);
  bool boolean(const std::string& key);
  // Throws "is missing" when the mapping has no `key`.
  void require(const std::string& key) const;
  // From now on every field read is required, fallback or not: for a file that is the one source
  // of its settings' defaults (a game file that extends none). Returns *this.
  YamlFields& requireEveryKey() {
    every_key_required_ = true;
    return *this;
  }
  std::string text(const std::string& key, const std::string& fallback, const std::set<std::string>& allowed);
  // A list [x, y] of two finite numbers, each in [min, max] (the same checks as number()).
  Vec2 vec2(const YAML::Node& node, const std::string& field, double min, double max) const;
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
  bool every_key_required_ = false;
};

// The largest configuration file read (a game, variant or map file is a few kB).
constexpr uintmax_t kMaxConfigFileBytes = 1 << 20;
// Parses a file, turning syntax errors into ConfigError; refuses what is not a regular file of at
// most kMaxConfigFileBytes.
YAML::Node loadYamlFile(const std::string& path);

}  // namespace hideseek_game
