// Turns observation batches into actions: uniformly random, or sampled from a trained network.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hideseek_hider/hider_net.h"

namespace hideseek_hider {

// One arena's observation as the policy needs it: the image and what makes sampling reproducible.
struct ArenaObservation {
  const uint8_t* image = nullptr;  // H x W x 3, rgb8
  uint32_t seed = 0;               // episode seed
  uint32_t step = 0;
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

// Inference from a checkpoint: one batched forward pass per step, no autograd.
class NetworkHiderPolicy : public HiderPolicy {
 public:
  NetworkHiderPolicy(HiderNet net, torch::Device device, bool greedy);
  std::vector<uint8_t> act(const std::vector<ArenaObservation>& batch) override;

 private:
  HiderNet net_;
  torch::Device device_;
  bool greedy_;
};

}  // namespace hideseek_hider
