#include "hideseek_analysis/bag_reader.h"

#include <gtest/gtest.h>
#include <rosbag/bag.h>

#include <filesystem>

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
