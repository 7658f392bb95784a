// The world node reads ActionBatch through CheckedActionBatch: what roscpp serializes parses back
// exactly; a cut message, trailing bytes, too many arenas and hostile lengths are refused with the
// reason, before anything is allocated.
#include "hideseek_game/checked_action_batch.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace {

std::vector<uint8_t> serialize(const hideseek_msgs::ActionBatch& m) {
  std::vector<uint8_t> bytes(ros::serialization::serializationLength(m));
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(out, m);
  return bytes;
}

hideseek_msgs::ActionBatch batch() {
  hideseek_msgs::ActionBatch m;
  m.header.seq = 7;
  m.header.stamp.sec = 12;
  m.header.frame_id = "map";
  m.actions = {1, 4, 0};
  m.step = {5, 6, 70000};
  return m;
}

}  // namespace

TEST(CheckedActionBatch, WhatRoscppWritesParsesBackExactly) {
  const std::vector<uint8_t> bytes = serialize(batch());
  hideseek_msgs::ActionBatch got;
  ASSERT_EQ(hideseek_game::parseActionBatch(bytes.data(), bytes.size(), 64, &got), "");
  EXPECT_EQ(got, batch());
  // Through roscpp's deserialization, as the subscription does.
  hideseek_game::CheckedActionBatch checked;
  std::vector<uint8_t> copy = bytes;
  ros::serialization::IStream in(copy.data(), static_cast<uint32_t>(copy.size()));
  ros::serialization::deserialize(in, checked);
  EXPECT_EQ(checked.problem, "");
  EXPECT_EQ(checked.msg, batch());
  EXPECT_EQ(hideseek_game::checkActionBatchSize(checked.msg, 3), "");
  EXPECT_EQ(hideseek_game::checkActionBatchSize(checked.msg, 2), "3 actions and 3 step ids for 2 arenas");
}

TEST(CheckedActionBatch, CutOrPaddedMessagesAreRefused) {
  const std::vector<uint8_t> bytes = serialize(batch());
  hideseek_msgs::ActionBatch got;
  for (size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_NE(hideseek_game::parseActionBatch(bytes.data(), n, 64, &got), "") << n << " bytes";
  }
  std::vector<uint8_t> padded = bytes;
  padded.push_back(0);
  EXPECT_EQ(hideseek_game::parseActionBatch(padded.data(), padded.size(), 64, &got), "1 bytes after the message");
  EXPECT_EQ(hideseek_game::parseActionBatch(bytes.data(), bytes.size(), 2, &got), "more than 2 actions");
}

TEST(CheckedActionBatch, HostileLengthsAreRefusedBeforeAnyAllocation) {
  hideseek_msgs::ActionBatch m = batch();
  m.header.frame_id.clear();
  std::vector<uint8_t> bytes = serialize(m);
  // Header: seq, sec, nsec, frame_id length (0) = 16 bytes; then the actions' length.
  const uint32_t huge = 0xFFFFFFF0u;
  std::memcpy(bytes.data() + 16, &huge, 4);
  hideseek_msgs::ActionBatch got;
  EXPECT_EQ(hideseek_game::parseActionBatch(bytes.data(), bytes.size(), 64, &got), "actions longer than the message");
  bytes = serialize(m);
  const uint32_t wraps = 0x40000001u;  // 4 x this wraps to 4 in 32 bits
  std::memcpy(bytes.data() + 16 + 4 + 3, &wraps, 4);
  EXPECT_EQ(hideseek_game::parseActionBatch(bytes.data(), bytes.size(), 64, &got), "step longer than the message");
  std::memcpy(bytes.data() + 12, &huge, 4);
  EXPECT_EQ(hideseek_game::parseActionBatch(bytes.data(), bytes.size(), 64, &got),
            "header frame_id longer than the message");
}
