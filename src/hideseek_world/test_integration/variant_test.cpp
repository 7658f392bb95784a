// Runs against a variant launch file in lockstep with the random hider (see variant_*.test):
// the three agents are separate processes and episodes end by capture or by the step limit.
#include <gtest/gtest.h>
#include <hideseek_msgs/GameState.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <ros/ros.h>

#include <set>

#include "test_helpers.h"

namespace {

using hideseek_test::nodeUri;

TEST(Variant, WorldSeekerAndHiderAreSeparateProcesses) {
  std::set<std::string> uris;
  for (const std::string node : {"/world", "/seeker", "/hider"}) {
    std::string uri;
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(30.0);
    while ((uri = nodeUri(node)).empty() && ros::WallTime::now() < end) ros::WallDuration(0.1).sleep();
    ASSERT_FALSE(uri.empty()) << node << " is not running";
    uris.insert(uri);
  }
  EXPECT_EQ(uris.size(), 3u) << "each node has its own XML-RPC server, so its own process";
}

TEST(Variant, EpisodesEndByCaptureOrStepLimit) {
  ros::NodeHandle nh, pnh("~");
  const int wanted = pnh.param("episodes", 8);
  const double min_capture = pnh.param("min_capture_fraction", 0.0);
  const int max_steps = pnh.param("max_steps", 1000);
  int captured = 0, survived = 0;
  std::vector<uint32_t> last_step;
  std::set<uint32_t> seeds;
  auto sub = nh.subscribe<hideseek_msgs::ObservationBatch>("hider/observations", 10, [&](const hideseek_msgs::ObservationBatch::ConstPtr& m) {
    if (last_step.size() != m->num_arenas) last_step.assign(m->num_arenas, 0);
    for (size_t i = 0; i < m->num_arenas; ++i) {
      if (m->done[i]) {
        if (m->outcome[i] == hideseek_msgs::GameState::OUTCOME_CAPTURED) {
          ++captured;
        } else {
          EXPECT_EQ(m->outcome[i], hideseek_msgs::GameState::OUTCOME_SURVIVED);
          EXPECT_EQ(last_step[i] + 1, static_cast<uint32_t>(max_steps)) << "survival only at the step limit";
          ++survived;
        }
        seeds.insert(m->seed[i]);
      }
      last_step[i] = m->step[i];
    }
  });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(240.0);
  while (ros::ok() && captured + survived < wanted && ros::WallTime::now() < end) {
    ros::spinOnce();
    ros::WallDuration(0.002).sleep();
  }
  ASSERT_GE(captured + survived, wanted) << "episodes did not finish";
  EXPECT_GE(captured, min_capture * (captured + survived)) << captured << " captures in " << captured + survived;
  EXPECT_GE(seeds.size(), static_cast<size_t>(wanted) / 2) << "new episodes start with new seeds";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "variant_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
