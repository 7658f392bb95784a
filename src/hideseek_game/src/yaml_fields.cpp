#include "hideseek_game/yaml_fields.h"

#include <cmath>
#include <filesystem>
#include <sstream>

namespace hideseek_game {

YamlFields::YamlFields(const YAML::Node& node, std::string source, std::string path)
    : node_(node), source_(std::move(source)), path_(std::move(path)) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap()) {
    throw ConfigError(source_, path_.empty() ? "<root>" : path_, "must be a mapping");
  }
}

namespace {

std::string range(double min, double max) {
  std::ostringstream s;
  s << "[" << min << ", " << max << "]";
  return s.str();
}

}  // namespace

void YamlFields::require(const std::string& key) const {
  if (!has(key)) {
    throw ConfigError(source_, field(key),
                      "is missing: this file gives every one of its keys (it is their one source of defaults)");
  }
}

double YamlFields::number(const std::string& key, double min, double max) {
  require(key);
  return number(key, 0.0, min, max);
}

int YamlFields::integer(const std::string& key, int min, int max) {
  require(key);
  return integer(key, 0, min, max);
}

bool YamlFields::boolean(const std::string& key) {
  require(key);
  return boolean(key, false);
}

double YamlFields::number(const std::string& key, double fallback, double min, double max) {
  used_.insert(key);
  if (every_key_required_) require(key);
  if (!has(key)) return fallback;
  double v = 0.0;
  try {
    v = node_[key].as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(source_, field(key), "must be a number");
  }
  if (!std::isfinite(v) || v < min || v > max) {
    std::ostringstream s;
    s << "must be in " << range(min, max) << ", got " << v;
    throw ConfigError(source_, field(key), s.str());
  }
  return v;
}

int YamlFields::integer(const std::string& key, int fallback, int min, int max) {
  used_.insert(key);
  if (every_key_required_) require(key);
  if (!has(key)) return fallback;
  int v = 0;
  try {
    v = node_[key].as<int>();
  } catch (const YAML::Exception&) {
    throw ConfigError(source_, field(key), "must be an integer");
  }
  if (v < min || v > max) {
    throw ConfigError(source_, field(key), "must be in " + range(min, max) + ", got " + std::to_string(v));
  }
  return v;
}

bool YamlFields::boolean(const std::string& key, bool fallback) {
  used_.insert(key);
  if (every_key_required_) require(key);
  if (!has(key)) return fallback;
  try {
    return node_[key].as<bool>();
  } catch (const YAML::Exception&) {
    throw ConfigError(source_, field(key), "must be true or false");
  }
}

std::string YamlFields::text(const std::string& key, const std::string& fallback,
                             const std::set<std::string>& allowed) {
  used_.insert(key);
  if (every_key_required_) require(key);
  std::string v = fallback;
  if (has(key)) {
    try {
      v = node_[key].as<std::string>();
    } catch (const YAML::Exception&) {
      throw ConfigError(source_, field(key), "must be a string");
    }
  }
  if (!allowed.empty() && !allowed.count(v)) {
    std::string names;
    for (const auto& a : allowed) names += (names.empty() ? "" : ", ") + a;
    throw ConfigError(source_, field(key), "must be one of {" + names + "}, got '" + v + "'");
  }
  return v;
}

Vec2 YamlFields::vec2(const YAML::Node& node, const std::string& f, double min, double max) const {
  if (!node.IsSequence() || node.size() != 2) throw ConfigError(source_, f, "must be a list [x, y]");
  Vec2 v;
  try {
    v = {node[0].as<double>(), node[1].as<double>()};
  } catch (const YAML::Exception&) {
    throw ConfigError(source_, f, "must hold two numbers");
  }
  for (const double c : {v.x, v.y}) {
    if (!std::isfinite(c) || c < min || c > max) {
      std::ostringstream s;
      s << "must hold two numbers in " << range(min, max) << ", got [" << v.x << ", " << v.y << "]";
      throw ConfigError(source_, f, s.str());
    }
  }
  return v;
}

Rgb YamlFields::rgb(const std::string& key, Rgb fallback) {
  used_.insert(key);
  if (every_key_required_) require(key);
  if (!has(key)) return fallback;
  const YAML::Node n = node_[key];
  if (!n.IsSequence() || n.size() != 3) throw ConfigError(source_, field(key), "must be a list [r, g, b] in [0, 1]");
  Rgb c;
  float* out[3] = {&c.r, &c.g, &c.b};
  for (int i = 0; i < 3; ++i) {
    double v = -1.0;
    try {
      v = n[i].as<double>();
    } catch (const YAML::Exception&) {
    }
    if (!(v >= 0.0 && v <= 1.0)) throw ConfigError(source_, field(key), "colour components must be numbers in [0, 1]");
    *out[i] = static_cast<float>(v);
  }
  return c;
}

YAML::Node YamlFields::child(const std::string& key) {
  used_.insert(key);
  return node_[key];
}

void YamlFields::rejectUnknown() const {
  if (!node_.IsMap()) return;
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    if (!used_.count(key)) throw ConfigError(source_, field(key), "unknown field");
  }
}

YAML::Node loadYamlFile(const std::string& path) {
  // A configuration file is a small regular file: a device, a pipe or a huge file is refused before
  // it is read (reading /dev/zero would never end).
  std::error_code error;
  if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error))
    throw ConfigError(path, "<file>", "is not a regular file");
  if (std::filesystem::is_regular_file(path, error) && std::filesystem::file_size(path, error) > kMaxConfigFileBytes)
    throw ConfigError(path, "<file>", "is larger than " + std::to_string(kMaxConfigFileBytes) + " bytes");
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(path, "<file>", "cannot be opened");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(path, "<file>", std::string("is not valid YAML: ") + e.what());
  }
}

}  // namespace hideseek_game
