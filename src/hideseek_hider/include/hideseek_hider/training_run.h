// A PPO training run fed one observation batch at a time: progress, CSV log, checkpoints,
// resume. ROS-free; the train mode of the hider node and of the seeker node drives it (one trainer,
// two roles: TrainingOptions::role).
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
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
  Precision precision = Precision::kFp32;                    // of the network's passes; weights stay fp32
  MemoryFormat memory_format = MemoryFormat::kChannelsLast;  // of the encoder (chooseMemoryFormat)
  NetworkKind network = NetworkKind::kFeedForward;
  // Whose policy it trains: "hider", or "seeker" (a learning seeker, from its own camera). Recorded
  // in the checkpoint; a checkpoint of the other role is not resumed.
  std::string role = "hider";
  int actions = kActions;  // the actor's outputs: the hider's 5, or the seeker's in this game
};

// The run's length: `requested` steps rounded up to whole rollouts of `rollout` samples.
int64_t wholeRollouts(int64_t requested, int64_t rollout);

// The network a training runs: `asked`, or with none asked (network auto) the network of the
// checkpoint it resumes from output_dir, else feed-forward. With several ranks only rank 0 writes
// checkpoints, so rank 0's decides and reaches the others: every rank calls this after the
// rendezvous, which compares what each was asked (a rank 1 with no checkpoint of its own would
// otherwise build a feed-forward network beside rank 0's resumed GRU).
NetworkKind trainingNetwork(const std::optional<NetworkKind>& asked, const std::string& output_dir,
                            Collective* collective = nullptr);

// What every rank of a training across machines must share, compared at the rendezvous: role,
// variant, game, the network as asked ("auto" where none was: rank 0's checkpoint decides it after
// the rendezvous), the run's seed, precision, code version, image size, arenas, steps and every
// PPO option. `seed` is this rank's (train.launch gives rank r seed + r x num_arenas): the
// fingerprint holds the run's, the seed less that offset.
Fingerprint trainingFingerprint(const TrainingOptions& t, const PpoOptions& p, int num_arenas,
                                const std::optional<NetworkKind>& network, int64_t seed, int rank);

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

// The episodes a training run finishes: each arena's return and length so far, the episodes
// finished since the last update, and the (length, return) of the last 100, which the log averages
// and a checkpoint keeps.
class EpisodeStatistics {
 public:
  static constexpr size_t kRecent = 100;
  explicit EpisodeStatistics(int num_arenas) : running_return_(num_arenas, 0.0), running_length_(num_arenas, 0) {}
  // One step of every arena: its reward, and whether it ended the episode.
  void add(const std::vector<float>& rewards, const std::vector<uint8_t>& dones);
  // Episodes finished since the last call.
  int64_t takeFinished();
  // Mean length and return over the recent window (0 when empty), summed term by term.
  std::pair<double, double> recentMeans() const;
  const std::deque<std::pair<int64_t, double>>& recent() const { return recent_; }
  // A resumed run's window, from its checkpoint.
  void restore(const std::vector<int64_t>& lengths, const std::vector<double>& returns);

 private:
  std::vector<double> running_return_;
  std::vector<int64_t> running_length_;
  std::deque<std::pair<int64_t, double>> recent_;
  int64_t finished_ = 0;
};

// training_log.csv (one row per update: its statistics) and loop_profile.csv (where its wall time
// went), continued across resumes: rows beyond the checkpoint a run resumes from are dropped first.
class TrainingLog {
 public:
  // `steps`: the steps of the checkpoint the run resumes from (0: a fresh run, whose old rows, from
  // a run killed before its first checkpoint, all go).
  TrainingLog(const std::string& log_path, const std::string& loop_path, int64_t steps);
  void writeUpdate(const UpdateReport& report);  // training_log.csv's row, flushed
  void writeLoop(const UpdateReport& report);    // loop_profile.csv's row, flushed
  int droppedRows() const { return dropped_rows_; }

 private:
  std::ofstream log_, loop_log_;
  int dropped_rows_ = 0;
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
  // Environment steps of all ranks in the updates done: what a checkpoint holds (the rollout being
  // recorded is not in the network yet).
  int64_t updatedSteps() const { return trainer_.samplesUpdated() * world_; }
  // Writes output_dir/checkpoint.pt atomically (the network and optimiser as the last update left
  // them, its steps and wall time); on a rank other than 0, nothing.
  void saveCheckpoint();
  // The process is asked to stop before the run is finished (Ctrl-C, roslaunch shutting down):
  // the checkpoint of the last update, unless the checkpoint holds it already. Whether it wrote one.
  bool saveCheckpointOnStop();
  const PpoTrainer& trainer() const { return trainer_; }
  int rank() const { return rank_; }
  std::string checkpointPath() const { return options_.output_dir + "/checkpoint.pt"; }
  std::string logPath() const { return options_.output_dir + "/training_log.csv"; }
  // One row per update: update,steps,wait_s,inference_s,update_s,other_s (LoopTimes).
  std::string loopProfilePath() const { return options_.output_dir + "/loop_profile.csv"; }

 private:
  using Clock = std::chrono::steady_clock;
  // The update that a full rollout triggers, and its report; `mark` is when the step's time was
  // last accounted for, and moves on.
  UpdateReport update(const torch::Tensor& next_observations, Clock::time_point& mark);
  // The steps, time and episodes of the report, over all ranks.
  void progress(UpdateReport& report, Clock::time_point now);

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
  double start_wall_s_ = 0.0;                              // wall seconds the run had trained before this process
  double updated_wall_s_ = 0.0;                            // the run's wall seconds at its last update
  std::filesystem::file_time_type updated_at_{};           // when that update was made (a file time)
  int64_t checkpoint_steps_ = 0;                           // the steps the checkpoint holds (0: none written)
  std::deque<std::pair<int64_t, double>> updated_recent_;  // the episode window at the last update
  Clock::time_point start_;
  Clock::time_point last_checkpoint_;
  EpisodeStatistics episodes_seen_;  // this rank's arenas
  int64_t episodes_ = 0;             // of all ranks
  std::optional<TrainingLog> log_;   // rank 0's
  LoopTimes loop_;
  std::optional<Clock::time_point> last_exit_;  // when step() last returned
};

}  // namespace hideseek_hider
