// The checks a hider and a seeker make of an observation batch before acting on it (beside the
// conversion that builds the batch): each wrong field is named.
#include <gtest/gtest.h>

#include "hideseek_game/msg_conversion.h"

namespace hideseek_game {
namespace {

hideseek_msgs::ObservationBatch observations(uint32_t n) {
  hideseek_msgs::ObservationBatch b;
  b.num_arenas = n;
  b.height = b.width = 2;
  b.images.assign(n * 2 * 2 * 3, 7);
  b.step.assign(n, 0);
  b.seed.assign(n, 1);
  b.rewards.assign(n, 0.f);
  b.done.assign(n, 0);
  return b;
}

hideseek_msgs::SeekerObservationBatch seekerObservations(uint32_t n) {
  hideseek_msgs::SeekerObservationBatch b;
  b.num_arenas = n;
  b.pose.resize(n);
  b.sees_hider.assign(n, 0);
  b.hider_position.resize(n);
  b.step.assign(n, 0);
  b.episode.assign(n, 0);
  b.seed.assign(n, 1);
  b.maps.resize(n);
  b.done.assign(n, 0);
  b.rewards.assign(n, 0.f);
  b.outcome.assign(n, 0);
  return b;
}

TEST(CheckObservationBatch, AcceptsAWholeBatchAndNamesWhatIsWrong) {
  EXPECT_EQ(checkObservationBatch(observations(2), 2, 2, 64), "");
  EXPECT_EQ(checkObservationBatch(observations(2), 84, 84, 64), "images of 2x2, the hider sees 84x84");
  auto b = observations(2);
  b.images.pop_back();
  EXPECT_EQ(checkObservationBatch(b, 2, 2, 64), "23 image bytes for 2 RGB8 images");
  b = observations(2);
  b.rewards.pop_back();
  EXPECT_EQ(checkObservationBatch(b, 2, 2, 64), "rewards has 1 entries for 2 arenas");
  b = observations(2);
  b.done.push_back(0);
  EXPECT_EQ(checkObservationBatch(b, 2, 2, 64), "done has 3 entries for 2 arenas");
  EXPECT_EQ(checkObservationBatch(observations(0), 2, 2, 64), "num_arenas 0 (1 to 64)");
  EXPECT_EQ(checkObservationBatch(observations(65), 2, 2, 64), "num_arenas 65 (1 to 64)");
}

TEST(CheckSeekerObservationBatch, AcceptsAWholeBatchAndNamesWhatIsWrong) {
  EXPECT_EQ(checkSeekerObservationBatch(seekerObservations(3), 64), "");
  auto b = seekerObservations(3);
  b.maps.pop_back();
  EXPECT_EQ(checkSeekerObservationBatch(b, 64), "maps has 2 entries for 3 arenas");
  b = seekerObservations(3);
  b.hider_position.clear();
  EXPECT_EQ(checkSeekerObservationBatch(b, 64), "hider_position has 0 entries for 3 arenas");
  EXPECT_EQ(checkSeekerObservationBatch(seekerObservations(65), 64), "num_arenas 65 (1 to 64)");
  b = seekerObservations(3);
  b.rewards.pop_back();
  EXPECT_EQ(checkSeekerObservationBatch(b, 64), "rewards has 2 entries for 3 arenas");
}

// A learning seeker needs every arena's camera image, of its size; the scripted one needs none.
TEST(CheckSeekerObservationBatch, ALearningSeekerNeedsItsImages) {
  auto b = seekerObservations(2);
  EXPECT_EQ(checkSeekerObservationBatch(b, 64), "");
  EXPECT_EQ(
      checkSeekerObservationBatch(b, 64, 2, 2),
      "no images: a learning seeker needs the world's seeker cameras (the world's ~learned_seeker, which the launch "
      "files set for seeker_mode:=random, policy or train)");
  b.height = b.width = 2;
  b.images.assign(2 * 2 * 2 * 3, 7);
  EXPECT_EQ(checkSeekerObservationBatch(b, 64, 2, 2), "");
  EXPECT_EQ(checkSeekerObservationBatch(b, 64, 84, 84), "images of 2x2, the seeker sees 84x84");
  b.images.pop_back();
  EXPECT_EQ(checkSeekerObservationBatch(b, 64, 2, 2), "23 image bytes for 2 RGB8 images");
}

}  // namespace
}  // namespace hideseek_game
