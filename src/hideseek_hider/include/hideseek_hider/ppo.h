// Proximal Policy Optimisation for the hider (after CleanRL's ppo_atari): a rollout buffer over
// arenas, GAE, the clipped policy objective, a clipped value loss, an entropy bonus, advantage
// normalisation, gradient clipping and Adam. ppo.cpp tells one update top to bottom, in the order
// it runs; the feed-forward and GRU networks share its loop.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <string>
#include <vector>

#include "hideseek_hider/collective.h"
#include "hideseek_hider/hider_net.h"

namespace hideseek_hider {

// Every hyperparameter. config/ppo.yaml is their one source of defaults: this struct holds none
// (a default-constructed one is all zeros, which PpoTrainer refuses), and loadPpoOptions requires
// every key, so that a key deleted from the file is an error, never a value from elsewhere.
// SPEC fixes the learning rate and a buffer of about 1000 steps per update (16 arenas x 64
// steps = 1024); the rest are CleanRL's Atari values.
struct PpoOptions {
  int rollout_steps{};          // decision steps per arena between updates
  int epochs{};                 // passes over the buffer per update
  int minibatches{};            // the buffer is split into this many minibatches per pass
  double learning_rate{};       // Adam; the initial rate when annealed
  bool anneal_learning_rate{};  // decay linearly to 0 over the run's total steps
  double adam_epsilon{};
  double gamma{};  // discount per decision step
  double gae_lambda{};
  double clip{};           // policy ratio clip
  bool clip_value_loss{};  // clip the value update to the same range
  double value_coef{};
  double entropy_coef{};
  double max_grad_norm{};       // global gradient norm clip
  bool normalize_advantages{};  // per minibatch
  // GRU networks only: the rollout of each arena is cut into chunks of this many steps, the
  // sequences that truncated backpropagation through time runs over; minibatches hold whole
  // sequences. Must divide rollout_steps.
  int sequence_length{};
};

// Reads a PPO file (config/ppo.yaml); every key is required, none may be unknown. Throws
// hideseek_game::ConfigError naming the file and the field.
PpoOptions loadPpoOptions(const std::string& path);

struct Gae {
  torch::Tensor advantages;  // [T, N]
  torch::Tensor returns;     // advantages + values: the value targets
};

// Generalised advantage estimation. dones[t] marks that step t ended its episode, so nothing
// after it is bootstrapped into it; next_value is V of the observation after the last step.
Gae computeGae(const torch::Tensor& rewards, const torch::Tensor& values, const torch::Tensor& dones,
               const torch::Tensor& next_value, double gamma, double lambda);

// The clipped surrogate objective, as a loss to minimise (mean over the batch).
torch::Tensor clippedPolicyLoss(const torch::Tensor& new_log_prob, const torch::Tensor& old_log_prob,
                                const torch::Tensor& advantages, double clip);

// Advantages normalised to zero mean and unit standard deviation, over this minibatch or, with
// a collective, over the union of every rank's minibatch (the same sample statistics).
torch::Tensor normalizeAdvantages(const torch::Tensor& advantages, Collective* collective = nullptr);

// One minibatch's PPO loss: the clipped policy objective, the (clipped) value loss and the
// entropy bonus, for the logits and values the network gives now and what the rollout stored.
// `advantages` are already normalised where the options ask for it.
struct PpoLoss {
  torch::Tensor total, policy, value, entropy, new_log_prob;
};
PpoLoss ppoLoss(const torch::Tensor& logits, const torch::Tensor& values, const torch::Tensor& actions,
                const torch::Tensor& old_log_prob, const torch::Tensor& old_values, const torch::Tensor& advantages,
                const torch::Tensor& returns, const PpoOptions& options);

// Floating-point operations of training per sample collected, counted from the network's layers
// (HiderNetImpl::forwardFlops) and the passes PPO makes: one forward pass in the rollout, a share
// of the bootstrap value's pass (one per arena per update), and per epoch a forward and a
// backward pass. A backward pass is counted as twice a forward one (gradients of the weights and
// of the layers' inputs) less the first convolution's input gradient, which is never computed.
double trainingFlopsPerSample(const HiderNetImpl& net, const PpoOptions& options);

// What one update did, for logs.
struct UpdateStats {
  double policy_loss = 0.0;
  double value_loss = 0.0;
  double entropy = 0.0;
  double approx_kl = 0.0;      // mean of (ratio - 1) - log ratio
  double clip_fraction = 0.0;  // share of samples whose ratio was clipped
  double learning_rate = 0.0;  // the rate this update used
};

// Collects rollout_steps decision steps of every arena, then updates the network in place.
// act() and record() alternate: act on the observations of step t, record the rewards and done
// flags that step t produced. All tensors stay on the trainer's device; observations are uint8.
// A GRU network is trained as in recurrent PPO (CleanRL's ppo_atari_lstm, SB3-contrib's
// RecurrentPPO): the trainer carries each arena's state from step to step, zeroes it where an
// episode starts, stores the state at every step, and the update re-runs whole sequences of
// sequence_length steps from the state stored at each one's start.
class PpoTrainer {
 public:
  PpoTrainer(HiderNet net, const PpoOptions& options, int num_arenas, torch::Device device);

