// Turns observation batches into actions: uniformly random, or sampled from a trained network.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hideseek_game/arena.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/hash_uniform.h"
#include "hideseek_hider/hider_net.h"
#include "hideseek_hider/scripted_evader.h"

namespace hideseek_hider {

// One arena's observation as the policy needs it: the image and what makes sampling reproducible,
// and the true poses, which only the scripted evaders read.
struct ArenaObservation {
  const uint8_t* image = nullptr;  // H x W x 3, rgb8
  uint32_t seed = 0;               // episode seed
  uint32_t step = 0;
  hideseek_game::AgentState hider;
  hideseek_game::AgentState seeker;
};

class HiderPolicy {
 public:
  virtual ~HiderPolicy() = default;
  virtual std::vector<uint8_t> act(const std::vector<ArenaObservation>& batch) = 0;
};

class RandomHiderPolicy : public HiderPolicy {
 public:
  std::vector<uint8_t> act(const std::vector<ArenaObservation>& batch) override;
};

// A scripted evader for every arena (policy scripted/NAME): a baseline that reads the true state.
// Each episode's layout is drawn again from its seed, as the world draws it.
class ScriptedHiderPolicy : public HiderPolicy {
 public:
  ScriptedHiderPolicy(EvaderKind kind, const hideseek_game::VariantConfig& variant);
  std::vector<uint8_t> act(const std::vector<ArenaObservation>& batch) override;

 private:
  EvaderKind kind_;
  hideseek_game::VariantConfig variant_;
  hideseek_game::Arena layout_source_;  // reset with an episode's seed, it holds that episode's layout
  std::vector<ScriptedEvader> evaders_;
  std::vector<std::optional<uint32_t>> seeds_;  // each arena's episode seed at the last act()
};

// The evader a policy name scripted/NAME asks for, nothing for a name without the prefix; throws
// std::invalid_argument for scripted/ and a name that is no evader.
std::optional<EvaderKind> scriptedPolicy(const std::string& policy);

// Inference from a checkpoint: one batched forward pass per step, no autograd. A GRU network
// carries each arena's state from step to step and starts from zero at an episode's step 0 (a
// new seed at any step, after a reset, also starts afresh).
class NetworkHiderPolicy : public HiderPolicy {
 public:
  // `salt`: the stream of the sampled actions (a learning seeker draws from its own).
  NetworkHiderPolicy(HiderNet net, torch::Device device, bool greedy,
                     uint32_t salt = hideseek_game::kSaltSampledPolicy);
  std::vector<uint8_t> act(const std::vector<ArenaObservation>& batch) override;
  // GRU only: each arena's state after the last act() ([N, 512]); undefined before it.
  const torch::Tensor& hidden() const { return hidden_; }
  // GRU only, an ablation: start every step from the zero state, as if each were an episode's
  // first, so that the action depends on the current image alone (the trained weights, no memory).
  // Throws std::invalid_argument for a feed-forward network, which has no state to zero.
  void setMemoryless(bool memoryless);

 private:
  HiderNet net_;
  torch::Device device_;
  bool greedy_;
  uint32_t salt_;
  bool memoryless_ = false;
  torch::Tensor hidden_;
  std::vector<uint32_t> seeds_;  // each arena's episode seed at the last act()
};

}  // namespace hideseek_hider
