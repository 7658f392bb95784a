#include "hideseek_hider/checkpoint_archive.h"

#include <zlib.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <stdexcept>
#include <vector>

namespace hideseek_hider {

namespace {

constexpr uint32_t kEndOfDirectory = 0x06054b50, kDirectoryEntry = 0x02014b50, kLocalHeader = 0x04034b50;

uint16_t u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | p[1] << 8); }
uint32_t u32(const uint8_t* p) { return p[0] | p[1] << 8 | p[2] << 16 | static_cast<uint32_t>(p[3]) << 24; }

bool digitsOnly(const std::string& s) {
  if (s.empty() || s.size() > 9) return false;
  for (const char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

// Whether `rest` (an entry's name below the top folder) is one our checkpoints hold.
bool knownEntry(const std::string& rest) {
  if (rest == "data.pkl" || rest == "constants.pkl" || rest == "version" || rest == "byteorder") return true;
  if (rest.rfind("data/", 0) == 0) return digitsOnly(rest.substr(5));
  return rest.rfind("code/", 0) == 0 || rest.rfind(".data/", 0) == 0;
}

// A value as far as the storage check needs it.
struct PickleValue {
  enum Kind { kOther, kMark, kString, kGlobal, kInt, kTuple } kind = kOther;
  std::string text;  // string, or "module name" of a global
  int64_t number = 0;
  std::vector<PickleValue> items;  // a tuple's
};

// One tensor storage the pickle declares: record data/KEY holds `bytes` bytes.
struct StorageRef {
  std::string key;
  uint64_t bytes = 0;
};

uint64_t elementBytes(const std::string& global) {
  static const std::map<std::string, uint64_t> sizes = {
      {"torch FloatStorage", 4}, {"torch DoubleStorage", 8}, {"torch HalfStorage", 2},  {"torch BFloat16Storage", 2},
      {"torch LongStorage", 8},  {"torch IntStorage", 4},    {"torch ShortStorage", 2}, {"torch CharStorage", 1},
      {"torch ByteStorage", 1},  {"torch BoolStorage", 1}};
  const auto it = sizes.find(global);
  return it == sizes.end() ? 0 : it->second;
}

// Walks a pickle (protocol 2, the opcodes libtorch writes) without running it, and collects the
// tensor storages it declares (BINPERSID of ('storage', torch.XStorage, key, location, numel)).
// Returns the problem, or "".
std::string scanPickle(const uint8_t* p, uint64_t size, std::vector<StorageRef>* storages) {
  std::vector<PickleValue> stack;
  std::map<uint32_t, PickleValue> memo;
  uint64_t at = 0;
  const auto need = [&](uint64_t n) { return at + n <= size; };
  const auto popToMark = [&](std::vector<PickleValue>* items) {
    for (size_t i = stack.size(); i-- > 0;) {
      if (stack[i].kind == PickleValue::kMark) {
        if (items) items->assign(stack.begin() + static_cast<std::ptrdiff_t>(i) + 1, stack.end());
        stack.resize(i);
        return true;
      }
    }
    return false;
  };
  const auto pop = [&](size_t n) {
    if (stack.size() < n) return false;
    stack.resize(stack.size() - n);
    return true;
  };
  while (at < size) {
    if (stack.size() > 100000 || memo.size() > 100000) return "a pickle too deep";
    const uint8_t op = p[at++];
    PickleValue v;
    switch (op) {
      case 0x80:  // PROTO
        if (!need(1)) return "a cut pickle";
        ++at;
        break;
      case '.':  // STOP
        return at == size ? "" : "bytes after the pickle's end";
      case '(':
        v.kind = PickleValue::kMark;
        stack.push_back(v);
        break;
      case ')':
      case '}':
      case ']':
      case 'N':
      case 0x88:
      case 0x89:  // empties, None, True, False
        stack.push_back(v);
        break;
      case 'G':  // BINFLOAT
        if (!need(8)) return "a cut pickle";
        at += 8;
        stack.push_back(v);
        break;
      case 'K':
      case 'M':
      case 'J': {  // BININT1, BININT2, BININT
        const uint64_t n = op == 'K' ? 1 : op == 'M' ? 2 : 4;
        if (!need(n)) return "a cut pickle";
        uint32_t x = 0;
        std::memcpy(&x, p + at, n);
        at += n;
        v.kind = PickleValue::kInt;
        v.number = op == 'J' ? static_cast<int32_t>(x) : static_cast<int64_t>(x);
        stack.push_back(v);
        break;
      }
      case 0x8a: {  // LONG1
        if (!need(1)) return "a cut pickle";
        const uint8_t n = p[at++];
        if (!need(n) || n > 8) return "a pickle integer longer than 8 bytes";
        uint64_t x = 0;
        std::memcpy(&x, p + at, n);
        if (n && n < 8 && (p[at + n - 1] & 0x80)) x |= ~uint64_t{0} << (8 * n);  // sign
        at += n;
        v.kind = PickleValue::kInt;
        v.number = static_cast<int64_t>(x);
        stack.push_back(v);
        break;
      }
      case 'X':
      case 0x8c:
      case 'B':
      case 'C': {  // BINUNICODE, SHORT_BINUNICODE, BINBYTES, SHORT_BINBYTES
        const uint64_t width = op == 'X' || op == 'B' ? 4 : 1;
        if (!need(width)) return "a cut pickle";
        uint32_t n = 0;
        std::memcpy(&n, p + at, width);
        at += width;
        if (!need(n)) return "a pickle string longer than the pickle";
        if (op == 'X' || op == 0x8c) {
          v.kind = PickleValue::kString;
          v.text.assign(reinterpret_cast<const char*>(p + at), n);
        }
        at += n;
        stack.push_back(v);
        break;
      }
      case 'c': {  // GLOBAL module\nname\n
        std::string text;
        for (int lines = 0; lines < 2; ++lines) {
          const uint64_t start = at;
          while (at < size && p[at] != '\n' && at - start < 256) ++at;
          if (at >= size || p[at] != '\n') return "a cut or overlong pickle global";
          text.append(reinterpret_cast<const char*>(p + start), at - start);
          if (lines == 0) text += ' ';
          ++at;
        }
        v.kind = PickleValue::kGlobal;
        v.text = text;
        stack.push_back(v);
        break;
      }
      case 'q':
      case 'r': {  // BINPUT, LONG_BINPUT
        const uint64_t width = op == 'q' ? 1 : 4;
        if (!need(width) || stack.empty()) return "a malformed pickle memo";
        uint32_t idx = 0;
        std::memcpy(&idx, p + at, width);
        at += width;
        memo[idx] = stack.back();
        break;
      }
      case 'h':
      case 'j': {  // BINGET, LONG_BINGET
        const uint64_t width = op == 'h' ? 1 : 4;
        if (!need(width)) return "a cut pickle";
        uint32_t idx = 0;
        std::memcpy(&idx, p + at, width);
        at += width;
        const auto it = memo.find(idx);
        if (it == memo.end()) return "a pickle reading a memo it never wrote";
        stack.push_back(it->second);
        break;
      }
      case 't': {  // TUPLE
        v.kind = PickleValue::kTuple;
        if (!popToMark(&v.items)) return "a pickle tuple without its mark";
        stack.push_back(v);
        break;
      }
      case 0x85:
      case 0x86:
      case 0x87: {  // TUPLE1, TUPLE2, TUPLE3
        const size_t n = op - 0x84;
        if (stack.size() < n) return "a pickle tuple of missing items";
        v.kind = PickleValue::kTuple;
        v.items.assign(stack.end() - static_cast<std::ptrdiff_t>(n), stack.end());
        stack.resize(stack.size() - n);
        stack.push_back(v);
        break;
      }
      case 'Q': {  // BINPERSID: a tensor storage
        if (stack.empty()) return "a pickle persistent id of nothing";
        const PickleValue id = stack.back();
        stack.pop_back();
        const auto& i = id.items;
        if (id.kind != PickleValue::kTuple || i.size() != 5 || i[0].kind != PickleValue::kString ||
            i[0].text != "storage" || i[1].kind != PickleValue::kGlobal || i[2].kind != PickleValue::kString ||
            i[4].kind != PickleValue::kInt)
          return "a pickle persistent id that is no tensor storage";
        const uint64_t element = elementBytes(i[1].text);
        if (element == 0) return "a tensor storage of type '" + i[1].text + "'";
        if (i[4].number < 0 || static_cast<uint64_t>(i[4].number) > (uint64_t{1} << 40) / element)
          return "a tensor storage of " + std::to_string(i[4].number) + " elements";
        storages->push_back({i[2].text, static_cast<uint64_t>(i[4].number) * element});
        stack.push_back(v);
        break;
      }
      case 'R':
      case 0x81:  // REDUCE, NEWOBJ: callable and arguments in, an object out
        if (!pop(2)) return "a pickle call of missing items";
        stack.push_back(v);
        break;
      case 'b':  // BUILD
        if (!pop(1)) return "a pickle build of missing items";
        break;
      case 's':  // SETITEM
        if (!pop(2)) return "a pickle setitem of missing items";
        break;
      case 'a':  // APPEND
        if (!pop(1)) return "a pickle append of missing items";
        break;
      case 'u':
      case 'e':  // SETITEMS, APPENDS
        if (!popToMark(nullptr)) return "a pickle setitems without its mark";
        break;
      default:
        return "pickle opcode 0x" + std::to_string(op) + " (none a checkpoint uses)";
    }
  }
  return "a pickle without its end";
}

// A deflated entry (method 8) inflated to exactly `plain` bytes (at most max_pickle_bytes, checked).
bool inflateRaw(const uint8_t* in, uint32_t packed, uint32_t plain, std::vector<uint8_t>* out) {
  out->assign(plain, 0);
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return false;
  z.next_in = const_cast<Bytef*>(in);
  z.avail_in = packed;
  z.next_out = out->data();
  z.avail_out = plain;
  const int status = inflate(&z, Z_FINISH);
  const bool whole = status == Z_STREAM_END && z.total_out == plain;
  inflateEnd(&z);
  return whole;
}

// The TorchScript that libtorch's OutputArchive writes beside a checkpoint's records: class
// declarations only (a module's attributes, parameters and types), never code. libtorch compiles
// these files when it loads the archive, and its parser crashes on crafted ones (found by
// checkpoint_fuzz), so every line must be one of the forms our checkpoints hold.
std::string checkTorchScriptDeclarations(const uint8_t* p, uint64_t size) {
  static const std::string type =
      R"((int|float|bool|str|Tensor|Tuple\[float, float\]|__torch__\.___torch_mangle_[0-9]{1,6}\.Module))";
  static const std::regex line(
      "|class Module\\(Module\\):"
      "|  __parameters__ = \\[(\"[A-Za-z0-9_/]{1,64}\", ){0,64}\\]"
      "|  __buffers__ = \\[\\]"
      "|  __annotations__ = \\[\\]"
      "|  __annotations__\\[\"[A-Za-z0-9_/]{1,64}\"\\] = " +
      type + "|  [A-Za-z_][A-Za-z0-9_]{0,63} : " + type);
  uint64_t start = 0;
  for (uint64_t i = 0; i <= size; ++i) {
    if (i < size && p[i] != '\n') continue;
    if (i - start > 512) return "a TorchScript line longer than 512 bytes";
    const std::string text(reinterpret_cast<const char*>(p + start), i - start);
    if (!std::regex_match(text, line))
      return "TorchScript that is no checkpoint's declaration: '" + text.substr(0, 80) + "'";
    start = i + 1;
  }
  return "";
}

}  // namespace

void checkCheckpointBytes(const uint8_t* data, uint64_t size, const std::string& name, const CheckpointLimits& limits) {
  const auto fail = [&](const std::string& why) { throw std::runtime_error("checkpoint " + name + ": " + why); };
  if (size > limits.max_file_bytes) fail("larger than " + std::to_string(limits.max_file_bytes) + " bytes");
  if (size < 22) fail("too short to be a checkpoint (a zip archive)");
  // The end-of-directory record: within the last 22 + 65535 bytes (its comment).
  int64_t eocd = -1;
  const uint64_t lowest = size > 22 + 65535 ? size - 22 - 65535 : 0;
  for (uint64_t at = size - 22 + 1; at-- > lowest;) {
    if (u32(data + at) == kEndOfDirectory) {
      eocd = static_cast<int64_t>(at);
      break;
    }
  }
  if (eocd < 0) fail("not a zip archive (no end of central directory)");
  const uint8_t* e = data + eocd;
  const uint32_t entries = u16(e + 10), dir_size = u32(e + 12), dir_offset = u32(e + 16);
  if (u16(e + 4) != 0 || u16(e + 6) != 0 || u16(e + 8) != entries) fail("a multi-part zip archive");
  if (entries == 0xFFFF || dir_size == 0xFFFFFFFFu || dir_offset == 0xFFFFFFFFu) fail("a ZIP64 archive");
  if (entries == 0 || entries > limits.max_entries) fail(std::to_string(entries) + " entries");
  if (static_cast<uint64_t>(dir_offset) + dir_size > static_cast<uint64_t>(eocd))
    fail("the directory lies outside the file");
  std::string top;
  bool has_pickle = false;
  std::map<std::string, uint64_t> records;                // data/KEY -> bytes
  std::vector<std::pair<std::string, uint64_t>> pickles;  // name, offset of its bytes
  uint64_t at = dir_offset, total = 0;
  for (uint32_t i = 0; i < entries; ++i) {
    if (at + 46 > static_cast<uint64_t>(dir_offset) + dir_size)
      fail("the directory ends inside entry " + std::to_string(i));
    const uint8_t* d = data + at;
    if (u32(d) != kDirectoryEntry) fail("directory entry " + std::to_string(i) + " is corrupt");
    const uint16_t flags = u16(d + 8), method = u16(d + 10);
    const uint32_t packed = u32(d + 20), plain = u32(d + 24);
    const uint16_t name_len = u16(d + 28), extra_len = u16(d + 30), comment_len = u16(d + 32);
    const uint32_t local = u32(d + 42);
    const uint64_t next = at + 46 + name_len + extra_len + comment_len;
    if (next > static_cast<uint64_t>(dir_offset) + dir_size)
      fail("directory entry " + std::to_string(i) + " overruns the directory");
    if (name_len == 0 || name_len > 512)
      fail("entry " + std::to_string(i) + " has a name of " + std::to_string(name_len) + " bytes");
    const std::string entry(reinterpret_cast<const char*>(d + 46), name_len);
    // Tensor records and pickles are stored; only the TorchScript source under code/ is deflated.
    const bool code = entry.find("/code/") != std::string::npos;
    if (!(method == 0 && packed == plain) && !(code && method == 8 && plain <= limits.max_pickle_bytes))
      fail("entry '" + entry + "' is compressed (checkpoints store their records)");
    if (flags & 0x1) fail("entry '" + entry + "' is encrypted");
    if (plain > limits.max_entry_bytes) fail("entry '" + entry + "' holds " + std::to_string(plain) + " bytes");
    const size_t slash = entry.find('/');
    if (slash == std::string::npos || slash == 0) fail("entry '" + entry + "' is outside a top folder");
    if (top.empty()) top = entry.substr(0, slash);
    if (entry.compare(0, slash, top) != 0 || entry[slash] != '/')
      fail("entries under more than one top folder ('" + top + "', '" + entry + "')");
    const std::string rest = entry.substr(slash + 1);
    if (!knownEntry(rest)) fail("entry '" + entry + "' is none a checkpoint holds");
    if ((rest == "data.pkl" || rest == "constants.pkl") && plain > limits.max_pickle_bytes)
      fail("entry '" + entry + "' holds " + std::to_string(plain) + " bytes");
    has_pickle |= rest == "data.pkl";
    if (rest.rfind("data/", 0) == 0) records[rest.substr(5)] = plain;
    // The entry's local header and data lie before the directory, under the same name.
    if (static_cast<uint64_t>(local) + 30 > dir_offset) fail("entry '" + entry + "' starts outside the file's data");
    const uint8_t* l = data + local;
    if (u32(l) != kLocalHeader) fail("entry '" + entry + "' has no local header where the directory says");
    const uint64_t body = static_cast<uint64_t>(local) + 30 + u16(l + 26) + u16(l + 28);
    if (u16(l + 26) != name_len || body > dir_offset || std::memcmp(l + 30, entry.data(), name_len) != 0)
      fail("entry '" + entry + "': its local header disagrees with the directory");
    if (body + packed > dir_offset) fail("entry '" + entry + "' runs past the file's data");
    const bool pickle = rest == "data.pkl" || rest == "constants.pkl" ||
                        (rest.size() > 10 && rest.compare(rest.size() - 10, 10, ".debug_pkl") == 0);
    if (pickle) pickles.emplace_back(entry, body);
    if (code && !pickle) {
      std::vector<uint8_t> text;
      if (method == 8 && !inflateRaw(data + body, packed, plain, &text))
        fail("entry '" + entry + "' does not inflate to its " + std::to_string(plain) + " bytes");
      const std::string problem = method == 8 ? checkTorchScriptDeclarations(text.data(), text.size())
                                              : checkTorchScriptDeclarations(data + body, plain);
      if (!problem.empty()) fail("entry '" + entry + "' holds " + problem);
    }
    total += plain;
    at = next;
  }
  if (!has_pickle) fail("no data.pkl (not a libtorch archive)");
  // Every tensor the pickles declare has its record, of exactly the declared size: libtorch 1.13
  // reads a short record past its end (a crash, found by checkpoint_fuzz).
  for (const auto& [entry, offset] : pickles) {
    std::vector<StorageRef> storages;
    uint64_t length = 0;
    for (uint64_t i = dir_offset; i + 46 <= static_cast<uint64_t>(dir_offset) + dir_size;) {
      const uint8_t* d = data + i;
      const uint16_t n = u16(d + 28);
      if (std::string(reinterpret_cast<const char*>(d + 46), n) == entry) length = u32(d + 24);
      i += 46 + n + u16(d + 30) + u16(d + 32);
    }
    const std::string problem = scanPickle(data + offset, length, &storages);
    if (!problem.empty()) fail("entry '" + entry + "' holds " + problem);
    for (const StorageRef& r : storages) {
      const auto it = records.find(r.key);
      if (it == records.end()) fail("tensor record data/" + r.key + " is missing");
      if (it->second != r.bytes)
        fail("tensor record data/" + r.key + " holds " + std::to_string(it->second) + " bytes, its tensor " +
             std::to_string(r.bytes));
    }
  }
  if (total > size) fail("entries hold more bytes than the file");
}

void checkCheckpointArchive(const std::string& path, const CheckpointLimits& limits) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error("checkpoint " + path + " cannot be read (missing or unreadable)");
  const std::streamoff size = in.tellg();
  if (size < 0) throw std::runtime_error("checkpoint " + path + " cannot be read");
  if (static_cast<uint64_t>(size) > limits.max_file_bytes)
    throw std::runtime_error("checkpoint " + path + ": larger than " + std::to_string(limits.max_file_bytes) +
                             " bytes");
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), size))
    throw std::runtime_error("checkpoint " + path + " cannot be read");
  checkCheckpointBytes(bytes.data(), bytes.size(), path, limits);
}

}  // namespace hideseek_hider
