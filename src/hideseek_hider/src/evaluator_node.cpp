// Watches the hider's observation stream until the episodes with seeds 0..N-1 have ended, then
// writes evaluation.md and evaluation.csv to ~output_dir, prints the table and exits.
#include <hideseek_msgs/GameState.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <ros/ros.h>

#include <fstream>
#include <iostream>

#include "hideseek_hider/episode_tally.h"
#include "hideseek_world/topic_names.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "evaluator");
  ros::NodeHandle nh, pnh("~");
  const int episodes = pnh.param("episodes", 100);
  const std::string output_dir = pnh.param<std::string>("output_dir", ".");
  const std::string variant = pnh.param<std::string>("variant", "unknown");
  // A greedy evaluation is reported as a policy of its own.
  const std::string policy =
      pnh.param<std::string>("policy", "random") + (pnh.param("greedy", false) ? " (greedy)" : "");
  if (episodes < 1) {
    ROS_FATAL("evaluator: parameter %s must be at least 1", pnh.resolveName("episodes").c_str());
    return 1;
  }
  hideseek_hider::EpisodeTally tally(static_cast<uint32_t>(episodes));
  size_t reported = 0;
  auto sub = nh.subscribe<hideseek_msgs::ObservationBatch>(
      hideseek_world::kHiderObservationsTopic, 10, [&](const hideseek_msgs::ObservationBatch::ConstPtr& m) {
        for (size_t i = 0; i < m->num_arenas && i < m->done.size(); ++i) {
          tally.observe(i, m->done[i], m->outcome[i] == hideseek_msgs::GameState::OUTCOME_SURVIVED, m->step[i], m->seed[i]);
        }
        if (tally.collected() >= reported + 10) {
          reported = tally.collected();
          ROS_INFO("evaluator: %zu / %d episodes", reported, episodes);
        }
      });
  while (ros::ok() && !tally.complete()) ros::spinOnce(), ros::WallDuration(0.001).sleep();
  if (!tally.complete()) return 1;
  const auto summary = tally.summary();
  std::ofstream(output_dir + "/evaluation.csv") << hideseek_hider::evaluationCsv(variant, policy, summary);
  const std::string md = hideseek_hider::evaluationMarkdown(variant, policy, summary);
  std::ofstream(output_dir + "/evaluation.md") << md;
  std::cout << md << std::flush;
  ROS_INFO("evaluator: wrote %s/evaluation.md and evaluation.csv", output_dir.c_str());
  return 0;
}
