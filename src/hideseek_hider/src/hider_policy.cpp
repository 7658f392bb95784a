#include "hideseek_hider/hider_policy.h"

#include <cstring>
#include <stdexcept>

#include "hideseek_game/hash_uniform.h"

namespace hideseek_hider {

using hideseek_game::hashUniform;

std::vector<uint8_t> RandomHiderPolicy::act(const std::vector<ArenaObservation>& batch) {
  std::vector<uint8_t> actions(batch.size());
  for (size_t i = 0; i < batch.size(); ++i) {
    actions[i] = hideseek_game::hashAction(batch[i].seed, batch[i].step, hideseek_game::kSaltRandomHider);
  }
  return actions;
}

std::optional<EvaderKind> scriptedPolicy(const std::string& policy) {
  const std::string prefix = "scripted/";
  if (policy.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  const auto kind = evaderKind(policy.substr(prefix.size()));
  if (!kind) {
    throw std::invalid_argument("'" + policy +
                                "' names no scripted evader: scripted/random, scripted/backpedal, scripted/flee, "
                                "scripted/hide or scripted/lap");
  }
  return kind;
}

ScriptedHiderPolicy::ScriptedHiderPolicy(EvaderKind kind, const hideseek_game::VariantConfig& variant)
    : kind_(kind),
      variant_(variant),
      layout_source_(variant.game,
                     std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(variant.map_file))) {}

std::vector<uint8_t> ScriptedHiderPolicy::act(const std::vector<ArenaObservation>& batch) {
  if (evaders_.size() != batch.size()) {
    evaders_.clear();
    for (size_t i = 0; i < batch.size(); ++i) evaders_.emplace_back(kind_, variant_.game);
    seeds_.assign(batch.size(), std::nullopt);
  }
  std::vector<uint8_t> actions(batch.size());
  for (size_t i = 0; i < batch.size(); ++i) {
    const ArenaObservation& o = batch[i];
    if (seeds_[i] != o.seed || o.step == 0) {
      layout_source_.reset(o.seed);
      evaders_[i].reset(layout_source_.layout());
      seeds_[i] = o.seed;
    }
    actions[i] = static_cast<uint8_t>(evaders_[i].act({o.hider, o.seeker, o.seed, o.step}));
  }
  return actions;
}

NetworkHiderPolicy::NetworkHiderPolicy(HiderNet net, torch::Device device, bool greedy, uint32_t salt)
    : net_(std::move(net)), device_(device), greedy_(greedy), salt_(salt) {
  net_->to(device_);
  net_->eval();
}

void NetworkHiderPolicy::setMemoryless(bool memoryless) {
  if (memoryless && !net_->recurrent()) {
    throw std::invalid_argument("memoryless applies to a GRU policy only, and this one is a feed-forward hider");
  }
  memoryless_ = memoryless;
}

std::vector<uint8_t> NetworkHiderPolicy::act(const std::vector<ArenaObservation>& batch) {
  const torch::NoGradGuard no_grad;
  const int64_t n = static_cast<int64_t>(batch.size());
  const int64_t h = net_->imageHeight(), w = net_->imageWidth();
  torch::Tensor images = torch::empty({n, h, w, 3}, torch::kUInt8);
  const size_t bytes = static_cast<size_t>(h * w * 3);
  for (int64_t i = 0; i < n; ++i) std::memcpy(images.data_ptr<uint8_t>() + i * bytes, batch[i].image, bytes);
  torch::Tensor logits;
  if (net_->recurrent()) {
    if (!hidden_.defined() || hidden_.size(0) != n) {
      hidden_ = net_->initialHidden(n);
      seeds_.assign(n, 0);
    }
    torch::Tensor starts = torch::zeros({1, n});
    for (int64_t i = 0; i < n; ++i) {
      if (memoryless_ || batch[i].step == 0 || batch[i].seed != seeds_[i]) starts[0][i] = 1.0;
      seeds_[i] = batch[i].seed;
    }
    logits = net_->forwardSequence(images.to(device_).unsqueeze(0), hidden_, starts.to(device_), &hidden_).logits[0];
  } else {
    logits = net_->forward(images.to(device_)).logits;
  }
  const torch::Tensor probs = torch::softmax(logits, 1).to(torch::kCPU).contiguous();
  const float* p = probs.data_ptr<float>();
  const int count = net_->actions();
  std::vector<uint8_t> actions(n);
  for (int64_t i = 0; i < n; ++i) {
    const float* row = p + i * count;
    if (greedy_) {
      actions[i] = static_cast<uint8_t>(std::max_element(row, row + count) - row);
      continue;
    }
    // Inverse-CDF sampling with a reproducible draw.
    const double u = hashUniform(batch[i].seed, batch[i].step, salt_);
    double cumulative = 0.0;
    actions[i] = static_cast<uint8_t>(count - 1);
    for (int a = 0; a < count; ++a) {
      cumulative += row[a];
      if (u < cumulative) {
        actions[i] = static_cast<uint8_t>(a);
        break;
      }
    }
  }
  return actions;
}

}  // namespace hideseek_hider
