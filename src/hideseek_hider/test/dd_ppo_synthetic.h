// PPO updates of a small network on synthetic rollouts, for the checks of training across
// machines (dd_ppo_test, dd_ppo_check): each rank's images, rewards and episode ends are its own
// and fixed by its rank, and every update's buffer and minibatches are recorded, so that one
// process can redo the ranks' updates on the union of their samples.
#pragma once

#include <ATen/CPUGeneratorImpl.h>
#include <torch/torch.h>

#include <mutex>
#include <vector>

#include "hideseek_hider/collective.h"
#include "hideseek_hider/ppo.h"
#include "shipped_ppo.h"

namespace hideseek_hider {

struct SyntheticSetup {
  int image = 36;  // the smallest image the network's convolutions take
  int arenas = 2;  // per rank
  PpoOptions ppo = shippedPpoOptions();
  SyntheticSetup() {
    ppo.rollout_steps = 8;
    ppo.epochs = 2;
    ppo.minibatches = 2;
  }
};

// What one rank trained on in one update.
struct UpdateRecord {
  torch::Tensor observations, actions, log_probs, values, advantages, returns;  // [T, N, ...]
  std::vector<torch::Tensor> minibatches;  // sample indices into [T * N], in training order
};

// Trains `updates` updates; every rank starts from rank 0's weights. Returns the final weights
// (every parameter, flattened and joined). `after_update(k)` runs after update k (1-based).
template <class AfterUpdate>
torch::Tensor trainSynthetic(const SyntheticSetup& s, Collective* collective, int rank, int updates,
                             std::vector<UpdateRecord>* records, torch::Tensor* initial, AfterUpdate after_update) {
  // Different initial weights, so that the broadcast matters; drawn from libtorch's global
  // generator, which threads share, so one rank at a time.
  static std::mutex global_generator;
  std::unique_lock<std::mutex> drawing(global_generator);
  torch::manual_seed(100 + rank);
  PpoTrainer trainer(HiderNet(s.image, s.image), s.ppo, s.arenas, torch::kCPU);
  drawing.unlock();
  trainer.setCollective(collective);
  // The ranks may be threads of one process: each samples from its own generator, so that what it
  // plays does not depend on how the threads interleave.
  trainer.setGenerator(at::make_generator<at::CPUGeneratorImpl>(31 + rank));
  if (collective) broadcastModule(*collective, *trainer.net());
  auto flat = [&] {
    std::vector<torch::Tensor> parts;
    for (const torch::Tensor& p : trainer.net()->parameters()) parts.push_back(p.detach().reshape({-1}).clone());
    return torch::cat(parts);
  };
  if (initial) *initial = flat();
  at::Generator data = at::make_generator<at::CPUGeneratorImpl>(7919 * (rank + 1));
  auto observation = [&] {
    return torch::randint(0, 256, {s.arenas, s.image, s.image, 3}, data, torch::TensorOptions().dtype(torch::kUInt8));
  };
  torch::Tensor obs = observation();
  int step = 0;
  for (int u = 1; u <= updates; ++u) {
    bool full = false;
    while (!full) {
      trainer.act(obs);
      ++step;
      const torch::Tensor rewards = torch::rand({s.arenas}, data) - 0.5;
      torch::Tensor dones = torch::zeros({s.arenas});
      if (step % (5 + rank) == 0) dones[0] = 1.0;
      full = trainer.record(rewards, dones);
      obs = observation();
    }
    trainer.update(obs);
    if (records) {
      UpdateRecord r;
      r.observations = trainer.bufferObservations().clone();
      r.actions = trainer.bufferActions().clone();
      r.log_probs = trainer.bufferLogProbs().clone();
      r.values = trainer.bufferValues().clone();
      r.advantages = trainer.lastGae().advantages.clone();
      r.returns = trainer.lastGae().returns.clone();
      r.minibatches = trainer.lastMinibatches();
      records->push_back(r);
    }
    after_update(u);
  }
  return flat();
}

}  // namespace hideseek_hider
