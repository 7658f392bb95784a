// The hider's network (SPEC section 5): a convolutional encoder to 512 mid-level features,
// an actor head and a critic head.
#pragma once

#include <torch/torch.h>

#include <string>

#include "hideseek_hider/precision.h"

namespace hideseek_hider {

// Named outputs: index-free reading of what the network computed.
struct HiderOutput {
  torch::Tensor logits;    // [B, 5]
  torch::Tensor value;     // [B]
  torch::Tensor features;  // [B, 512] mid-level features, what the probes read
};

constexpr int kFeatures = 512;
constexpr int kActions = 5;
// Written into every checkpoint; a checkpoint of another architecture is refused.
constexpr char kArchitecture[] =
    "hideseek_hider/v1: conv8x8s4x32-conv4x4s2x64-conv3x3s1x64-fc512 | actor fc512-5 | critic fc512-1 | leaky_relu";

class HiderNetImpl : public torch::nn::Module {
 public:
  HiderNetImpl(int image_height, int image_width);

  // images: [B, H, W, 3] uint8 (as the world sends them), scaled to [0, 1] here. Runs in the
  // network's precision; the outputs are always fp32.
  HiderOutput forward(const torch::Tensor& images);

  // bf16 autocasts every forward pass (and so its backward); the parameters stay fp32.
  void setPrecision(Precision precision) { precision_ = precision; }
  Precision precision() const { return precision_; }

  int imageHeight() const { return image_height_; }
  int imageWidth() const { return image_width_; }

 private:
  int image_height_;
  int image_width_;
  Precision precision_ = Precision::kFp32;
  torch::nn::Conv2d conv1_{nullptr}, conv2_{nullptr}, conv3_{nullptr};
  torch::nn::Linear features_{nullptr}, actor_hidden_{nullptr}, actor_out_{nullptr}, critic_hidden_{nullptr},
      critic_out_{nullptr};
};
TORCH_MODULE(HiderNet);

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
};

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
// Builds the network a checkpoint describes and loads its weights. Throws std::runtime_error
// saying what does not match (architecture, image size, tensor shapes) or that the file is
// truncated or corrupt; never returns a half-loaded network.
HiderNet loadCheckpoint(const std::string& path, int expected_height, int expected_width, CheckpointInfo* info = nullptr);

}  // namespace hideseek_hider
