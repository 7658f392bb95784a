// The hider's network: a convolutional encoder to 512 mid-level features, an actor head and a
// critic head; optionally (network gru) a GRU between the features and the heads, the hider's
// memory.
#pragma once

#include <torch/torch.h>

#include <optional>
#include <string>
#include <vector>

#include "hideseek_hider/precision.h"

namespace hideseek_hider {

// Named outputs: index-free reading of what the network computed.
// forward() gives [B, ...]; forwardSequence() gives [T, B, ...].
struct HiderOutput {
  torch::Tensor logits;    // [B, actions] (the hider's 5)
  torch::Tensor value;     // [B]
  torch::Tensor features;  // [B, 512] mid-level features, what the probes read
  torch::Tensor memory;    // [B, 512] the GRU's state after this step (network gru only)
};

constexpr int kFeatures = 512;
constexpr int kHidden = 512;     // GRU state size
constexpr int kActions = 5;      // the hider's; a learning seeker of game v3 has 7 (the two that turn while moving)
constexpr int kMaxActions = 16;  // the most actions a network's actor may have (either role)
// Written into every checkpoint; a checkpoint of another architecture is refused. These are the
// five-action networks' names (every hider's); architectureName gives any action count's.
constexpr char kArchitecture[] =
    "hideseek_hider/v1: conv8x8s4x32-conv4x4s2x64-conv3x3s1x64-fc512 | actor fc512-5 | critic fc512-1 | leaky_relu";
constexpr char kArchitectureGru[] =
    "hideseek_hider/v1-gru: conv8x8s4x32-conv4x4s2x64-conv3x3s1x64-fc512 | gru512 | actor fc512-5 | critic fc512-1 | "
    "leaky_relu";

// Feed-forward (the paper's network) or recurrent (a GRU of kHidden units before the heads).
enum class NetworkKind { kFeedForward, kGru };
const char* networkName(NetworkKind kind);  // "ff", "gru"
// The architecture string of a network with `actions` outputs: kArchitecture or kArchitectureGru
// for 5, the same with "fc512-<actions>" in the actor otherwise.
std::string architectureName(NetworkKind kind, int actions);
// What an architecture string describes; nullopt for one this build does not run.
struct ArchitectureParts {
  NetworkKind network = NetworkKind::kFeedForward;
  int actions = kActions;
};
std::optional<ArchitectureParts> parseArchitecture(const std::string& architecture);
// "ff" or "gru"; throws std::invalid_argument naming `what` (a parameter or field) otherwise.
NetworkKind parseNetwork(const std::string& name, const std::string& what);

class HiderNetImpl : public torch::nn::Module {
 public:
  // `actions`: the actor's outputs, the hider's 5 or a learning seeker's (2 to kMaxActions).
  HiderNetImpl(int image_height, int image_width, NetworkKind network = NetworkKind::kFeedForward,
               int actions = kActions);

  // images: [B, H, W, 3] uint8 (as the world sends them), scaled to [0, 1] here. Runs in the
  // network's precision; the outputs are always fp32. Feed-forward networks only: a GRU needs
  // its state (forwardSequence).
  HiderOutput forward(const torch::Tensor& images);

  // Any network, over T steps of B arenas. images: [T, B, H, W, 3] uint8; hidden: [B, 512], the
  // GRU state before step 0 (ignored by a feed-forward network); starts: [T, B], 1 where step t
  // begins an episode, so that the state is zeroed before it. The encoder and heads run batched
  // over all T x B images, the GRU cell step by step. The state after the last step goes to
  // *hidden_out when given. The GRU runs in fp32 whatever the precision.
  HiderOutput forwardSequence(const torch::Tensor& images, const torch::Tensor& hidden, const torch::Tensor& starts,
                              torch::Tensor* hidden_out = nullptr);
  // The state at an episode's start: zeros [batch, 512] on the network's device.
  torch::Tensor initialHidden(int64_t batch) const;

  NetworkKind network() const { return network_; }
  bool recurrent() const { return network_ == NetworkKind::kGru; }
  int actions() const { return actions_; }
  std::string architecture() const { return architectureName(network_, actions_); }

  // bf16 autocasts every forward pass (and so its backward); the parameters stay fp32.
  void setPrecision(Precision precision) { precision_ = precision; }
  Precision precision() const { return precision_; }
  // The encoder's layout (precision.h, chooseMemoryFormat): channels-last by default.
  void setMemoryFormat(MemoryFormat format) { memory_format_ = format; }
  MemoryFormat memoryFormat() const { return memory_format_; }

  int imageHeight() const { return image_height_; }
  int imageWidth() const { return image_width_; }

  // Floating-point operations (a multiply-add counts as 2) of one forward pass over one image,
  // counted from the layers' shapes: the three convolutions, the fully connected layers and, for
  // the GRU, its input and recurrent products. Biases, activations, softmax and the GRU's gate
  // arithmetic are not counted (together well under 1 % of the total).
  struct Flops {
    double total = 0.0;
    double first_conv = 0.0;  // conv1 alone: its input gradient is never computed
  };
  Flops forwardFlops() const;

 private:
  torch::Tensor encode(const torch::Tensor& images);     // [B, H, W, 3] uint8 -> [B, 512] in the precision
  void heads(const torch::Tensor& x, HiderOutput& out);  // [B, 512] -> logits, value (fp32)

  int image_height_;
  int image_width_;
  NetworkKind network_;
  int actions_;
  Precision precision_ = Precision::kFp32;
  MemoryFormat memory_format_ = MemoryFormat::kChannelsLast;
  torch::nn::GRUCell gru_{nullptr};
  torch::nn::Conv2d conv1_{nullptr}, conv2_{nullptr}, conv3_{nullptr};
  torch::nn::Linear features_{nullptr}, actor_hidden_{nullptr}, actor_out_{nullptr}, critic_hidden_{nullptr},
      critic_out_{nullptr};
};
TORCH_MODULE(HiderNet);

}  // namespace hideseek_hider
