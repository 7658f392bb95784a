// Turns a complete StepLog into the arrays the report's statistics read: every step's state,
// the 512 mid-level features of every recorded image through the trained network and through a
// randomly initialised one, the random policy's states over as many steps, and the layouts of
// the episodes whose trajectories the report draws.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <torch/torch.h>

#include "hideseek_analysis/step_log.h"
#include "hideseek_hider/hider_net.h"
#include "hideseek_world/game_options.h"
#include "hideseek_world/map.h"

namespace hideseek_analysis {

struct AnalysisInputsOptions {
  uint32_t random_init_seed = 0;         // torch seed of the randomly initialised network
  int trajectory_episodes = 4;           // complete episodes (smallest seeds) whose layouts are written
  int batch = 256;                       // images per forward pass
};

struct AnalysisInputsSummary {
  size_t steps = 0;          // arena steps of the rollout
  size_t episodes = 0;       // episodes it touches (complete or not)
  int64_t images = 0;        // probed images
  size_t random_steps = 0;   // steps of the random policy
  size_t random_episodes = 0;
  std::vector<uint32_t> trajectory_seeds;
};

// The mid-level features of `count` RGB8 images ([count, 512], fp32, in batches, no gradients).
torch::Tensor extractFeatures(hideseek_hider::HiderNet& net, const uint8_t* images, int64_t count, int height,
                              int width, int batch = 256);

// Writes a [rows, cols] float32 array as a NumPy .npy file (format 1.0, C order).
void writeNpy(const std::string& path, const float* data, int64_t rows, int64_t cols);

// Writes into `dir`: steps_trained.csv and steps_random.csv (one row per step, sorted by episode
// then step; the random policy plays the recording's seeds in order, from its smallest, until it
// has played at least as many steps), features.csv with features_trained.npy and features_random.npy (one row per
// recorded image), and layouts.csv (the obstacles of the trajectory episodes). Throws
// std::runtime_error naming what does not fit (image size, an unwritable file).
AnalysisInputsSummary writeAnalysisInputs(const StepLog& log, hideseek_hider::HiderNet& trained,
                                          const hideseek_world::VariantConfig& variant,
                                          std::shared_ptr<const hideseek_world::MapSpec> map,
                                          const AnalysisInputsOptions& options, const std::string& dir);

}  // namespace hideseek_analysis
