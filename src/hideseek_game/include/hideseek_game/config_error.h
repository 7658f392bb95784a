// The error every loader throws: it names the file and the field at fault.
#pragma once

#include <stdexcept>
#include <string>

namespace hideseek_game {

class ConfigError : public std::runtime_error {
 public:
  ConfigError(const std::string& source, const std::string& field, const std::string& problem)
      : std::runtime_error(source + ": field '" + field + "': " + problem) {}
};

}  // namespace hideseek_game
