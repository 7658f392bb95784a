// The learned side of an agent's node, for either role: a network policy (policy mode) or a PPO
// training run (train mode), fed one batch of the agent's own camera images, rewards and done
// flags at a time. The hider node and the seeker node both drive it: one trainer, two roles.
#pragma once

#include <ros/ros.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_game/game_options.h"
#include "hideseek_hider/collective.h"
#include "hideseek_hider/hider_defaults.h"
#include "hideseek_hider/hider_policy.h"
#include "hideseek_hider/training_run.h"

namespace hideseek_hider {

enum class LearnerMode { kPolicy, kTrain };

// The parameters of the policy and train modes, read once and validated: a bad value throws before
// the node publishes, naming the parameter (or the file and field).
struct LearnerOptions {
  std::string role = "hider";  // whose policy: hider or seeker; a checkpoint of the other role is refused
  int actions = kActions;      // the role's actions in this game
  hideseek_game::VariantConfig variant;
  LearnerMode mode = LearnerMode::kPolicy;
  // The defaults of the parameters below are config/hider.yaml's (loadHiderDefaults), not these.
  std::string policy;  // checkpoint path (policy mode)
  int threads{};       // intra-op threads of the network
  PrecisionRequest precision{};
  MemoryFormatRequest memory_format{};
  std::optional<NetworkKind> network;  // empty: auto (the checkpoint's; a new training run: ff)
  torch::Device device = torch::kCPU;
  bool greedy{};      // policy mode
  bool memoryless{};  // policy mode, GRU only: every step from the zero state (an ablation)
  // Train mode only.
  TrainingOptions training;  // output_dir, total_steps, checkpoint_interval_s, image size, variant, role
  PpoOptions ppo;
  int num_arenas = 16;
  int seed = 0;
  // Training across machines (DD-PPO): this rank of world_size, the rendezvous (host:port of the
  // store rank 0 hosts) and how long a rank waits for the others.
  RendezvousOptions rendezvous;
};

// Reads the network's parameters (~threads, ~precision, ~memory_format, ~device, ~greedy,
// ~memoryless and, in train mode, ~output_dir, ~total_steps, ~checkpoint_interval, ~ppo_config,
// ~num_arenas, ~seed and the rendezvous) into `o`, whose role, actions, variant, mode, policy and
// network the node has set. Defaults from `defaults`. Where no network plays (`network_used`
// false: a random or scripted agent), only the first four are read, so that a typo is refused in
// every mode.
void loadLearnerParams(const ros::NodeHandle& pnh, const HiderDefaults& defaults, LearnerOptions& o,
                       bool network_used = true);

// One batch for the learner: n arenas, images arena after arena (height x width x 3 bytes each).
struct LearnerBatch {
  size_t n = 0;
  const uint8_t* images = nullptr;
  const std::vector<float>* rewards = nullptr;
  const std::vector<uint8_t>* done = nullptr;
  const std::vector<uint32_t>* step = nullptr;
  const std::vector<uint32_t>* seed = nullptr;
};

class Learner {
 public:
  // Loads the policy (checkpoint of this role, network, image size and action count checked) or
  // starts or resumes the training run, logging what it does under the role's name.
  explicit Learner(const LearnerOptions& o);

  // The actions for a batch. In train mode, empty once training stopped (an error: exitCode() is
  // then 1) or finished (its final checkpoint written): the node then shuts down.
  std::vector<uint8_t> act(const LearnerBatch& batch);
  int exitCode() const { return exit_code_; }
  // The node is stopping (Ctrl-C, roslaunch shutting down): a training run not yet finished writes
  // the checkpoint of its last update, so that the same command resumes from there.
  void stop();

 private:
  void startTraining(const LearnerOptions& o);
  std::vector<uint8_t> trainStep(const LearnerBatch& batch);

  std::string role_;
  size_t image_bytes_;
  std::unique_ptr<NetworkHiderPolicy> policy_;  // policy mode
  std::unique_ptr<Collective> collective_;      // train mode across machines; outlives training_
  std::unique_ptr<TrainingRun> training_;       // train mode
  int exit_code_ = 0;
};

}  // namespace hideseek_hider
