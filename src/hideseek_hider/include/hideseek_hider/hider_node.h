// Wires a HiderPolicy to the world: answers every observation batch with one action batch.
#pragma once

#include <hideseek_msgs/ActionBatch.h>
#include <hideseek_msgs/ObservationBatch.h>
#include <ros/ros.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_game/game_options.h"
#include "hideseek_game/wall_throttle.h"
#include "hideseek_hider/hider_policy.h"
#include "hideseek_hider/training_run.h"

namespace hideseek_hider {

enum class HiderMode { kRandom, kPolicy, kTrain };

// Everything the hider node reads from the parameter server, read once and validated: a bad value
// throws before the node publishes, naming the parameter (or the file and field).
struct HiderNodeOptions {
  hideseek_game::VariantConfig variant;
  HiderMode mode = HiderMode::kRandom;
  // The defaults of the parameters below are config/hider.yaml's (loadHiderDefaults), not these.
  std::string policy = "random";  // checkpoint path (policy mode)
  int threads{};                  // intra-op threads of the network
  PrecisionRequest precision{};
  MemoryFormatRequest memory_format{};
  std::optional<NetworkKind> network;  // empty: auto (the checkpoint's; a new training run: ff)
  torch::Device device = torch::kCPU;  // policy and train modes
  bool greedy{};                       // policy mode
  bool memoryless{};                   // policy mode, GRU only: every step from the zero state (an ablation)
  // Train mode only.
  TrainingOptions training;  // output_dir, total_steps, checkpoint_interval_s, image size, variant
  PpoOptions ppo;
  int num_arenas = 16;
  int seed = 0;
  // Training across machines (DD-PPO): this rank of world_size, the rendezvous (host:port of the
  // store rank 0 hosts) and how long a rank waits for the others.
  RendezvousOptions rendezvous;
};
HiderNodeOptions loadHiderNodeOptions(const ros::NodeHandle& pnh);

class HiderNode {
 public:
  HiderNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // The process's exit status once spinning ends: non-zero when training stopped on an error.
  int exitCode() const { return exit_code_; }

 private:
  void onObservations(const hideseek_msgs::ObservationBatch::ConstPtr& msg);

  void startTraining(const HiderNodeOptions& o);

  ros::NodeHandle nh_;
  std::unique_ptr<HiderPolicy> policy_;     // random and policy modes
  std::unique_ptr<Collective> collective_;  // train mode across machines; outlives training_
  std::unique_ptr<TrainingRun> training_;   // train mode
  int exit_code_ = 0;
  ros::Time last_stamp_;  // a batch the world re-sent gets the same answer again
  hideseek_msgs::ActionBatch last_answer_;
  std::vector<uint32_t> last_seeds_;  // seeds of the batch last_answer_ answers
  int image_height_ = 0;
  int image_width_ = 0;
  ros::Publisher actions_pub_;
  ros::Subscriber observations_sub_;
  uint64_t malformed_ = 0;
  hideseek_game::WallThrottle malformed_throttle_{2.0};  // warnings of malformed batches
};

}  // namespace hideseek_hider
