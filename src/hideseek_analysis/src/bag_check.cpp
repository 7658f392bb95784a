#include "hideseek_analysis/bag_check.h"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <vector>

#include "hideseek_game/wire_reader.h"

namespace hideseek_analysis {

namespace {

using hideseek_game::WireReader;

constexpr char kVersionLine[] = "#ROSBAG V2.0\n";
constexpr size_t kVersionBytes = sizeof(kVersionLine) - 1;
constexpr char kStepBatch[] = "hideseek_msgs/StepBatch";
enum Op : uint8_t { kMessage = 2, kBagHeader = 3, kIndex = 4, kChunk = 5, kChunkInfo = 6, kConnection = 7 };

// Thrown inside the check, turned into its returned problem.
struct Bad {
  std::string what;
};
[[noreturn]] void bad(uint64_t at, const std::string& what) {
  throw Bad{"at byte " + std::to_string(at) + ": " + what};
}

// A record's header fields, <u32 length><name>=<value> each.
class Fields {
 public:
  Fields(const uint8_t* data, size_t size, uint64_t at) : at_(at) {
    WireReader r(data, size);
    while (r.left()) {
      uint32_t n = 0;
      if (!r.u32(n) || n > r.left()) bad(at, "a record header field runs past its header");
      const char* f = reinterpret_cast<const char*>(r.here());
      r.skip(n);
      const std::string field(f, n);
      const size_t eq = field.find('=');
      if (eq == std::string::npos || eq == 0) bad(at, "a record header field is not name=value");
      if (!values_.emplace(field.substr(0, eq), field.substr(eq + 1)).second) {
        bad(at, "record header field '" + field.substr(0, eq) + "' appears twice");
      }
    }
  }
  const std::string& text(const char* name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) bad(at_, std::string("the record has no '") + name + "' field");
    return it->second;
  }
  template <typename T>
  T number(const char* name) const {
    const std::string& v = text(name);
    if (v.size() != sizeof(T)) bad(at_, std::string("field '") + name + "' has " + std::to_string(v.size()) + " bytes");
    T x;
    std::memcpy(&x, v.data(), sizeof(T));
    return x;
  }
  uint8_t op() const { return number<uint8_t>("op"); }

 private:
  uint64_t at_;
  std::map<std::string, std::string> values_;
};

struct Record {
  uint64_t at = 0;    // where the record starts
  uint64_t data = 0;  // where its data starts
  uint32_t size = 0;  // of its data
  uint64_t next = 0;  // where the next record starts
  std::vector<uint8_t> header;
};

// Bytes read by position: the file, or a chunk decompressed in memory.
class Source {
 public:
  virtual ~Source() = default;
  virtual uint64_t size() const = 0;
  virtual void read(uint64_t at, void* out, size_t n) = 0;  // [at, at + n) checked to lie inside
};

class FileSource : public Source {
 public:
  explicit FileSource(const std::string& path) : in_(path, std::ios::binary) {
    if (!in_) throw Bad{"cannot be opened"};
    in_.seekg(0, std::ios::end);
    size_ = static_cast<uint64_t>(in_.tellg());
  }
  uint64_t size() const override { return size_; }
  void read(uint64_t at, void* out, size_t n) override {
    if (n == 0) return;
    in_.seekg(static_cast<std::streamoff>(at));
    in_.read(static_cast<char*>(out), static_cast<std::streamsize>(n));
    if (!in_) bad(at, "the file could not be read");
  }

 private:
  std::ifstream in_;
  uint64_t size_ = 0;
};

class BufferSource : public Source {
 public:
  explicit BufferSource(const std::vector<uint8_t>& bytes) : bytes_(bytes) {}
  uint64_t size() const override { return bytes_.size(); }
  void read(uint64_t at, void* out, size_t n) override {
    if (n) std::memcpy(out, bytes_.data() + at, n);  // an empty vector's data() may be null
  }

