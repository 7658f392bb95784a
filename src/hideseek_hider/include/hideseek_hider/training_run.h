// A PPO training run fed one observation batch at a time: progress, CSV log, checkpoints,
// resume. ROS-free; the hider node's train mode drives it.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_hider/ppo.h"

namespace hideseek_hider {

struct TrainingOptions {
  std::string output_dir;               // checkpoint.pt and training_log.csv live here
  int64_t total_steps = 1000000;        // environment steps (decisions of all arenas together)
  double checkpoint_interval_s = 300.0;  // wall seconds between checkpoints
  std::string variant;
  int image_height = 84;
  int image_width = 84;
};

// What one PPO update reports: the console line and the CSV row come from it.
struct UpdateReport {
  int64_t update = 0;
  int64_t steps = 0;
  double wall_s = 0.0;
  double steps_per_s = 0.0;  // over this run's wall time since start or resume
  double eta_s = 0.0;
  int64_t episodes = 0;      // finished since the run started (this process)
  double mean_length = 0.0;  // over the last 100 finished episodes
  double mean_return = 0.0;
  UpdateStats ppo;
};

class TrainingRun {
 public:
  // Starts fresh, or resumes from output_dir/checkpoint.pt when it exists.
  TrainingRun(const TrainingOptions& options, const PpoOptions& ppo, int num_arenas, torch::Device device);

  // One batch: rewards and done flags of the previous actions, then this step's images.
  // Returns the actions, and the report when the batch completed a rollout and an update ran.
  std::vector<uint8_t> step(const uint8_t* images, const std::vector<float>& rewards,
                            const std::vector<uint8_t>& dones, std::optional<UpdateReport>* report);
  bool finished() const { return trainer_.samplesSeen() >= options_.total_steps; }
  bool resumed() const { return resumed_; }
  int64_t steps() const { return trainer_.samplesSeen(); }
  int64_t totalSteps() const { return options_.total_steps; }
  // Writes output_dir/checkpoint.pt atomically.
  void saveCheckpoint();
  std::string checkpointPath() const { return options_.output_dir + "/checkpoint.pt"; }
  std::string logPath() const { return options_.output_dir + "/training_log.csv"; }

 private:
  TrainingOptions options_;
  int num_arenas_;
  bool resumed_ = false;
  PpoTrainer trainer_;
  bool acted_ = false;
  int64_t updates_ = 0;
  int64_t start_steps_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_checkpoint_;
  std::vector<double> running_return_;
  std::vector<int64_t> running_length_;
  std::deque<std::pair<int64_t, double>> recent_;  // (length, return) of finished episodes
  int64_t episodes_ = 0;
  std::ofstream log_;
};

}  // namespace hideseek_hider
