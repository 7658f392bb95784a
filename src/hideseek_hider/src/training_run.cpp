#include "hideseek_hider/training_run.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/code_version.h"

namespace hideseek_hider {

namespace {

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

bool exists(const std::string& path) {
  struct stat s;
  return stat(path.c_str(), &s) == 0;
}

HiderNet startingNet(const TrainingOptions& o, const std::string& resume_from) {
  // A resumed run must be the game and variant it was: a run's steps all come from one game and
  // one variant (a checkpoint written before the variant was recorded names none).
  if (!resume_from.empty()) {
    const CheckpointInfo info = readCheckpointInfo(resume_from);
    if (info.game != o.game) {
      throw std::runtime_error("checkpoint " + resume_from + " was trained on game " + info.game +
                               "; this run's game is " + o.game +
                               ": a run is not resumed under another game (train it into another folder)");
    }
    if (!info.variant.empty() && !o.variant.empty() && info.variant != o.variant) {
      throw std::runtime_error("checkpoint " + resume_from + " was trained on variant '" + info.variant +
                               "'; this run's variant is '" + o.variant +
                               "': a run is not resumed under another variant (train it into another folder)");
    }
  }
  // A resumed run must be the network it was: a GRU checkpoint is not resumed as feed-forward.
  HiderNet net = !resume_from.empty()
                     ? loadCheckpoint(resume_from, o.image_height, o.image_width, nullptr, o.network, o.role, o.actions)
                     : HiderNet(o.image_height, o.image_width, o.network, o.actions);
  net->setPrecision(o.precision);
  net->setMemoryFormat(o.memory_format);
  return net;
}

int worldOf(const Collective* c) { return c ? c->worldSize() : 1; }

TrainingOptions roundedToRollouts(TrainingOptions o, const PpoOptions& ppo, int num_arenas, int world) {
  o.total_steps = wholeRollouts(o.total_steps, static_cast<int64_t>(ppo.rollout_steps) * num_arenas * world);
  return o;
}

// The checkpoint a rank starts from: its own output_dir's, or with several ranks rank 0's, which
// rank 0 sends to the others; they keep it in a temporary file until it is loaded.
std::string resumeSource(const TrainingOptions& o, Collective* c) {
  const std::string own = o.output_dir + "/checkpoint.pt";
  if (worldOf(c) == 1) return exists(own) ? own : "";
  std::string bytes;
  if (c->rank() == 0 && exists(own)) {
    std::ifstream in(own, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) throw std::runtime_error("cannot read " + own);
  }
  bytes = broadcastBytes(*c, bytes);
  if (bytes.empty()) return "";
  if (c->rank() == 0) return own;
  const char* tmpdir = std::getenv("TMPDIR");
  std::string path = std::string(tmpdir && *tmpdir ? tmpdir : "/tmp") + "/hideseek_rank0_checkpoint_XXXXXX";
  const int fd = mkstemp(path.data());
  if (fd < 0)
    throw std::runtime_error("cannot create a temporary file for rank 0's checkpoint: " +
                             std::string(std::strerror(errno)));
  const bool written = write(fd, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
  close(fd);
  if (!written) throw std::runtime_error("cannot write rank 0's checkpoint to " + path + " (disk full?)");
  return path;
}

}  // namespace

NetworkKind trainingNetwork(const std::optional<NetworkKind>& asked, const std::string& output_dir,
                            Collective* collective) {
  if (asked) return *asked;
  const std::string own = output_dir + "/checkpoint.pt";
  const bool decides = worldOf(collective) == 1 || collective->rank() == 0;
  NetworkKind network = decides && exists(own) ? readCheckpointInfo(own).network : NetworkKind::kFeedForward;
  if (worldOf(collective) > 1) {
    network = parseNetwork(broadcastBytes(*collective, networkName(network)), "rank 0's network");
  }
  return network;
}

Fingerprint trainingFingerprint(const TrainingOptions& t, const PpoOptions& p, int num_arenas,
                                const std::optional<NetworkKind>& network, int64_t seed, int rank) {
  auto text = [](double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
  };
  return {{"role", t.role},
          {"variant", t.variant},
          {"game", t.game},
          {"network", network ? networkName(*network) : "auto"},
          {"seed (train.launch's)", std::to_string(seed - static_cast<int64_t>(rank) * num_arenas)},
          {"precision", precisionName(t.precision)},
          {"code_version", codeVersion()},
          {"image", std::to_string(t.image_width) + "x" + std::to_string(t.image_height)},
          {"num_arenas", std::to_string(num_arenas)},
          {"total_steps", std::to_string(t.total_steps)},
          {"ppo", "rollout_steps=" + std::to_string(p.rollout_steps) + " epochs=" + std::to_string(p.epochs) +
                      " minibatches=" + std::to_string(p.minibatches) + " learning_rate=" + text(p.learning_rate) +
                      " anneal=" + std::to_string(p.anneal_learning_rate) + " adam_epsilon=" + text(p.adam_epsilon) +
                      " gamma=" + text(p.gamma) + " gae_lambda=" + text(p.gae_lambda) + " clip=" + text(p.clip) +
                      " clip_value_loss=" + std::to_string(p.clip_value_loss) + " value_coef=" + text(p.value_coef) +
                      " entropy_coef=" + text(p.entropy_coef) + " max_grad_norm=" + text(p.max_grad_norm) +
                      " normalize_advantages=" + std::to_string(p.normalize_advantages) +
                      " sequence_length=" + std::to_string(p.sequence_length)}};
}

int64_t wholeRollouts(int64_t requested, int64_t rollout) {
  if (rollout < 1) throw std::invalid_argument("a rollout must hold at least one sample");
  return (requested + rollout - 1) / rollout * rollout;
}

std::string formatDuration(double seconds) {
  const auto total = static_cast<int64_t>(std::llround(std::max(0.0, seconds)));
  char text[64];
  if (total < 60) {
    std::snprintf(text, sizeof(text), "%ld s", static_cast<long>(total));
  } else if (total < 3600) {
    std::snprintf(text, sizeof(text), "%ld min %02ld s", static_cast<long>(total / 60), static_cast<long>(total % 60));
  } else {
    const int64_t minutes = (total + 30) / 60;
    std::snprintf(text, sizeof(text), "%ld h %02ld min", static_cast<long>(minutes / 60),
                  static_cast<long>(minutes % 60));
  }
  return text;
}

int truncateLogAfter(const std::string& path, int64_t steps) {
  std::ifstream in(path);
  if (!in) return 0;
  std::string header, line, kept;
  std::getline(in, header);
  int dropped = 0;
  while (std::getline(in, line)) {
    // A row cut off by a kill mid-write (no newline) is dropped, or the next row would join it.
    if (in.eof()) {
      ++dropped;
      break;
    }
    // Column 2 is the step count (update,steps,...).
    const size_t comma = line.find(',');
    const int64_t row_steps = comma == std::string::npos ? 0 : std::atoll(line.c_str() + comma + 1);
    if (row_steps > steps) {
      ++dropped;
    } else {
      kept += line + '\n';
    }
  }
  in.close();
  if (dropped == 0) return 0;
  const std::string tmp = path + ".tmp";
  std::ofstream out(tmp);
  out << header << '\n' << kept;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + tmp + " (disk full?); " + path + " is left as it was");
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot move " + tmp + " to " + path);
  return dropped;
}

void EpisodeStatistics::add(const std::vector<float>& rewards, const std::vector<uint8_t>& dones) {
  for (size_t i = 0; i < running_return_.size(); ++i) {
    running_return_[i] += rewards[i];
    ++running_length_[i];
    if (dones[i]) {
      recent_.emplace_back(running_length_[i], running_return_[i]);
      if (recent_.size() > kRecent) recent_.pop_front();
      ++finished_;
      running_return_[i] = 0.0;
      running_length_[i] = 0;
    }
  }
}

int64_t EpisodeStatistics::takeFinished() { return std::exchange(finished_, 0); }

std::pair<double, double> EpisodeStatistics::recentMeans() const {
  double length = 0.0, ret = 0.0;
  for (const auto& [l, r] : recent_) {
    length += static_cast<double>(l) / recent_.size();
    ret += r / recent_.size();
  }
  return {length, ret};
}

void EpisodeStatistics::restore(const std::vector<int64_t>& lengths, const std::vector<double>& returns) {
  recent_.clear();
  for (size_t i = 0; i < lengths.size() && i < returns.size(); ++i) recent_.emplace_back(lengths[i], returns[i]);
  while (recent_.size() > kRecent) recent_.pop_front();
}

TrainingLog::TrainingLog(const std::string& log_path, const std::string& loop_path, int64_t steps) {
  // A log without a checkpoint (steps 0) belongs to a run killed before its first checkpoint: none
  // of its updates survive, so neither do its rows.
  dropped_rows_ = truncateLogAfter(log_path, steps);
  truncateLogAfter(loop_path, steps);
  const bool new_log = !exists(log_path);
  log_.open(log_path, std::ios::app);
  if (!log_) throw std::runtime_error("cannot write " + log_path);
  if (new_log) {
    log_ << "update,steps,wall_s,steps_per_s,episodes,mean_length,mean_return,policy_loss,value_loss,entropy,"
            "approx_kl,clip_fraction,learning_rate\n";
  }
  const bool new_loop_log = !exists(loop_path);
  loop_log_.open(loop_path, std::ios::app);
  if (!loop_log_) throw std::runtime_error("cannot write " + loop_path);
  if (new_loop_log) loop_log_ << "update,steps,wait_s,inference_s,update_s,other_s\n";
}

void TrainingLog::writeUpdate(const UpdateReport& r) {
  log_ << r.update << ',' << r.steps << ',' << r.wall_s << ',' << r.steps_per_s << ',' << r.episodes << ','
       << r.mean_length << ',' << r.mean_return << ',' << r.ppo.policy_loss << ',' << r.ppo.value_loss << ','
       << r.ppo.entropy << ',' << r.ppo.approx_kl << ',' << r.ppo.clip_fraction << ',' << r.ppo.learning_rate << '\n';
  log_.flush();
}

void TrainingLog::writeLoop(const UpdateReport& r) {
  loop_log_ << r.update << ',' << r.steps << ',' << r.loop.wait_s << ',' << r.loop.inference_s << ',' << r.loop.update_s
            << ',' << r.loop.other_s << '\n';
  loop_log_.flush();
}

TrainingRun::TrainingRun(const TrainingOptions& options, const PpoOptions& ppo, int num_arenas, torch::Device device,
                         Collective* collective)
    : options_(roundedToRollouts(options, ppo, num_arenas, worldOf(collective))),
      num_arenas_(num_arenas),
      collective_(worldOf(collective) > 1 ? collective : nullptr),
      rank_(collective ? collective->rank() : 0),
      world_(worldOf(collective)),
      resume_from_(resumeSource(options_, collective_)),
      resumed_(!resume_from_.empty()),
      trainer_(startingNet(options_, resume_from_), ppo, num_arenas, device),
      start_(Clock::now()),
      last_checkpoint_(start_),
      episodes_seen_(num_arenas) {
  trainer_.setCollective(collective_);
  if (rank_ == 0) {
    // With its parents, as `mkdir -p` does: the default (~/.ros/hideseek_runs/<variant>) and a
    // user's ~/runs/basic need not exist yet.
    std::error_code error;
    std::filesystem::create_directories(options_.output_dir, error);
    if (error) {
      throw std::runtime_error("cannot create output folder " + options_.output_dir + ": " + error.message());
    }
  }
  if (resumed_) {
    loadTrainingState(resume_from_, trainer_.optimizer());
    const CheckpointInfo info = readCheckpointInfo(resume_from_);
    // The checkpoint counts the steps of all ranks; the trainer counts this rank's.
    trainer_.setSamplesSeen(info.steps / world_);
    start_wall_s_ = info.wall_s;
    episodes_ = info.episodes;
    if (rank_ == 0) {
      episodes_seen_.restore(info.recent_lengths, info.recent_returns);
    } else {
      // Rank 0's generator state came with its checkpoint: the other ranks sample on their own.
      std::remove(resume_from_.c_str());
      torch::manual_seed(static_cast<uint64_t>(info.steps) * 1000003u + static_cast<uint64_t>(rank_));
    }
  } else if (collective_) {
    broadcastModule(*collective_, *trainer_.net());  // every rank starts from rank 0's weights
  }
  trainer_.setTotalSamples(options_.total_steps / world_);
  start_steps_ = steps();
  checkpoint_steps_ = start_steps_;
  updated_wall_s_ = start_wall_s_;
  updated_recent_ = episodes_seen_.recent();
  // the log continues across resumes
  updates_ = start_steps_ / (static_cast<int64_t>(ppo.rollout_steps) * num_arenas * world_);
  if (rank_ != 0) return;  // rank 0 alone writes the logs
  log_.emplace(logPath(), loopProfilePath(), resumed_ ? start_steps_ : 0);
  dropped_log_rows_ = log_->droppedRows();
}

std::vector<uint8_t> TrainingRun::step(const uint8_t* images, const std::vector<float>& rewards,
                                       const std::vector<uint8_t>& dones, std::optional<UpdateReport>* report) {
  const Clock::time_point enter = Clock::now();
  if (last_exit_) loop_.wait_s += seconds(enter - *last_exit_);
  Clock::time_point mark = enter;  // the step's time is accounted for up to here
  report->reset();
  const int64_t n = num_arenas_;
  const torch::Tensor obs =
      torch::from_blob(const_cast<uint8_t*>(images), {n, options_.image_height, options_.image_width, 3}, torch::kUInt8)
          .clone();
  if (acted_) {
    // The rewards and done flags of the actions taken at the last step.
    episodes_seen_.add(rewards, dones);
    const torch::Tensor r = torch::tensor(rewards);
    const torch::Tensor d =
        torch::from_blob(const_cast<uint8_t*>(dones.data()), {n}, torch::kUInt8).to(torch::kFloat32);
    if (trainer_.record(r, d)) *report = update(obs, mark);
  }
  acted_ = true;
  const Clock::time_point act_start = Clock::now();
  loop_.other_s += seconds(act_start - mark);
  const torch::Tensor actions = trainer_.act(obs).to(torch::kUInt8).contiguous();
  const Clock::time_point act_end = Clock::now();
  loop_.inference_s += seconds(act_end - act_start);
  std::vector<uint8_t> out(actions.data_ptr<uint8_t>(), actions.data_ptr<uint8_t>() + n);
  last_exit_ = Clock::now();
  loop_.other_s += seconds(*last_exit_ - act_end);
  return out;
}

UpdateReport TrainingRun::update(const torch::Tensor& next_observations, Clock::time_point& mark) {
  UpdateReport rep;
  const Clock::time_point update_start = Clock::now();
  loop_.other_s += seconds(update_start - mark);
  rep.ppo = trainer_.update(next_observations);
  rep.update = ++updates_;
  const Clock::time_point now = Clock::now();
  loop_.update_s += seconds(now - update_start);
  mark = now;
  progress(rep, now);
  if (rank_ == 0) {
    log_->writeUpdate(rep);  // before the checkpoint, which must never be ahead of its log
    // The final checkpoint is the node's to write once finished().
    if (seconds(now - last_checkpoint_) >= options_.checkpoint_interval_s) saveCheckpoint();
  }
  const Clock::time_point logged = Clock::now();
  loop_.other_s += seconds(logged - mark);
  mark = logged;
  rep.loop = loop_;
  loop_ = LoopTimes{};
  if (rank_ == 0) log_->writeLoop(rep);
  return rep;
}

void TrainingRun::progress(UpdateReport& rep, Clock::time_point now) {
  rep.steps = steps();
  const double process_s = std::chrono::duration<double>(now - start_).count();
  rep.wall_s = start_wall_s_ + process_s;
  updated_wall_s_ = rep.wall_s;
  updated_at_ = std::filesystem::file_time_type::clock::now();
  rep.steps_per_s = (rep.steps - start_steps_) / std::max(process_s, 1e-9);
  rep.eta_s = std::max<int64_t>(0, options_.total_steps - rep.steps) / std::max(rep.steps_per_s, 1e-9);
  const int64_t finished = episodes_seen_.takeFinished();
  if (collective_) {
    // The episodes of every rank: their count, and the means over each rank's recent window.
    double totals[4] = {static_cast<double>(finished), 0.0, 0.0, static_cast<double>(episodes_seen_.recent().size())};
    for (const auto& [length, ret] : episodes_seen_.recent()) {
      totals[1] += static_cast<double>(length);
      totals[2] += ret;
    }
    std::vector<torch::Tensor> t{torch::tensor({totals[0], totals[1], totals[2], totals[3]}, torch::kFloat64)};
    collective_->allReduceSum(t);
    for (int k = 0; k < 4; ++k) totals[k] = t[0][k].item<double>();
    episodes_ += static_cast<int64_t>(std::llround(totals[0]));
    if (totals[3] > 0) {
      rep.mean_length = totals[1] / totals[3];
      rep.mean_return = totals[2] / totals[3];
    }
  } else {
    episodes_ += finished;
    std::tie(rep.mean_length, rep.mean_return) = episodes_seen_.recentMeans();
  }
  rep.episodes = episodes_;
  updated_recent_ = episodes_seen_.recent();
}

void TrainingRun::saveCheckpoint() {
  if (rank_ != 0) return;
  CheckpointInfo info{trainer_.net()->architecture(), options_.image_height, options_.image_width, options_.variant,
                      updatedSteps()};
  info.game = options_.game;
  info.role = options_.role;
  info.wall_s = updated_wall_s_;  // the log's row of that update has the same
  info.episodes = episodes_;
  for (const auto& [length, ret] : updated_recent_) {  // the window of the log's last row, as its counts
    info.recent_lengths.push_back(length);
    info.recent_returns.push_back(ret);
  }
  hideseek_hider::saveCheckpoint(checkpointPath(), trainer_.net(), info, &trainer_.optimizer());
  // Dated at the update it holds, not when it was written (a stop comes later; a pause can fall in
  // between): the sweep drops the pauses that ended after a run's checkpoint, since a run resumed
  // from it holds none of them.
  std::error_code ignored;  // an undated file still holds the right state
  if (updated_at_ != std::filesystem::file_time_type{})
    std::filesystem::last_write_time(checkpointPath(), updated_at_, ignored);
  last_checkpoint_ = Clock::now();
  checkpoint_steps_ = info.steps;
}

bool TrainingRun::saveCheckpointOnStop() {
  if (rank_ != 0 || updatedSteps() == checkpoint_steps_) return false;
  saveCheckpoint();
  return true;
}

}  // namespace hideseek_hider
