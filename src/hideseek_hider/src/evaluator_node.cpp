// Watches the hider's observation stream until the episodes with seeds first_seed..first_seed+N-1
// have ended, then writes evaluation.md, evaluation.csv and episodes.csv (one row per episode)
// to ~output_dir, prints the table and exits.
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
  const int first_seed = pnh.param("first_seed", 0);
  const std::string output_dir = pnh.param<std::string>("output_dir", ".");
  const std::string variant = pnh.param<std::string>("variant", "unknown");
  // A network policy is evaluated either greedily or sampling its actions: the table says which.
  std::string policy = pnh.param<std::string>("policy", "random");
  if (policy != "random") policy += pnh.param("greedy", true) ? " (greedy)" : " (sampled)";
  if (episodes < 1) {
    ROS_FATAL("evaluator: parameter %s must be at least 1", pnh.resolveName("episodes").c_str());
    return 1;
  }
  if (first_seed < 0) {
    ROS_FATAL("evaluator: parameter %s must not be negative", pnh.resolveName("first_seed").c_str());
    return 1;
  }
  hideseek_hider::EpisodeTally tally(static_cast<uint32_t>(episodes), static_cast<uint32_t>(first_seed));
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
  std::ofstream(output_dir + "/episodes.csv") << hideseek_hider::episodesCsv(tally.records());
  const std::string md = hideseek_hider::evaluationMarkdown(variant, policy, summary);
  std::ofstream(output_dir + "/evaluation.md") << md;
  std::cout << md << std::flush;
  ROS_INFO("evaluator: wrote %s/evaluation.md, evaluation.csv and episodes.csv", output_dir.c_str());
  return 0;
}
