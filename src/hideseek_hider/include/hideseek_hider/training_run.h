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
  std::string output_dir;  // checkpoint.pt and training_log.csv live here
  // Environment steps (decisions of all arenas together), rounded up to whole rollouts so that
  // every collected sample is trained on and the checkpoint's count is what was trained.
  int64_t total_steps = 1000000;
  double checkpoint_interval_s = 300.0;  // wall seconds between checkpoints
  std::string variant;
  std::string game = "v2";  // recorded in the checkpoint; a checkpoint of another game is not resumed
  int image_height = 84;
  int image_width = 84;
  Precision precision = Precision::kFp32;  // of the network's passes; weights stay fp32
  NetworkKind network = NetworkKind::kFeedForward;
};

// The run's length: `requested` steps rounded up to whole rollouts of `rollout` samples.
int64_t wholeRollouts(int64_t requested, int64_t rollout);

// "42 s", "12 min 05 s", "3 h 07 min": an ETA or a duration that reads at every scale.
std::string formatDuration(double seconds);

// Drops the rows of a training log whose step count is beyond `steps` (updates a killed run logged
// after its last checkpoint) and a last row cut off mid-write, so that a resumed run continues the
// log without duplicates. Returns the number of rows dropped; the header stays. The file is
// rewritten atomically.
int truncateLogAfter(const std::string& path, int64_t steps);

// Where the training loop's wall time went between two updates: waiting for the next batch (the
// world and the seeker stepping, and the messages), the network's inference, the PPO update,
// and the rest (copying the batch, bookkeeping, the log and checkpoints).
struct LoopTimes {
  double wait_s = 0.0;
  double inference_s = 0.0;
  double update_s = 0.0;
  double other_s = 0.0;
  double total() const { return wait_s + inference_s + update_s + other_s; }
};

// What one PPO update reports: the console line and the CSV rows come from it.
struct UpdateReport {
  int64_t update = 0;
  int64_t steps = 0;
  double wall_s = 0.0;       // over the whole run, resumes included
  double steps_per_s = 0.0;  // over this process's wall time since start or resume
  double eta_s = 0.0;
  int64_t episodes = 0;      // finished over the whole run, resumes included
  double mean_length = 0.0;  // over the last 100 finished episodes
  double mean_return = 0.0;
  UpdateStats ppo;
  LoopTimes loop;  // since the previous update (the last rollout's inference and waits, this update)
};

// With a collective of several ranks (DD-PPO), each rank's TrainingRun steps its own arenas and
// the ranks train one network: rank 0's initial weights are broadcast, a resume starts every rank
// from rank 0's checkpoint (rank 0 decides whether there is one, and sends it), steps, episodes
// and the logged statistics are the ranks' together, and rank 0 alone writes the checkpoint and
// the logs. total_steps counts the environment steps of all ranks.
class TrainingRun {
 public:
  // Starts fresh, or resumes from output_dir/checkpoint.pt (rank 0's) when it exists. The
  // collective, if any, must outlive the run.
  TrainingRun(const TrainingOptions& options, const PpoOptions& ppo, int num_arenas, torch::Device device,
              Collective* collective = nullptr);

  // One batch: rewards and done flags of the previous actions, then this step's images.
  // Returns the actions, and the report when the batch completed a rollout and an update ran.
  std::vector<uint8_t> step(const uint8_t* images, const std::vector<float>& rewards, const std::vector<uint8_t>& dones,
                            std::optional<UpdateReport>* report);
  bool finished() const { return steps() >= options_.total_steps; }
  bool resumed() const { return resumed_; }
  // Log rows of updates lost with the killed process, dropped at resume.
  int droppedLogRows() const { return dropped_log_rows_; }
  // Environment steps of all ranks.
  int64_t steps() const { return trainer_.samplesSeen() * world_; }
  int64_t totalSteps() const { return options_.total_steps; }
  int numArenas() const { return num_arenas_; }
  // Writes output_dir/checkpoint.pt atomically; on a rank other than 0, nothing.
  void saveCheckpoint();
  const PpoTrainer& trainer() const { return trainer_; }
  int rank() const { return rank_; }
  std::string checkpointPath() const { return options_.output_dir + "/checkpoint.pt"; }
  std::string logPath() const { return options_.output_dir + "/training_log.csv"; }
  // One row per update: update,steps,wait_s,inference_s,update_s,other_s (LoopTimes).
  std::string loopProfilePath() const { return options_.output_dir + "/loop_profile.csv"; }

 private:
  TrainingOptions options_;
  int num_arenas_;
  Collective* collective_;
  int rank_, world_;
  std::string resume_from_;  // the checkpoint this rank starts from ("": a fresh run)
  bool resumed_ = false;
  int dropped_log_rows_ = 0;
  PpoTrainer trainer_;
  bool acted_ = false;
  int64_t updates_ = 0;
  int64_t start_steps_ = 0;
  double start_wall_s_ = 0.0;  // wall seconds the run had trained before this process
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_checkpoint_;
  std::vector<double> running_return_;
  std::vector<int64_t> running_length_;
  std::deque<std::pair<int64_t, double>> recent_;  // (length, return) of finished episodes
  int64_t episodes_ = 0;                           // of all ranks
  int64_t new_episodes_ = 0;                       // this rank's since the last update
  std::ofstream log_;
  std::ofstream loop_log_;
  LoopTimes loop_;
  std::optional<std::chrono::steady_clock::time_point> last_exit_;  // when step() last returned
};

}  // namespace hideseek_hider
