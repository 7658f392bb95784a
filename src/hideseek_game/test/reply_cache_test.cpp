#include <gtest/gtest.h>
#include <hideseek_game/reply_cache.h>

namespace {

hideseek_msgs::ActionBatch answer(std::vector<uint8_t> actions, std::vector<uint32_t> step) {
  hideseek_msgs::ActionBatch a;
  a.actions = std::move(actions);
  a.step = std::move(step);
  return a;
}

}  // namespace

TEST(ReplyCache, AReSentBatchGetsTheSameAnswer) {
  hideseek_game::ReplyCache cache;
  const ros::Time t(12.5);
  EXPECT_EQ(cache.find(t, {3, 7}, {11, 12}), nullptr);
  cache.keep(t, {11, 12}, answer({1, 4}, {3, 7}));
  const hideseek_msgs::ActionBatch* again = cache.find(t, {3, 7}, {11, 12});
  ASSERT_NE(again, nullptr);
  EXPECT_EQ(again->actions, (std::vector<uint8_t>{1, 4}));
  EXPECT_EQ(again->step, (std::vector<uint32_t>{3, 7}));
}

TEST(ReplyCache, AResetAtTheSameTimeIsAnsweredAfresh) {
  hideseek_game::ReplyCache cache;
  const ros::Time t(12.5);
  cache.keep(t, {11, 12}, answer({1, 4}, {3, 7}));
  EXPECT_EQ(cache.find(t, {0, 0}, {11, 12}), nullptr);                // new step ids: the episodes restarted
  EXPECT_EQ(cache.find(t, {3, 7}, {21, 22}), nullptr);                // new seeds
  EXPECT_EQ(cache.find(ros::Time(13.0), {3, 7}, {11, 12}), nullptr);  // the next step
}

TEST(ReplyCache, AnEmptyAnswerIsNeverReplayed) {
  hideseek_game::ReplyCache cache;
  const ros::Time t(1.0);
  cache.keep(t, {5}, answer({}, {2}));
  EXPECT_EQ(cache.find(t, {2}, {5}), nullptr);
}
