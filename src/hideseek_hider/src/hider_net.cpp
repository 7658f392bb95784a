#include "hideseek_hider/hider_net.h"

#include <stdexcept>

#include "hideseek_hider/gru_sequence.h"

namespace hideseek_hider {

namespace {

int convOut(int size, int kernel, int stride) { return (size - kernel) / stride + 1; }

torch::Tensor leaky(const torch::Tensor& x) { return torch::leaky_relu(x, 0.01); }

}  // namespace

const char* networkName(NetworkKind kind) { return kind == NetworkKind::kGru ? "gru" : "ff"; }

NetworkKind parseNetwork(const std::string& name, const std::string& what) {
  if (name == "ff") return NetworkKind::kFeedForward;
  if (name == "gru") return NetworkKind::kGru;
  throw std::invalid_argument(what + " must be ff or gru, got '" + name + "'");
}

std::string architectureName(NetworkKind kind, int actions) {
  std::string name = kind == NetworkKind::kGru ? kArchitectureGru : kArchitecture;
  if (actions != kActions) {
    const std::string five = "actor fc512-" + std::to_string(kActions) + " ";
    name.replace(name.find(five), five.size(), "actor fc512-" + std::to_string(actions) + " ");
  }
  return name;
}

std::optional<ArchitectureParts> parseArchitecture(const std::string& architecture) {
  for (NetworkKind kind : {NetworkKind::kFeedForward, NetworkKind::kGru}) {
    for (int actions = 2; actions <= kMaxActions; ++actions) {
      if (architectureName(kind, actions) == architecture) return ArchitectureParts{kind, actions};
    }
  }
  return std::nullopt;
}

HiderNetImpl::HiderNetImpl(int image_height, int image_width, NetworkKind network, int actions)
    : image_height_(image_height), image_width_(image_width), network_(network), actions_(actions) {
  if (actions < 2 || actions > kMaxActions) {
    throw std::invalid_argument("hider network: " + std::to_string(actions) + " actions (2 to " +
                                std::to_string(kMaxActions) + ")");
  }
  const int h = convOut(convOut(convOut(image_height, 8, 4), 4, 2), 3, 1);
  const int w = convOut(convOut(convOut(image_width, 8, 4), 4, 2), 3, 1);
  if (h < 1 || w < 1) {
    throw std::invalid_argument("hider network: images of " + std::to_string(image_height) + "x" +
                                std::to_string(image_width) + " are too small for the encoder (at least 36x36)");
  }
  conv1_ = register_module("conv1", torch::nn::Conv2d(torch::nn::Conv2dOptions(3, 32, 8).stride(4)));
  conv2_ = register_module("conv2", torch::nn::Conv2d(torch::nn::Conv2dOptions(32, 64, 4).stride(2)));
  conv3_ = register_module("conv3", torch::nn::Conv2d(torch::nn::Conv2dOptions(64, 64, 3).stride(1)));
  features_ = register_module("features", torch::nn::Linear(64 * h * w, kFeatures));
  if (recurrent()) gru_ = register_module("gru", torch::nn::GRUCell(torch::nn::GRUCellOptions(kFeatures, kHidden)));
  const int head_in = recurrent() ? kHidden : kFeatures;
  actor_hidden_ = register_module("actor_hidden", torch::nn::Linear(head_in, 512));
  actor_out_ = register_module("actor_out", torch::nn::Linear(512, actions_));
  critic_hidden_ = register_module("critic_hidden", torch::nn::Linear(head_in, 512));
  critic_out_ = register_module("critic_out", torch::nn::Linear(512, 1));
}

torch::Tensor HiderNetImpl::encode(const torch::Tensor& images) {
  TORCH_CHECK(
      images.dim() == 4 && images.size(1) == image_height_ && images.size(2) == image_width_ && images.size(3) == 3,
      "hider network expects [B, ", image_height_, ", ", image_width_, ", 3] images, got ", images.sizes());
  const AutocastScope autocast(precision_, conv1_->weight.device());
  // [B, H, W, 3] bytes viewed as [B, 3, H, W]: channels-last strides, which the conversion keeps
  // and oneDNN's convolutions follow. nchw copies them into NCHW order (chooseMemoryFormat).
  torch::Tensor x = images.permute({0, 3, 1, 2}).to(torch::kFloat32).div(255.0);
  if (memory_format_ == MemoryFormat::kNchw) x = x.contiguous();
  x = leaky(conv1_->forward(x));
  x = leaky(conv2_->forward(x));
  x = leaky(conv3_->forward(x));
  return leaky(features_->forward(x.flatten(1)));
}

void HiderNetImpl::heads(const torch::Tensor& x, HiderOutput& out) {
  torch::Tensor actor, critic;
  {
    const AutocastScope autocast(precision_, conv1_->weight.device());
    actor = leaky(actor_hidden_->forward(x));
    critic = leaky(critic_hidden_->forward(x));
  }
  // The two output layers run in fp32 (a negligible share of the work): a bf16 value would be
  // rounded to about 0.004 near 1, coarser than the 0.001 per-step reward GAE works with.
  // Losses, softmax and probes then work in fp32 whatever precision the layers ran in.
  out.logits = actor_out_->forward(actor.to(torch::kFloat32));
  out.value = critic_out_->forward(critic.to(torch::kFloat32)).squeeze(1);
}

HiderOutput HiderNetImpl::forward(const torch::Tensor& images) {
  TORCH_CHECK(!recurrent(), "a GRU hider network needs its state: call forwardSequence");
  HiderOutput out;
  out.features = encode(images).to(torch::kFloat32);
  heads(out.features, out);
  return out;
}

HiderOutput HiderNetImpl::forwardSequence(const torch::Tensor& images, const torch::Tensor& hidden,
                                          const torch::Tensor& starts, torch::Tensor* hidden_out) {
  TORCH_CHECK(images.dim() == 5, "forwardSequence expects [T, B, H, W, 3] images, got ", images.sizes());
  const int64_t steps = images.size(0), batch = images.size(1);
  TORCH_CHECK(starts.dim() == 2 && starts.size(0) == steps && starts.size(1) == batch, "starts must be [", steps, ", ",
              batch, "], got ", starts.sizes());
  HiderOutput out;
  const torch::Tensor features = encode(images.flatten(0, 1)).to(torch::kFloat32);
  out.features = features.view({steps, batch, kFeatures});
  torch::Tensor x = features;
  if (recurrent()) {
    TORCH_CHECK(hidden.dim() == 2 && hidden.size(0) == batch && hidden.size(1) == kHidden, "hidden must be [", batch,
                ", ", kHidden, "], got ", hidden.sizes());
    // The input side of every step's gates in one matrix product: only the recurrent product is
    // sequential (gruSequence).
    const torch::Tensor input_gates =
        torch::nn::functional::linear(out.features, gru_->weight_ih, gru_->bias_ih);  // [T, B, 1536]
    out.memory = gruSequence(input_gates, 1.0 - starts.to(torch::kFloat32), hidden.to(torch::kFloat32), gru_->weight_hh,
                             gru_->bias_hh);
    x = out.memory.flatten(0, 1);
    if (hidden_out) *hidden_out = out.memory[steps - 1];
  } else if (hidden_out) {
    *hidden_out = hidden;
  }
  heads(x, out);
  out.logits = out.logits.view({steps, batch, actions_});
  out.value = out.value.view({steps, batch});
  return out;
}

HiderNetImpl::Flops HiderNetImpl::forwardFlops() const {
  const int h1 = convOut(image_height_, 8, 4), w1 = convOut(image_width_, 8, 4);
  const int h2 = convOut(h1, 4, 2), w2 = convOut(w1, 4, 2);
  const int h3 = convOut(h2, 3, 1), w3 = convOut(w2, 3, 1);
  // 2 x outputs x inputs per output, layer by layer.
  auto conv = [](int h, int w, int out, int kernel, int in) { return 2.0 * h * w * out * kernel * kernel * in; };
  auto fc = [](int in, int out) { return 2.0 * in * out; };
  Flops f;
  f.first_conv = conv(h1, w1, 32, 8, 3);
  f.total = f.first_conv + conv(h2, w2, 64, 4, 32) + conv(h3, w3, 64, 3, 64) + fc(64 * h3 * w3, kFeatures);
  if (recurrent()) f.total += fc(kFeatures, 3 * kHidden) + fc(kHidden, 3 * kHidden);
  const int head_in = recurrent() ? kHidden : kFeatures;
  f.total += 2 * fc(head_in, 512) + fc(512, actions_) + fc(512, 1);
  return f;
}

torch::Tensor HiderNetImpl::initialHidden(int64_t batch) const {
  return torch::zeros({batch, kHidden}, torch::TensorOptions().device(conv1_->weight.device()).dtype(torch::kFloat32));
}

}  // namespace hideseek_hider
