// A cursor over bytes that came from outside (a message on the wire, a record of a file): every
// read checks first that the bytes are there, so a length written by a sender is never trusted
// before it is compared with what follows (issue #49). ROS serializes little-endian, as this host.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace hideseek_game {

class WireReader {
 public:
  WireReader(const uint8_t* data, size_t size) : data_(data), left_(size) {}

  bool u32(uint32_t& v) { return bytes(&v, 4); }
  bool u64(uint64_t& v) { return bytes(&v, 8); }
  // n bytes into out, n checked against what is left first.
  bool bytes(void* out, size_t n) {
    if (n > left_) return false;
    if (n) std::memcpy(out, data_, n);
    return skip(n);
  }
  bool skip(size_t n) {
    if (n > left_) return false;
    data_ += n;
    left_ -= n;
    return true;
  }
  const uint8_t* here() const { return data_; }
  size_t left() const { return left_; }

 private:
  const uint8_t* data_;
  size_t left_;
};

}  // namespace hideseek_game
