// A rosbag file checked record by record before rosbag's reader sees it (issue #49).
//
// rosbag's C++ reader (1.15) trusts the lengths and offsets a bag declares: a record header's
// length, a chunk's uncompressed size, an index entry's offset into its chunk. A cut or crafted bag
// can make it allocate gigabytes or read outside a buffer, and roscpp's deserializer then sizes
// each array of a message from the length written in it. So an analysis bag is walked here first,
// in the 2.0 format rosbag writes: the version line; the bag header; each chunk (stored, lz4 or
// bz2), decompressed by us to exactly its declared size, its records walked, and the index records
// after it, each offset the start of a message of its connection; then the connections and chunk
// infos at the index position, in the numbers the bag header declares, agreeing with the chunks.
// Every hideseek_msgs/StepBatch in it is checked byte for byte (checkStepBatchBytes). A bag that
// passes can still hold a hole in the decisions: StepLog finds that.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace hideseek_analysis {

struct BagLimits {
  uint32_t max_record_header = 1u << 20;  // bytes; rosbag writes a few dozen
  uint32_t max_chunk = 256u << 20;        // bytes, compressed or not; rosbag's default is 768 KiB
  uint32_t max_connections = 4096;
  uint32_t max_chunks = 1u << 20;
  size_t max_arenas = 64;  // per StepBatch: the most a world runs
};

// "" for a bag rosbag can read safely, or the first problem, naming the byte where it is.
std::string checkBagFile(const std::string& path, const BagLimits& limits = BagLimits());

// The serialized bytes of one StepBatch: every array of at most max_arenas entries (the images at
// most what is left) and within the bytes given, and every byte used. "" or the problem.
std::string checkStepBatchBytes(const uint8_t* data, size_t size, size_t max_arenas);

}  // namespace hideseek_analysis
