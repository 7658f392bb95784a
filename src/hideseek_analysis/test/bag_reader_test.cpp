#include "hideseek_analysis/bag_reader.h"

#include <gtest/gtest.h>
#include <rosbag/bag.h>

#include <filesystem>

#include "hideseek_analysis/bag_check.h"

namespace hideseek_analysis {
namespace {

hideseek_msgs::StepBatch batch(uint64_t decision) {
  hideseek_msgs::StepBatch b;
  b.decision = decision;
  b.num_arenas = 1;
  b.episode = {0};
  b.seed = {7};
  b.step = {static_cast<uint32_t>(decision)};
  b.hider_pose.resize(1);
  b.seeker_pose.resize(1);
  b.hider_pose[0].x = 0.5 * static_cast<double>(decision);
  b.distance = {3.f};
  b.hider_sees_seeker = {1};
  b.seeker_sees_hider = {0};
  b.obstacle_in_view = {1};
  b.hider_action = {1};
  b.seeker_action = {2};
  b.reward = {0.001f};
  b.outcome = {0};
  b.header.stamp = ros::Time(1.0 + 0.12 * static_cast<double>(decision));
  return b;
}

std::string writeBag(const std::string& name, const std::vector<uint64_t>& decisions) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  bag.setCompression(rosbag::compression::LZ4);
  for (uint64_t d : decisions) bag.write("/world/steps", batch(d).header.stamp, batch(d));
  bag.close();
  return path;
}

TEST(ReadStepBag, ReadsEveryStepOfACompleteBag) {
  const std::string path = writeBag("hideseek_complete.bag", {0, 1, 2, 3});
  const StepLog log = readStepBag(path);
  EXPECT_EQ(log.decisions(), 4u);
  ASSERT_EQ(log.records().size(), 4u);
  EXPECT_DOUBLE_EQ(log.records()[3].hider_x, 1.5);
  EXPECT_TRUE(log.records()[3].hider_sees_seeker);
  EXPECT_FALSE(log.records()[3].seeker_sees_hider);
  EXPECT_EQ(log.records()[3].seeker_action, 2);
  std::filesystem::remove(path);
}

TEST(ReadStepBag, ReportsAMissingStepInsteadOfAnalysingPastIt) {
  const std::string path = writeBag("hideseek_gap.bag", {0, 1, 3, 4});
  try {
    readStepBag(path);
    FAIL() << "a bag with a missing step was read";
  } catch (const MissingStepsError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("decisions 2 to 2 are missing"), std::string::npos) << what;
    EXPECT_NE(what.find("nothing was analysed"), std::string::npos) << what;
  }
  std::filesystem::remove(path);
}

TEST(ReadStepBag, SaysWhatIsWrongWithABagItCannotUse) {
  EXPECT_THROW(readStepBag("/nonexistent/hideseek.bag"), std::runtime_error);
  const std::string empty = (std::filesystem::temp_directory_path() / "hideseek_empty.bag").string();
  { rosbag::Bag bag(empty, rosbag::bagmode::Write); }
  try {
    readStepBag(empty);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no hideseek_msgs/StepBatch"), std::string::npos) << e.what();
  }
  std::filesystem::remove(empty);
}

// bag_fuzz's seed corpus (fuzz/make_bag_corpus.py): bags as rosbag writes them, and copies cut or
// altered as a copy that did not finish, a killed recorder or a hostile file would leave them.
std::string corpus(const std::string& name) { return std::string(HIDESEEK_BAG_CORPUS) + "/" + name; }

std::string refusal(const std::string& name) {
  try {
    readStepBag(corpus(name));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "read without an error";
}

TEST(ReadStepBag, ReadsStoredLz4AndBz2ChunksImagesAndOtherTopics) {
  EXPECT_EQ(readStepBag(corpus("steps_lz4")).decisions(), 24u);
  EXPECT_EQ(readStepBag(corpus("steps_none")).decisions(), 12u);
  EXPECT_EQ(readStepBag(corpus("steps_bz2")).decisions(), 12u);
  EXPECT_EQ(readStepBag(corpus("steps_two_topics")).decisions(), 12u);
  const StepLog images = readStepBag(corpus("steps_images"));
  EXPECT_EQ(images.numImages(), 8);  // 2 arenas x decisions 0, 2, 4, 6
  EXPECT_EQ(images.imageHeight(), 2);
}

TEST(ReadStepBag, RefusesACutUnclosedOrHostileBagBeforeRosbagReadsIt) {
  const std::pair<const char*, const char*> cases[] = {
      {"cut_mid_chunk", "the bag is cut: its index is declared at byte"},
      {"unindexed", "its recording was not closed"},
      {"huge_chunk_size", "a chunk of 4294967280 bytes"},
      {"index_offset_mid_record", "which is not a message of connection"},
      {"record_header_2gib", "a record header of 2147483647 bytes"},
      {"hostile_array_length", "StepBatch on /world/steps: episode of 4294967280 entries"},
  };
  for (const auto& [name, expected] : cases) {
    const std::string what = refusal(name);
    EXPECT_NE(what.find(expected), std::string::npos) << name << ": " << what;
    EXPECT_NE(what.find(corpus(name)), std::string::npos) << name << ": " << what;
    EXPECT_NE(what.find("at byte"), std::string::npos) << name << ": " << what;
  }
}

TEST(CheckStepBatchBytes, AcceptsWhatRoscppWritesAndRefusesEveryCut) {
  auto b = batch(3);
  b.height = b.width = 2;
  b.images.assign(12, 9);
  std::vector<uint8_t> bytes(ros::serialization::serializationLength(b));
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(out, b);
  EXPECT_EQ(checkStepBatchBytes(bytes.data(), bytes.size(), 64), "");
  for (size_t cut = 0; cut < bytes.size(); ++cut) {
    EXPECT_NE(checkStepBatchBytes(bytes.data(), cut, 64), "") << "cut at " << cut;
  }
  bytes.push_back(0);
  EXPECT_EQ(checkStepBatchBytes(bytes.data(), bytes.size(), 64), "1 bytes after the message");
  b.num_arenas = 65;
  bytes.assign(ros::serialization::serializationLength(b), 0);
  ros::serialization::OStream out2(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(out2, b);
  EXPECT_EQ(checkStepBatchBytes(bytes.data(), bytes.size(), 64), "num_arenas 65 (at most 64)");
}

TEST(ToDecisionRecord, NamesTheFieldWhoseLengthIsWrong) {
  auto b = batch(0);
  b.reward.clear();
  try {
    toDecisionRecord(b);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("reward has 0 entries for 1 arenas"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hideseek_analysis