 private:
  const std::vector<uint8_t>& bytes_;
};

// The record at `at`: <u32 header length><header><u32 data length><data>, all inside the source.
Record readRecord(Source& src, uint64_t at, const BagLimits& limits, const char* where) {
  Record r;
  r.at = at;
  const uint64_t end = src.size();
  uint32_t n = 0;
  if (end - at < 4) bad(at, std::string("a record is cut (") + where + " ends at byte " + std::to_string(end) + ")");
  src.read(at, &n, 4);
  if (n > limits.max_record_header) bad(at, "a record header of " + std::to_string(n) + " bytes");
  if (end - at - 4 < static_cast<uint64_t>(n) + 4) {
    bad(at, std::string("a record is cut (") + where + " ends at byte " + std::to_string(end) + ")");
  }
  r.header.resize(n);
  src.read(at + 4, r.header.data(), n);
  src.read(at + 4 + n, &r.size, 4);
  r.data = at + 8 + n;
  if (r.size > end - r.data) {
    bad(at, "a record of " + std::to_string(r.size) + " data bytes is cut (" + where + " ends at byte " +
                std::to_string(end) + ")");
  }
  r.next = r.data + r.size;
  return r;
}

std::vector<uint8_t> readData(Source& src, const Record& r) {
  std::vector<uint8_t> data(r.size);
  src.read(r.data, data.data(), r.size);
  return data;
}

struct Connection {
  std::string type;
  std::string topic;
};

// A connection record's header and data (the connection header: type, md5sum, definition, and
// what the publisher added).
Connection readConnection(Source& src, const Record& r, const Fields& f, uint32_t* id) {
  *id = f.number<uint32_t>("conn");
  const std::vector<uint8_t> data = readData(src, r);
  const Fields c(data.data(), data.size(), r.at);
  for (const char* name : {"type", "md5sum", "message_definition"}) c.text(name);
  return Connection{c.text("type"), f.text("topic")};
}

std::vector<uint8_t> decompress(const std::string& compression, std::vector<uint8_t> in, uint32_t size, uint64_t at) {
  if (compression == "none") {
    if (in.size() != size)
      bad(at, "a stored chunk of " + std::to_string(in.size()) + " bytes declares " + std::to_string(size));
    return in;
  }
  std::vector<uint8_t> out(size);
  unsigned int got = size;
  bool ok = false;
  if (compression == "lz4") {
    ok = roslz4_buffToBuffDecompress(reinterpret_cast<char*>(in.data()), static_cast<unsigned int>(in.size()),
                                     reinterpret_cast<char*>(out.data()), &got) == ROSLZ4_OK;
  } else if (compression == "bz2") {
    ok = BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out.data()), &got, reinterpret_cast<char*>(in.data()),
                                    static_cast<unsigned int>(in.size()), 0, 0) == BZ_OK;
  } else {
    bad(at, "a chunk compressed with '" + compression + "' (rosbag writes none, lz4 or bz2)");
  }
  if (!ok || got != size)
    bad(at, "a " + compression + " chunk does not decompress to its declared " + std::to_string(size) + " bytes");
  return out;
}

class BagCheck {
 public:
  BagCheck(const std::string& path, const BagLimits& limits) : file_(path), limits_(limits) {}

  void run() {
    char version[kVersionBytes];
    if (file_.size() < kVersionBytes) bad(0, "too short for a bag");
    file_.read(0, version, kVersionBytes);
    if (std::string(version, kVersionBytes) != kVersionLine) bad(0, "not a rosbag 2.0 file (no '#ROSBAG V2.0' line)");
    const Record head = readRecord(file_, kVersionBytes, limits_, "the file");
    const Fields h(head.header.data(), head.header.size(), head.at);
    if (h.op() != kBagHeader) bad(head.at, "the first record is not the bag header");
    const uint64_t index_pos = h.number<uint64_t>("index_pos");
    const uint32_t conn_count = h.number<uint32_t>("conn_count");
    const uint32_t chunk_count = h.number<uint32_t>("chunk_count");
    if (index_pos == 0) {
      bad(head.at, "the bag has no index: its recording was not closed (killed?); `rosbag reindex` repairs it");
    }
    if (index_pos > file_.size()) {
      bad(head.at, "the bag is cut: its index is declared at byte " + std::to_string(index_pos) +
                       ", and the file ends at byte " + std::to_string(file_.size()) +
                       " (a copy that did not finish?)");
    }
    if (index_pos < head.next) {
      bad(head.at, "the index position " + std::to_string(index_pos) + " lies outside the bag's records");
    }
    if (conn_count > limits_.max_connections) bad(head.at, std::to_string(conn_count) + " connections");
    if (chunk_count > limits_.max_chunks) bad(head.at, std::to_string(chunk_count) + " chunks");
    uint64_t at = head.next;
    while (at < index_pos) at = chunkAndIndex(at);
    if (at != index_pos) bad(at, "the index position " + std::to_string(index_pos) + " is not where a record starts");
    indexSection(at, conn_count, chunk_count);
  }

