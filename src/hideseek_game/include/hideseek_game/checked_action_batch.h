// An ActionBatch read from its wire bytes with every length checked against the bytes that are
// there before anything is allocated (issue #49). roscpp's own deserializer sizes each array from
// the length the sender wrote, before it checks that the bytes follow, so a hostile 4-byte length
// makes it allocate gigabytes before our callback could refuse anything. The world node subscribes
// with CheckedActionBatch, which is ActionBatch on the wire (same type name, MD5 and definition),
// so publishers are unchanged; a message that does not parse arrives with `problem` set and is
// counted and refused like any other malformed input.
#pragma once

#include <hideseek_msgs/ActionBatch.h>
#include <ros/message_traits.h>
#include <ros/serialization.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "hideseek_game/game_selection.h"  // kMaxArenas: the most a batch may carry

namespace hideseek_game {

struct CheckedActionBatch {
  hideseek_msgs::ActionBatch msg;  // valid only where problem is empty
  std::string problem;             // why the bytes are not an ActionBatch
};

// Parses the wire bytes of one ActionBatch: lengths within the bytes given (the arrays of at most
// max_arenas entries), all bytes used. Returns the problem, or "" with *out filled.
std::string parseActionBatch(const uint8_t* data, size_t size, size_t max_arenas, hideseek_msgs::ActionBatch* out);

// A batch whose arrays hold one entry per arena; "" or why not.
std::string checkActionBatchSize(const hideseek_msgs::ActionBatch& msg, size_t num_arenas);

}  // namespace hideseek_game

namespace ros {
namespace message_traits {
template <>
struct MD5Sum<hideseek_game::CheckedActionBatch> {
  static const char* value() { return MD5Sum<hideseek_msgs::ActionBatch>::value(); }
  static const char* value(const hideseek_game::CheckedActionBatch&) {
    return MD5Sum<hideseek_msgs::ActionBatch>::value();
  }
};
template <>
struct DataType<hideseek_game::CheckedActionBatch> {
  static const char* value() { return DataType<hideseek_msgs::ActionBatch>::value(); }
  static const char* value(const hideseek_game::CheckedActionBatch&) {
    return DataType<hideseek_msgs::ActionBatch>::value();
  }
};
template <>
struct Definition<hideseek_game::CheckedActionBatch> {
  static const char* value() { return Definition<hideseek_msgs::ActionBatch>::value(); }
  static const char* value(const hideseek_game::CheckedActionBatch&) {
    return Definition<hideseek_msgs::ActionBatch>::value();
  }
};
}  // namespace message_traits

namespace serialization {
template <>
struct Serializer<hideseek_game::CheckedActionBatch> {
  template <typename Stream>
  inline static void write(Stream& stream, const hideseek_game::CheckedActionBatch& m) {
    stream.next(m.msg);
  }
  // Reads the whole buffer roscpp hands over (one message) through parseActionBatch.
  template <typename Stream>
  inline static void read(Stream& stream, hideseek_game::CheckedActionBatch& m) {
    const uint32_t size = stream.getLength();
    m.problem = hideseek_game::parseActionBatch(stream.getData(), size, hideseek_game::kMaxArenas, &m.msg);
    stream.advance(size);
  }
  inline static uint32_t serializedLength(const hideseek_game::CheckedActionBatch& m) {
    return serializationLength(m.msg);
  }
};
}  // namespace serialization
}  // namespace ros
