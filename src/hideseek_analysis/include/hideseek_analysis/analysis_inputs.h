// Turns a complete StepLog into the arrays the report's statistics read: every step's state,
// the 512 mid-level features of every recorded image through the trained network and through a
// randomly initialised one, the random policy's states over as many steps, and the layouts of
// the episodes whose trajectories the report draws.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hideseek_analysis/step_log.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"
#include "hideseek_hider/hider_net.h"

namespace hideseek_analysis {

struct AnalysisInputsOptions {
  uint32_t random_init_seed = 0;  // torch seed of the randomly initialised network
  int trajectory_episodes = 4;    // complete episodes (smallest seeds) whose layouts are written
  int batch = 256;                // images per forward pass
  int pixel_tolerance = 0;        // GRU policies: see replayMemory
};

struct AnalysisInputsSummary {
  size_t steps = 0;         // arena steps of the rollout
  size_t episodes = 0;      // episodes it touches (complete or not)
  int64_t images = 0;       // probed images
  size_t random_steps = 0;  // steps of the random policy
  size_t random_episodes = 0;
  std::vector<uint32_t> trajectory_seeds;
  // Recurrent (GRU) policies only: the recorded images compared with their re-rendering (see
  // replayMemory) and the largest difference of a pixel channel found.
  int64_t memory_images_compared = 0;
  int max_pixel_difference = 0;
};

// The GRU states of a recurrent rollout, one [images, 512] array per network: row k is the state
// after the step whose recorded image is image k of the log (the state the heads acted on).
struct MemoryReplay {
  std::vector<torch::Tensor> memory;
  int64_t images_compared = 0;
  int max_pixel_difference = 0;
};

// A GRU's state depends on every image of its episode, and the log keeps only some images. So
// the hider's camera image of every logged step is rendered again from the recorded poses, in the
// episode's layout rebuilt from its seed (as the world renders it: arena i in view i), and each
// network runs over the arenas' steps in order, its state zeroed at each episode start, as the
// hider node runs it. Every recorded image is compared with its re-rendering. Throws
// std::runtime_error when one differs by more than `tolerance` (0-255) in a pixel channel (a
// recording of another variant or map), or when an arena's first logged step does not start an
// episode (the state before it is unknown); std::invalid_argument for a feed-forward network.
MemoryReplay replayMemory(const StepLog& log, const std::vector<hideseek_hider::HiderNet*>& nets,
                          const hideseek_game::VariantConfig& variant,
                          std::shared_ptr<const hideseek_game::MapSpec> map, int tolerance = 0, int render_threads = 2);

// The mid-level features of `count` RGB8 images ([count, 512], fp32, in batches, no gradients);
// for a recurrent network, the features its GRU reads (they do not depend on its state).
torch::Tensor extractFeatures(hideseek_hider::HiderNet& net, const uint8_t* images, int64_t count, int height,
                              int width, int batch = 256);

// Writes a [rows, cols] float32 array as a NumPy .npy file (format 1.0, C order).
void writeNpy(const std::string& path, const float* data, int64_t rows, int64_t cols);

// Writes into `dir`: steps_trained.csv and steps_random.csv (one row per step, sorted by episode
// then step; the random policy plays the recording's seeds in order, from its smallest, until it
// has played at least as many steps), features.csv with features_trained.npy and features_random.npy (one row per
// recorded image), and layouts.csv (the obstacles of the trajectory episodes). For a recurrent
// (GRU) policy also memory_trained.npy and memory_random.npy: the GRU states of the same rows
// (replayMemory), of the trained network and of the random-init one. Throws
// std::runtime_error naming what does not fit (image size, an unwritable file).
AnalysisInputsSummary writeAnalysisInputs(const StepLog& log, hideseek_hider::HiderNet& trained,
                                          const hideseek_game::VariantConfig& variant,
                                          std::shared_ptr<const hideseek_game::MapSpec> map,
                                          const AnalysisInputsOptions& options, const std::string& dir);

}  // namespace hideseek_analysis