 private:
  // A chunk record and the index records after it; returns where the next record starts.
  uint64_t chunkAndIndex(uint64_t at) {
    const Record r = readRecord(file_, at, limits_, "the file");
    const Fields f(r.header.data(), r.header.size(), r.at);
    if (f.op() != kChunk) bad(at, "a record of op " + std::to_string(f.op()) + " where a chunk was expected");
    if (chunks_.size() >= limits_.max_chunks) bad(at, "more than " + std::to_string(limits_.max_chunks) + " chunks");
    const uint32_t size = f.number<uint32_t>("size");
    if (size > limits_.max_chunk || r.size > limits_.max_chunk) {
      bad(at, "a chunk of " + std::to_string(size) + " bytes (at most " + std::to_string(limits_.max_chunk) + ")");
    }
    const std::vector<uint8_t> bytes = decompress(f.text("compression"), readData(file_, r), size, at);
    std::map<uint64_t, uint32_t> messages;  // offset in the chunk -> connection
    std::map<uint32_t, uint32_t> counts;    // connection -> messages
    chunkRecords(bytes, at, &messages, &counts);
    // The index records: every message of the chunk, once, at its offset.
    std::map<uint32_t, uint32_t> indexed;
    uint64_t next = r.next;
    while (next < file_.size()) {
      const Record ir = readRecord(file_, next, limits_, "the file");
      const Fields fi(ir.header.data(), ir.header.size(), ir.at);
      if (fi.op() != kIndex) break;
      if (fi.number<uint32_t>("ver") != 1) bad(next, "an index record of a version other than 1");
      const uint32_t conn = fi.number<uint32_t>("conn");
      const uint32_t count = fi.number<uint32_t>("count");
      if (static_cast<uint64_t>(count) * 12 != ir.size) bad(next, "an index record's entries do not fill its data");
      if (!indexed.emplace(conn, count).second)
        bad(next, "a second index record for connection " + std::to_string(conn));
      const std::vector<uint8_t> entries = readData(file_, ir);
      for (uint32_t i = 0; i < count; ++i) {
        uint32_t offset = 0;
        std::memcpy(&offset, entries.data() + 12 * i + 8, 4);
        const auto m = messages.find(offset);
        if (m == messages.end() || m->second != conn) {
          bad(next, "index entry " + std::to_string(i) + " points at byte " + std::to_string(offset) +
                        " of its chunk, which is not a message of connection " + std::to_string(conn));
        }
      }
      next = ir.next;
    }
    if (indexed != counts) bad(r.at, "the index records after the chunk do not list its messages");
    chunks_.emplace(at, counts);
    return next;
  }

  // The records inside a decompressed chunk: connections and messages.
  void chunkRecords(const std::vector<uint8_t>& bytes, uint64_t chunk_at, std::map<uint64_t, uint32_t>* messages,
                    std::map<uint32_t, uint32_t>* counts) {
    BufferSource src(bytes);
    const std::string where = "the chunk at byte " + std::to_string(chunk_at);
    for (uint64_t at = 0; at < bytes.size();) {
      Record r;
      try {
        r = readRecord(src, at, limits_, where.c_str());
        const Fields f(r.header.data(), r.header.size(), r.at);
        if (f.op() == kConnection) {
          uint32_t id = 0;
          const Connection c = readConnection(src, r, f, &id);
          learn(id, c, at);
        } else if (f.op() == kMessage) {
          const uint32_t conn = f.number<uint32_t>("conn");
          f.number<uint64_t>("time");
          const auto c = connections_.find(conn);
          if (c == connections_.end()) bad(at, "a message of connection " + std::to_string(conn) + ", never declared");
          if (c->second.type == kStepBatch) {
            const std::vector<uint8_t> data = readData(src, r);
            const std::string problem = checkStepBatchBytes(data.data(), data.size(), limits_.max_arenas);
            if (!problem.empty()) bad(at, "StepBatch on " + c->second.topic + ": " + problem);
          }
          messages->emplace(at, conn);
          ++(*counts)[conn];
        } else {
          bad(at, "a record of op " + std::to_string(f.op()) + " inside a chunk");
        }
      } catch (const Bad& e) {
        throw Bad{where + ", " + e.what};
      }
      at = r.next;
    }
  }

  void learn(uint32_t id, const Connection& c, uint64_t at) {
    const auto it = connections_.find(id);
    if (it == connections_.end()) {
      if (connections_.size() >= limits_.max_connections)
        bad(at, "more than " + std::to_string(limits_.max_connections) + " connections");
      connections_.emplace(id, c);
    } else if (it->second.type != c.type || it->second.topic != c.topic) {
      bad(at, "connection " + std::to_string(id) + " declared twice, differently");
    }
  }