  // Samples actions for [N, H, W, 3] uint8 observations and stores what the update needs.
  torch::Tensor act(const torch::Tensor& observations);
  // Stores the rewards [N] and done flags [N] of the last act(); true when the buffer is full.
  bool record(const torch::Tensor& rewards, const torch::Tensor& dones);
  // Runs the PPO update on the full buffer; next_observations follow its last step.
  UpdateStats update(const torch::Tensor& next_observations);

  HiderNet& net() { return net_; }
  torch::optim::Adam& optimizer() { return optimizer_; }
  int64_t samplesSeen() const { return samples_; }
  // The samples of the rollouts updated on: samplesSeen() less the rows of the one being recorded.
  int64_t samplesUpdated() const { return samples_ - static_cast<int64_t>(step_) * num_arenas_; }
  // GRU only: each arena's state after the last act() ([N, 512]).
  const torch::Tensor& hidden() const { return hidden_; }
  void setSamplesSeen(int64_t samples) { samples_ = samples; }
  // The run's length in samples, which the annealed learning rate decays over (0: no annealing).
  void setTotalSamples(int64_t total) { total_samples_ = total; }
  // The rate the next update uses: learning_rate x the share of the run left when its rollout began.
  double currentLearningRate() const;
  // Data-parallel training (DD-PPO): every minibatch's gradients are averaged across the ranks
  // before the optimiser step, advantages are normalised over all ranks' minibatch, and the
  // update's statistics are the ranks' mean. The collective must outlive the trainer; null: one
  // process, exactly as without it.
  void setCollective(Collective* collective) { collective_ = collective; }
  Collective* collective() const { return collective_; }
  // The generator (on the trainer's device) that samples actions and shuffles minibatches; by
  // default libtorch's global one, which the node seeds. Ranks trained as threads of one process each need their own.
  void setGenerator(at::Generator generator) { generator_ = std::move(generator); }

  // What the last update trained on, for checks: the buffer (time x arenas), its advantages and
  // returns, and each minibatch's sample indices (feed-forward: into the buffer flattened to
  // [T * N]; GRU: sequences), in the order they were trained.
  const torch::Tensor& bufferObservations() const { return observations_; }
  const torch::Tensor& bufferActions() const { return actions_; }
  const torch::Tensor& bufferLogProbs() const { return log_probs_; }
  const torch::Tensor& bufferValues() const { return values_; }
  // GRU only: the state before each step [T, N, 512], and 1 where that step began an episode [T, N].
  const torch::Tensor& bufferHiddens() const { return hiddens_; }
  const torch::Tensor& bufferStarts() const { return starts_; }
  const Gae& lastGae() const { return last_gae_; }
  const std::vector<torch::Tensor>& lastMinibatches() const { return last_minibatches_; }
  bool recurrent() const { return net_->recurrent(); }

 private:
  HiderNet net_;
  PpoOptions options_;
  int num_arenas_;
  torch::Device device_;
  torch::optim::Adam optimizer_;
  int step_ = 0;  // next buffer row
  int64_t samples_ = 0;
  int64_t total_samples_ = 0;
  torch::Tensor observations_, actions_, log_probs_, values_, rewards_, dones_;
  // GRU only: the state before each step, and whether that step began an episode.
  torch::Tensor hiddens_, starts_;
  torch::Tensor hidden_;      // [N, 512] each arena's state before its next step
  torch::Tensor last_dones_;  // [N] the last recorded done flags: the next step starts an episode
  Collective* collective_ = nullptr;
  c10::optional<at::Generator> generator_;
  Gae last_gae_;
  std::vector<torch::Tensor> last_minibatches_;
};

}  // namespace hideseek_hider
