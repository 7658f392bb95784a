// Checkpoints, all their reading and writing: the network's weights with what the file says about
// itself (architecture, image size, variant, game, training progress), and for training the
// optimiser's state and the random generator's. The zip layout is checked before libtorch reads a
// byte (checkpoint_archive.h).
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_hider/hider_net.h"

namespace hideseek_hider {

// What a checkpoint says about itself.
struct CheckpointInfo {
  std::string architecture;
  int image_height = 0;
  int image_width = 0;
  std::string variant;
  int64_t steps = 0;  // environment steps trained
  // Training progress, so that a resumed run's log continues where the checkpoint left it.
  double wall_s = 0.0;   // wall seconds of training up to this checkpoint, over all resumes
  int64_t episodes = 0;  // episodes finished up to this checkpoint
  // Length and return of the last finished episodes (the log's mean_length and mean_return), so a
  // resumed log does not restart its average from the first, necessarily short, episodes to end.
  std::vector<int64_t> recent_lengths{};
  std::vector<double> recent_returns{};
  NetworkKind network = NetworkKind::kFeedForward;  // from the architecture
  int actions = kActions;                           // from the architecture
  // The game it trained on (game.yaml's `game`); a checkpoint written before the field existed is
  // game v2's, the only game then trained.
  std::string game = "v2";
  // Whose policy it is: hider, or seeker (a learning seeker's, issue #68). A checkpoint written
  // before the field existed is a hider's, the only role then trained.
  std::string role = "hider";
};

// Writes `data` to path.tmp, syncs it, then renames it over `path`. On any error (a full disk:
// ENOSPC) it removes path.tmp and throws std::runtime_error naming the file and the cause; the
// previous file at `path` is left untouched.
void writeFileAtomically(const std::string& path, const std::string& data);

// Writes the network and its description to `path` atomically (temporary file, then rename).
// With an optimiser it also writes the optimiser state and the CPU random generator's state,
// so that training resumes where it stopped.
void saveCheckpoint(const std::string& path, HiderNet& net, const CheckpointInfo& info,
                    torch::optim::Optimizer* optimizer = nullptr);
// Restores what saveCheckpoint wrote for training into `optimizer` and the CPU generator.
// Throws std::runtime_error naming the file when the checkpoint holds no training state.
void loadTrainingState(const std::string& path, torch::optim::Optimizer& optimizer);
// Reads only the description; throws std::runtime_error naming the file when unreadable.
CheckpointInfo readCheckpointInfo(const std::string& path);
// Builds the network a checkpoint describes (feed-forward or GRU) and loads its weights. Throws
// std::runtime_error saying what does not match (the role asked for: every hider node and tool asks
// for a hider's; architecture, the network asked for, the action count, image size, tensor shapes)
// or that the file is truncated or corrupt; never returns a half-loaded network.
HiderNet loadCheckpoint(const std::string& path, int expected_height, int expected_width,
                        CheckpointInfo* info = nullptr, std::optional<NetworkKind> expected_network = std::nullopt,
                        const std::string& expected_role = "hider", int expected_actions = kActions);

}  // namespace hideseek_hider