  // The connections and chunk infos at the index position, to the end of the file.
  void indexSection(uint64_t at, uint32_t conn_count, uint32_t chunk_count) {
    std::set<uint32_t> seen;
    std::set<uint64_t> infos;
    while (at < file_.size()) {
      const Record r = readRecord(file_, at, limits_, "the file");
      const Fields f(r.header.data(), r.header.size(), r.at);
      if (f.op() == kConnection && infos.empty()) {
        uint32_t id = 0;
        const Connection c = readConnection(file_, r, f, &id);
        const auto it = connections_.find(id);
        if (it == connections_.end() || it->second.type != c.type || it->second.topic != c.topic) {
          bad(at, "connection " + std::to_string(id) + " of the index is not the one its chunks declare");
        }
        if (!seen.insert(id).second) bad(at, "connection " + std::to_string(id) + " twice in the index");
      } else if (f.op() == kChunkInfo) {
        if (f.number<uint32_t>("ver") != 1) bad(at, "a chunk info of a version other than 1");
        const uint64_t pos = f.number<uint64_t>("chunk_pos");
        f.number<uint64_t>("start_time");
        f.number<uint64_t>("end_time");
        const uint32_t count = f.number<uint32_t>("count");
        if (static_cast<uint64_t>(count) * 8 != r.size) bad(at, "a chunk info's entries do not fill its data");
        const auto chunk = chunks_.find(pos);
        if (chunk == chunks_.end()) bad(at, "a chunk info for byte " + std::to_string(pos) + ", where no chunk starts");
        if (!infos.insert(pos).second) bad(at, "a second chunk info for the chunk at byte " + std::to_string(pos));
        const std::vector<uint8_t> entries = readData(file_, r);
        std::map<uint32_t, uint32_t> counts;
        for (uint32_t i = 0; i < count; ++i) {
          uint32_t conn = 0, n = 0;
          std::memcpy(&conn, entries.data() + 8 * i, 4);
          std::memcpy(&n, entries.data() + 8 * i + 4, 4);
          if (!counts.emplace(conn, n).second)
            bad(at, "a chunk info lists connection " + std::to_string(conn) + " twice");
        }
        if (counts != chunk->second) bad(at, "a chunk info's message counts are not its chunk's");
      } else {
        bad(at, "a record of op " + std::to_string(f.op()) + " in the index");
      }
      at = r.next;
    }
    if (seen.size() != conn_count || seen.size() != connections_.size()) {
      bad(at, "the index holds " + std::to_string(seen.size()) + " connections; the bag header declares " +
                  std::to_string(conn_count) + " and its chunks " + std::to_string(connections_.size()));
    }
    if (infos.size() != chunk_count || infos.size() != chunks_.size()) {
      bad(at, "the index holds " + std::to_string(infos.size()) + " chunk infos; the bag header declares " +
                  std::to_string(chunk_count) + ", and there are " + std::to_string(chunks_.size()) + " chunks");
    }
  }

  FileSource file_;
  const BagLimits& limits_;
  std::map<uint32_t, Connection> connections_;
  std::map<uint64_t, std::map<uint32_t, uint32_t>> chunks_;  // position -> connection -> messages
};

}  // namespace

std::string checkBagFile(const std::string& path, const BagLimits& limits) {
  try {
    BagCheck(path, limits).run();
  } catch (const Bad& e) {
    return e.what;
  }
  return "";
}

std::string checkStepBatchBytes(const uint8_t* data, size_t size, size_t max_arenas) {
  WireReader r(data, size);
  uint32_t stamp[3], n = 0;
  uint64_t decision = 0;
  if (!r.bytes(stamp, sizeof stamp) || !r.u32(n) || !r.skip(n)) return "the header is cut";
  if (!r.u64(decision) || !r.u32(n)) return "cut before num_arenas";
  if (n > max_arenas) return "num_arenas " + std::to_string(n) + " (at most " + std::to_string(max_arenas) + ")";
  // Each array in the message's order, with the bytes of one entry (Pose2D: three float64).
  const std::pair<const char*, size_t> arrays[] = {{"episode", 4},
                                                   {"seed", 4},
                                                   {"step", 4},
                                                   {"hider_pose", 24},
                                                   {"seeker_pose", 24},
                                                   {"distance", 4},
                                                   {"hider_sees_seeker", 1},
                                                   {"seeker_sees_hider", 1},
                                                   {"obstacle_in_view", 1},
                                                   {"hider_action", 1},
                                                   {"seeker_action", 1},
                                                   {"reward", 4},
                                                   {"outcome", 1}};
  for (const auto& [name, bytes] : arrays) {
    if (!r.u32(n)) return std::string("cut before ") + name;
    if (n > max_arenas)
      return std::string(name) + " of " + std::to_string(n) + " entries (at most " + std::to_string(max_arenas) + ")";
    if (!r.skip(n * bytes)) return std::string(name) + " runs past the message";
  }
  uint32_t image[3];
  if (!r.bytes(image, sizeof image) || !r.u32(n)) return "cut before images";
  if (!r.skip(n)) return "images of " + std::to_string(n) + " bytes run past the message";
  if (r.left()) return std::to_string(r.left()) + " bytes after the message";
  return "";
}

}  // namespace hideseek_analysis
