// Fuzz target: the analysis's bag reader, bag file bytes in (issue #49). The bytes are written to a
// file and read as analyze_bag and the analysis node read a recording: readStepBag, which checks the
// file record by record (checkBagFile) before rosbag opens it, then reads every StepBatch into the
// step log with its completeness checks. A refusal must be an exception; a crash beyond our check
// is rosbag's or roscpp's and is recorded in docs/reliability.md with its input, not hidden.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

#include "hideseek_analysis/bag_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/hideseek_bag_fuzz." + std::to_string(getpid()) + ".bag";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    hideseek_analysis::readStepBag(path);
  } catch (const std::exception&) {
  }
  std::remove(path.c_str());
  return 0;
}
