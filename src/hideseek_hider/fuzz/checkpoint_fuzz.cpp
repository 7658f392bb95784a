// Fuzz target: checkpoint loading, file bytes in (issue #49). The bytes go through the archive
// check (checkCheckpointBytes); what passes is written to a file and loaded as the hider node loads
// a policy (loadCheckpoint, 84 x 84). A refusal must be an exception; a crash beyond our check is
// libtorch's and is recorded in docs/testing.md with its input, not hidden.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/checkpoint_archive.h"
#include "hideseek_hider/hider_net.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    hideseek_hider::checkCheckpointBytes(data, size, "fuzz input");
  } catch (const std::runtime_error&) {
    return 0;
  }
  static const std::string path = "/tmp/hideseek_checkpoint_fuzz." + std::to_string(getpid()) + ".pt";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    hideseek_hider::loadCheckpoint(path, 84, 84);
  } catch (const std::exception&) {
  }
  std::remove(path.c_str());
  return 0;
}
