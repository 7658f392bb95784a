// What a checkpoint file must look like before libtorch is handed its bytes (issue #49). libtorch
// 1.13's archive reader trusts the zip directory and the pickled records it reads, and crafted
// files crash it. So the zip layout is checked first against what our checkpoints hold: one
// top folder; only data.pkl, constants.pkl, version, byteorder, .data/..., data/N and code/...
// entries; every entry stored (uncompressed) within the file, its local header where the directory
// says; no ZIP64; bounded counts and sizes. A file that passes may still be refused by libtorch,
// with an error; one that fails is refused here, naming the file and the rule it breaks.
#pragma once

#include <cstdint>
#include <string>

namespace hideseek_hider {

struct CheckpointLimits {
  uint64_t max_file_bytes = 512ull << 20;  // a GRU training checkpoint is about 50 MB
  uint64_t max_entry_bytes = 128ull << 20;
  uint64_t max_pickle_bytes = 1ull << 20;  // data.pkl and constants.pkl
  uint32_t max_entries = 4096;
};

// Throws std::runtime_error("checkpoint PATH ...") naming the rule the file breaks.
void checkCheckpointArchive(const std::string& path, const CheckpointLimits& limits = {});
// The same on bytes in memory; `name` goes into the message.
void checkCheckpointBytes(const uint8_t* data, uint64_t size, const std::string& name,
                          const CheckpointLimits& limits = {});

}  // namespace hideseek_hider
