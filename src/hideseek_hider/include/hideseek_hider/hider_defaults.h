// The hider node's defaults, config/hider.yaml: the one place they are written.
#pragma once

#include <string>

namespace hideseek_hider {

struct HiderDefaults {
  int threads{};
  std::string precision;      // auto | fp32 | bf16
  std::string memory_format;  // auto | channels_last | nchw
  std::string device;         // cpu | cuda
  std::string network;        // auto | ff | gru
  bool greedy{};
  bool memoryless{};
  double total_steps{};
  double checkpoint_interval_s{};
};

// Reads a hider defaults file; every key is required, none may be unknown, and each value is
// checked as the node checks its parameter. Throws hideseek_game::ConfigError naming the file and
// the field.
HiderDefaults loadHiderDefaults(const std::string& path);

}  // namespace hideseek_hider
