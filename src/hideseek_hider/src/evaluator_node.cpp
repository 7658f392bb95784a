// Listens to the world's episode results until the episodes with seeds first_seed..first_seed+N-1
// have ended, then writes evaluation.md, evaluation.csv and episodes.csv (one row per episode)
// to ~output_dir, prints the table and exits.
#include <hideseek_msgs/EpisodeResult.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>

#include "hideseek_game/params.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_game/topic_names.h"
#include "hideseek_hider/episode_tally.h"

namespace {

constexpr int kMaxEpisodes = 1 << 24;  // ~episodes: far beyond any evaluation

// What the node evaluates and where it writes, from its private parameters.
struct EvaluatorOptions {
  int episodes = 100;
  int first_seed = 0;
  std::string output_dir = ".";
  std::string variant;
  std::string game;    // the game played, as the world resolves ~game, ~game_config and ~variant_config
  std::string policy;  // as the table names it: the file played, greedy or sampled
};

// Throws naming the parameter at fault.
EvaluatorOptions loadEvaluatorOptions(const ros::NodeHandle& pnh) {
  EvaluatorOptions o;
  o.episodes = hideseek_game::readInt(pnh, "episodes", 100, 1, kMaxEpisodes);
  o.first_seed = hideseek_game::readInt(pnh, "first_seed", 0, 0, hideseek_game::kMaxSeed);
  o.output_dir = hideseek_game::readString(pnh, "output_dir", ".");
  o.variant = hideseek_game::readString(pnh, "variant", "unknown");
  // The table names the game: the same parameters as the world's, resolved the same way.
  const hideseek_game::VariantConfig played = hideseek_game::loadVariantParams(pnh);
  o.game = played.game.name;
  // A network policy is evaluated either greedily or sampling its actions: the table says which.
  o.policy = hideseek_game::readString(pnh, "policy", "random");
  if (o.policy == hideseek_game::kShippedPolicy) {
    // The table names the file the hider plays (the hider node resolves it the same way).
    o.policy = hideseek_game::shippedPolicyFile(
        hideseek_game::requireString(pnh, "policy_registry", "the run registry file"), played.name,
        hideseek_game::readString(pnh, "network", "auto") == "gru" ? "gru" : "ff", played.game.name);
    if (o.policy.empty()) o.policy = "random";
  }
  // random, a person (play.launch), a node of one's own (policy:=external) and the scripted
  // evaders (scripted/NAME, deterministic rules) have no greedy form.
  if (o.policy != "random" && o.policy != "human" && o.policy != "external" && o.policy.rfind("scripted/", 0) != 0) {
    o.policy += hideseek_game::readBool(pnh, "greedy", true) ? " (greedy" : " (sampled";
    o.policy += hideseek_game::readBool(pnh, "memoryless", false) ? ", memoryless)" : ")";
  }
  // Another seeker than the variant's scripted one: the table says which.
  const std::string seeker = hideseek_game::readString(pnh, "seeker", "");
  if (!seeker.empty()) o.policy += " against the seeker " + seeker;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "evaluator");
  ros::NodeHandle nh, pnh("~");
  EvaluatorOptions options;
  try {
    options = loadEvaluatorOptions(pnh);
  } catch (const std::exception& e) {
    ROS_FATAL("evaluator: %s", e.what());
    return 1;
  }
  const int episodes = options.episodes;
  const std::string& output_dir = options.output_dir;
  // A folder that cannot be written is found out now, not after the whole evaluation.
  std::error_code error;
  std::filesystem::create_directories(output_dir, error);
  const std::string probe = output_dir + "/.evaluator_can_write";
  if (error || !std::ofstream(probe)) {
    ROS_FATAL("evaluator: cannot write to %s (parameter %s)", output_dir.c_str(),
              pnh.resolveName("output_dir").c_str());
    return 1;
  }
  std::remove(probe.c_str());
  hideseek_hider::EpisodeTally tally(static_cast<uint32_t>(episodes), static_cast<uint32_t>(options.first_seed));
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
  // Blocks until a callback is due (or 0.1 s passes, to notice a shutdown): no busy wait.
  while (ros::ok() && !tally.complete()) ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.1));
  if (!tally.complete()) return 1;
  const auto summary = tally.summary();
  const std::string md = hideseek_hider::evaluationMarkdown(options.variant, options.policy, options.game, summary);
  const std::pair<std::string, std::string> files[] = {
      {"evaluation.csv", hideseek_hider::evaluationCsv(options.variant, options.policy, options.game, summary)},
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
