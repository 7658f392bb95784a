#include "hideseek_hider/learner.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "hideseek_game/game_selection.h"
#include "hideseek_game/params.h"
#include "hideseek_hider/checkpoint.h"

namespace hideseek_hider {

namespace {

torch::Device deviceFrom(const std::string& name, const std::string& param) {
  if (name == "cpu") return torch::kCPU;
  if (name == "cuda") {
    if (!torch::cuda::is_available()) {
      throw std::runtime_error("parameter " + param + " is 'cuda' but the linked libtorch has no usable CUDA device");
    }
    return torch::kCUDA;
  }
  throw std::runtime_error("parameter " + param + " must be 'cpu' or 'cuda', got '" + name + "'");
}

}  // namespace

void loadLearnerParams(const ros::NodeHandle& pnh, const HiderDefaults& d, LearnerOptions& o, bool network_used) {
  using hideseek_game::readString;
  o.threads = hideseek_game::readInt(pnh, "threads", d.threads, 1, 64);
  o.precision = parsePrecision(readString(pnh, "precision", d.precision), pnh.resolveName("precision"));
  o.memory_format =
      parseMemoryFormat(readString(pnh, "memory_format", d.memory_format), pnh.resolveName("memory_format"));
  o.memoryless = hideseek_game::readBool(pnh, "memoryless", d.memoryless);
  if (!network_used) return;
  if (o.memoryless && o.mode != LearnerMode::kPolicy) {
    throw std::invalid_argument("parameter " + pnh.resolveName("memoryless") + " is true, but the " + o.role +
                                " is in train mode: memoryless applies to a GRU policy only");
  }
  o.device = deviceFrom(readString(pnh, "device", d.device), pnh.resolveName("device"));
  o.greedy = hideseek_game::readBool(pnh, "greedy", d.greedy);
  if (o.mode == LearnerMode::kPolicy) return;
  TrainingOptions& t = o.training;
  t.role = o.role;
  t.actions = o.actions;
  t.variant = o.variant.name;
  t.game = o.variant.game.name;
  t.image_height = o.variant.game.camera.height;
  t.image_width = o.variant.game.camera.width;
  t.output_dir = hideseek_game::requireString(pnh, "output_dir", "a folder, in train mode");
  // A double: launch files write large step counts as 2e6.
  t.total_steps = static_cast<int64_t>(hideseek_game::readDouble(pnh, "total_steps", d.total_steps, 1.0, 1e12));
  t.checkpoint_interval_s = hideseek_game::readDouble(pnh, "checkpoint_interval", d.checkpoint_interval_s, 1e-3, 1e6);
  o.ppo = loadPpoOptions(hideseek_game::requireString(pnh, "ppo_config", "a file path, in train mode"));
  o.num_arenas =
      hideseek_game::readInt(pnh, "num_arenas", hideseek_game::kWatchingArenas, 1, hideseek_game::kMaxArenas);
  o.seed = hideseek_game::readInt(pnh, "seed", 0, 0, hideseek_game::kMaxSeed);
  RendezvousOptions& r = o.rendezvous;
  r.world_size = hideseek_game::readInt(pnh, "world_size", 1, 1, 4096);
  r.rank = hideseek_game::readInt(pnh, "rank", 0, 0, 4095);
  if (r.rank >= r.world_size) {
    throw std::invalid_argument("parameter " + pnh.resolveName("rank") + " is " + std::to_string(r.rank) +
                                ", not below " + pnh.resolveName("world_size") + " (" + std::to_string(r.world_size) +
                                ")");
  }
  r.address = readString(pnh, "rendezvous", r.address);
  if (r.world_size > 1) parseHostPort(r.address, "parameter " + pnh.resolveName("rendezvous"));
  r.timeout_s = hideseek_game::readDouble(pnh, "rendezvous_timeout", r.timeout_s, 1.0, 86400.0);
  r.interface_host = readString(pnh, "rendezvous_interface", "");
}

Learner::Learner(const LearnerOptions& o)
    : role_(o.role), image_bytes_(static_cast<size_t>(o.variant.game.camera.height) * o.variant.game.camera.width * 3) {
  // Measured on the 2-core reference machine: 2 intra-op threads train 1.5x faster than 1.
  torch::set_num_threads(o.threads);
  if (o.mode == LearnerMode::kTrain) {
    startTraining(o);
    return;
  }
  const int height = o.variant.game.camera.height, width = o.variant.game.camera.width;
  const CpuBf16Support cpu = detectCpuBf16();
  const PrecisionChoice precision = choosePrecision(o.precision, o.device, cpu);
  CheckpointInfo info;
  HiderNet net = loadCheckpoint(o.policy, height, width, &info, o.network, o.role, o.actions);
  net->setPrecision(precision.precision);
  const MemoryFormatChoice layout = chooseMemoryFormat(o.memory_format, precision.precision, cpu);
  net->setMemoryFormat(layout.format);
  const uint32_t salt =
      o.role == "seeker" ? hideseek_game::kSaltSampledSeekerPolicy : hideseek_game::kSaltSampledPolicy;
  policy_ = std::make_unique<NetworkHiderPolicy>(net, o.device, o.greedy, salt);
  try {
    policy_->setMemoryless(o.memoryless);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("parameter " + ros::NodeHandle("~").resolveName("memoryless") + " is true for " +
                                o.policy + ": " + e.what());
  }
  ROS_INFO("%s: policy %s (variant '%s', game %s, network %s, %ld training steps), %s, on %s in %s, %s%s",
           role_.c_str(), o.policy.c_str(), info.variant.c_str(), info.game.c_str(), networkName(info.network),
           static_cast<long>(info.steps), o.greedy ? "greedy (its most likely action)" : "sampled",
           o.device.str().c_str(), precision.reason.c_str(), layout.reason.c_str(),
           o.memoryless ? ", memoryless (the GRU state zeroed at every step)" : "");
  if (info.game != o.variant.game.name) {
    ROS_WARN("%s: %s was trained on game %s and plays game %s here (an evaluation across games)", role_.c_str(),
             o.policy.c_str(), info.game.c_str(), o.variant.game.name.c_str());
  }
}

void Learner::startTraining(const LearnerOptions& options) {
  const char* who = role_.c_str();
  const CpuBf16Support cpu = detectCpuBf16();
  const PrecisionChoice precision = choosePrecision(options.precision, options.device, cpu);
  TrainingOptions o = options.training;
  o.precision = precision.precision;
  const MemoryFormatChoice layout = chooseMemoryFormat(options.memory_format, o.precision, cpu);
  o.memory_format = layout.format;
  // A resumed run restores its own generator state.
  torch::manual_seed(static_cast<uint64_t>(options.seed));
  if (options.rendezvous.world_size > 1) {
    RendezvousOptions r = options.rendezvous;
    r.fingerprint = trainingFingerprint(o, options.ppo, options.num_arenas, options.network, options.seed, r.rank);
    ROS_INFO("%s: rank %d of %d: joining the rendezvous at %s (waits up to %.0f s for the other ranks)", who, r.rank,
             r.world_size, r.address.c_str(), r.timeout_s);
    collective_ = joinRanks(r);
    ROS_INFO("%s: rank %d of %d: every rank joined; gradients are averaged over Gloo", who, r.rank, r.world_size);
  }
  try {
    // auto: a run resumed from a checkpoint keeps its network (rank 0's checkpoint's, across ranks);
    // a new run is feed-forward.
    o.network = trainingNetwork(options.network, o.output_dir, collective_.get());
    training_ = std::make_unique<TrainingRun>(o, options.ppo, options.num_arenas, options.device, collective_.get());
  } catch (const std::exception& e) {
    // The other ranks wait in the same collective calls: they stop naming this reason instead of
    // waiting out the timeout.
    if (collective_) collective_->abort(e.what());
    throw;
  }
  ROS_INFO("%s: training %s PPO, network %s, on %s in %s, %s; BLAS: %s", who, o.variant.c_str(), networkName(o.network),
           options.device.str().c_str(), precision.reason.c_str(), layout.reason.c_str(), blasDescription().c_str());
  if (training_->totalSteps() != o.total_steps) {
    ROS_INFO(
        "%s: %ld steps asked, training %ld: whole rollouts of %d arenas x %d steps, so that every sample "
        "collected is trained on",
        who, static_cast<long>(o.total_steps), static_cast<long>(training_->totalSteps()), options.num_arenas,
        options.ppo.rollout_steps);
  }
  ROS_INFO("%s: %s at step %ld of %ld, into %s", who, training_->resumed() ? "resumed" : "started",
           static_cast<long>(training_->steps()), static_cast<long>(training_->totalSteps()), o.output_dir.c_str());
  if (training_->droppedLogRows() > 0) {
    ROS_INFO("%s: dropped %d log rows of updates made after the checkpoint (lost with the stopped run)", who,
             training_->droppedLogRows());
  }
}

std::vector<uint8_t> Learner::act(const LearnerBatch& b) {
  if (training_) return trainStep(b);
  std::vector<ArenaObservation> batch(b.n);
  for (size_t i = 0; i < b.n; ++i) batch[i] = {b.images + i * image_bytes_, (*b.seed)[i], (*b.step)[i], {}, {}};
  return policy_->act(batch);
}

std::vector<uint8_t> Learner::trainStep(const LearnerBatch& b) {
  const char* who = role_.c_str();
  // The learner's buffers are shaped for its arena count: another count would be read past, and
  // lockstep would wait for ever on a batch ignored, so this configuration error stops the node.
  if (b.n != static_cast<size_t>(training_->numArenas())) {
    ROS_FATAL("%s: train mode learns from %d arenas (parameter %s), the world sends %zu: set the same num_arenas", who,
              training_->numArenas(), ros::NodeHandle("~").resolveName("num_arenas").c_str(), b.n);
    exit_code_ = 1;
    return {};
  }
  std::optional<UpdateReport> report;
  std::vector<uint8_t> actions;
  try {
    actions = training_->step(b.images, *b.rewards, *b.done, &report);
  } catch (const std::exception& e) {
    // A rank that stopped (CollectiveError names it), or this rank's own failure, which the
    // others are told of so that they stop at once, naming this rank.
    if (collective_ && !dynamic_cast<const CollectiveError*>(&e)) collective_->abort(e.what());
    ROS_FATAL("%s: training stopped: %s", who, e.what());
    exit_code_ = 1;
    return {};
  }
  if (report) {
    const LoopTimes& loop = report->loop;
    const double total = std::max(loop.total(), 1e-9);
    // Until an episode ends (in this run, or in the window a checkpoint kept) there is no length
    // or return to show (the log writes 0 there); every episode lasts a step at least.
    char episodes[96];
    if (report->mean_length > 0.0) {
      std::snprintf(episodes, sizeof episodes, "%ld episodes, length %.1f, return %.3f",
                    static_cast<long>(report->episodes), report->mean_length, report->mean_return);
    } else {
      std::snprintf(episodes, sizeof episodes, "no episode ended yet");
    }
    ROS_INFO(
        "train: %ld/%ld steps, %.0f steps/s, ETA %s, %s, entropy %.3f; "
        "time: update %.0f %%, inference %.0f %%, waiting for the world %.0f %%, other %.0f %%",
        static_cast<long>(report->steps), static_cast<long>(training_->totalSteps()), report->steps_per_s,
        formatDuration(report->eta_s).c_str(), episodes, report->ppo.entropy, 100 * loop.update_s / total,
        100 * loop.inference_s / total, 100 * loop.wait_s / total, 100 * loop.other_s / total);
  }
  if (!training_->finished()) return actions;
  try {
    training_->saveCheckpoint();
  } catch (const std::exception& e) {
    ROS_FATAL("%s: training finished, but its final checkpoint was not written: %s", who, e.what());
    exit_code_ = 1;
    return {};
  }
  if (training_->rank() != 0) {
    ROS_INFO("train: done, %ld steps (rank %d: rank 0 writes the checkpoint and the log)",
             static_cast<long>(training_->steps()), training_->rank());
  } else {
    ROS_INFO("train: done, %ld steps; checkpoint %s, log %s", static_cast<long>(training_->steps()),
             training_->checkpointPath().c_str(), training_->logPath().c_str());
  }
  return {};
}

void Learner::stop() {
  if (!training_ || exit_code_ != 0 || training_->finished()) return;
  if (training_->rank() != 0) {
    ROS_INFO("train: stopped at %ld steps (rank %d: rank 0 writes the checkpoint)",
             static_cast<long>(training_->updatedSteps()), training_->rank());
    return;
  }
  try {
    if (training_->saveCheckpointOnStop()) {
      ROS_INFO(
          "train: stopped at %ld of %ld steps (its last update); checkpoint %s: the same command resumes from there",
          static_cast<long>(training_->updatedSteps()), static_cast<long>(training_->totalSteps()),
          training_->checkpointPath().c_str());
    }
  } catch (const std::exception& e) {
    ROS_ERROR("%s: stopped, but its checkpoint was not written: %s", role_.c_str(), e.what());
    exit_code_ = 1;
  }
}

}  // namespace hideseek_hider
