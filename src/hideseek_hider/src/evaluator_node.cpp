// Listens to the world's episode results until the episodes with seeds first_seed..first_seed+N-1
// have ended, then writes evaluation.md, evaluation.csv and episodes.csv (one row per episode)
// to ~output_dir, prints the table and exits.
#include <hideseek_msgs/EpisodeResult.h>
#include <ros/ros.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <utility>

#include "hideseek_hider/episode_tally.h"
#include "hideseek_game/params.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_game/world_node_options.h"
#include "hideseek_game/topic_names.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "evaluator");
  ros::NodeHandle nh, pnh("~");
  int episodes = 0, first_seed = 0;
  std::string output_dir, variant, policy;
  try {
    episodes = hideseek_game::readInt(pnh, "episodes", 100, 1, 1 << 24);
    first_seed = hideseek_game::readInt(pnh, "first_seed", 0, 0, 1 << 30);
    output_dir = hideseek_game::readString(pnh, "output_dir", ".");
    variant = hideseek_game::readString(pnh, "variant", "unknown");
    // A network policy is evaluated either greedily or sampling its actions: the table says which.
    policy = hideseek_game::readString(pnh, "policy", "random");
    if (policy == hideseek_game::kShippedPolicy) {
      // The table names the file the hider plays (the hider node resolves it the same way).
      const hideseek_game::VariantConfig played = hideseek_game::loadVariantParams(pnh);
      policy = hideseek_game::shippedPolicyFile(
          hideseek_game::requireString(pnh, "policy_registry", "the run registry file"), played.name,
          hideseek_game::readString(pnh, "network", "auto") == "gru" ? "gru" : "ff", played.game.name);
      if (policy.empty()) policy = "random";
    }
    if (policy != "random" && policy != "human") {
      policy += hideseek_game::readBool(pnh, "greedy", true) ? " (greedy" : " (sampled";
      policy += hideseek_game::readBool(pnh, "memoryless", false) ? ", memoryless)" : ")";
    }
  } catch (const std::exception& e) {
    ROS_FATAL("evaluator: %s", e.what());
    return 1;
  }
  // A folder that cannot be written is found out now, not after the whole evaluation.
  std::error_code error;
  std::filesystem::create_directories(output_dir, error);
  const std::string probe = output_dir + "/.evaluator_can_write";
  if (error || !std::ofstream(probe)) {
    ROS_FATAL("evaluator: cannot write to %s (parameter %s)", output_dir.c_str(), pnh.resolveName("output_dir").c_str());
    return 1;
  }
  std::remove(probe.c_str());
  hideseek_hider::EpisodeTally tally(static_cast<uint32_t>(episodes), static_cast<uint32_t>(first_seed));
  size_t reported = 0;
  // Every episode result, however far behind the world this node falls: the world publishes them
  // with a deep queue, and evaluate.launch holds lockstep until this subscription is connected.
  auto sub = nh.subscribe<hideseek_msgs::EpisodeResult>(
      hideseek_game::kEpisodesTopic, 10000, [&](const hideseek_msgs::EpisodeResult::ConstPtr& m) {
        tally.record(m->seed, m->steps, m->outcome == hideseek_msgs::EpisodeResult::OUTCOME_SURVIVED);
        if (tally.collected() >= reported + 10) {
          reported = tally.collected();
          ROS_INFO("evaluator: %zu / %d episodes", reported, episodes);
        }
      });
  while (ros::ok() && !tally.complete()) ros::spinOnce(), ros::WallDuration(0.001).sleep();
  if (!tally.complete()) return 1;
  const auto summary = tally.summary();
  const std::string md = hideseek_hider::evaluationMarkdown(variant, policy, summary);
  const std::pair<std::string, std::string> files[] = {
      {"evaluation.csv", hideseek_hider::evaluationCsv(variant, policy, summary)},
      {"episodes.csv", hideseek_hider::episodesCsv(tally.records())},
      {"evaluation.md", md}};
  for (const auto& [name, text] : files) {
    std::ofstream file(output_dir + "/" + name);
    if (!(file << text)) {
      ROS_FATAL("evaluator: cannot write %s/%s", output_dir.c_str(), name.c_str());
      return 1;
    }
  }
  std::cout << md << std::flush;
  ROS_INFO("evaluator: wrote %s/evaluation.md, evaluation.csv and episodes.csv", output_dir.c_str());
  return 0;
}
