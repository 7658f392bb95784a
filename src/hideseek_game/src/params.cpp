#include "hideseek_game/params.h"

#include <stdexcept>

namespace hideseek_game {

namespace {

std::runtime_error bad(const ros::NodeHandle& nh, const std::string& name, const std::string& problem) {
  return std::runtime_error("parameter " + nh.resolveName(name) + " " + problem);
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
    throw bad(nh, name,
              "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + std::to_string(value));
  }
  return value;
}

bool readBool(const ros::NodeHandle& nh, const std::string& name, bool fallback) {
  bool value = fallback;
  if (nh.hasParam(name) && !nh.getParam(name, value)) throw bad(nh, name, "must be true or false");
  return value;
}

}  // namespace hideseek_game
