// PPO for the hider, in the order it runs (after CleanRL's ppo_atari.py):
//   1. the rollout: act() samples every arena's action and stores what the update needs, record()
//      stores the rewards and done flags the step produced, until rollout_steps rows are full;
//   2. update(): the learning rate, the value of the observation after the last step, GAE;
//   3. epochs x minibatches over the buffer, shuffled each epoch: a MinibatchSource gives each
//      minibatch's network outputs and stored rollout (single samples for the feed-forward network,
//      whole sequences for the GRU);
//   4. the losses: advantages normalised, the clipped policy objective, the (clipped) value loss,
//      the entropy bonus;
//   5. the step: gradients (averaged across ranks under DD-PPO), clipped to max_grad_norm, Adam.
// The options file's reader and the arithmetic count for make bench come last.
#include "hideseek_hider/ppo.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "hideseek_game/yaml_fields.h"

namespace hideseek_hider {

namespace {

// The optimiser must see the parameters where they will live.
HiderNet onDevice(HiderNet net, torch::Device device) {
  net->to(device);
  return net;
}

void checkShapes(const PpoOptions& options, int64_t arenas, bool recurrent) {
  const int64_t t = options.rollout_steps;
  if (options.rollout_steps < 1 || options.epochs < 1 || options.minibatches < 1 ||
      (recurrent && options.sequence_length < 1)) {
    throw std::invalid_argument(
        "PPO: rollout_steps, epochs, minibatches (and sequence_length for a GRU) must be at least 1; PpoOptions "
        "has no defaults: load them from config/ppo.yaml (loadPpoOptions)");
  }
  if ((t * arenas) % options.minibatches != 0) {
    throw std::invalid_argument("PPO: rollout_steps x arenas (" + std::to_string(t * arenas) +
                                ") must divide into minibatches (" + std::to_string(options.minibatches) + ")");
  }
  if (!recurrent) return;
  if (t % options.sequence_length != 0) {
    throw std::invalid_argument("PPO: sequence_length (" + std::to_string(options.sequence_length) +
                                ") must divide rollout_steps (" + std::to_string(t) + ")");
  }
  const int64_t sequences = t / options.sequence_length * arenas;
  if (sequences % options.minibatches != 0) {
    throw std::invalid_argument("PPO: the " + std::to_string(sequences) +
                                " sequences of a rollout (arenas x "
                                "rollout_steps / sequence_length) must divide into minibatches (" +
                                std::to_string(options.minibatches) + ")");
  }
}

}  // namespace

// ---- 1. The rollout ------------------------------------------------------------------------------

PpoTrainer::PpoTrainer(HiderNet net, const PpoOptions& options, int num_arenas, torch::Device device)
    : net_(onDevice(std::move(net), device)),
      options_(options),
      num_arenas_(num_arenas),
      device_(device),
      optimizer_(net_->parameters(), torch::optim::AdamOptions(options.learning_rate).eps(options.adam_epsilon)) {
  checkShapes(options, num_arenas, net_->recurrent());
  const int64_t t = options.rollout_steps, n = num_arenas;
  const auto f = torch::TensorOptions().device(device).dtype(torch::kFloat32);
  observations_ = torch::zeros({t, n, net_->imageHeight(), net_->imageWidth(), 3},
                               torch::TensorOptions().device(device).dtype(torch::kUInt8));
  actions_ = torch::zeros({t, n}, torch::TensorOptions().device(device).dtype(torch::kInt64));
  log_probs_ = torch::zeros({t, n}, f);
  values_ = torch::zeros({t, n}, f);
  rewards_ = torch::zeros({t, n}, f);
  dones_ = torch::zeros({t, n}, f);
  if (net_->recurrent()) {
    hiddens_ = torch::zeros({t, n, kHidden}, f);
    starts_ = torch::zeros({t, n}, f);
    hidden_ = net_->initialHidden(n);
    last_dones_ = torch::ones({n}, f);  // the first observation of every arena starts an episode
  }
}

torch::Tensor PpoTrainer::act(const torch::Tensor& observations) {
  const torch::NoGradGuard no_grad;
  const torch::Tensor obs = observations.to(device_);
  HiderOutput out;
  if (net_->recurrent()) {
    hiddens_[step_].copy_(hidden_);
    starts_[step_].copy_(last_dones_);
    out = net_->forwardSequence(obs.unsqueeze(0), hidden_, last_dones_.unsqueeze(0), &hidden_);
    out.logits = out.logits[0];
    out.value = out.value[0];
  } else {
    out = net_->forward(obs);
  }
  const torch::Tensor log_probs = torch::log_softmax(out.logits, 1);
  const torch::Tensor actions = torch::multinomial(log_probs.exp(), 1, false, generator_).squeeze(1);
  observations_[step_].copy_(obs);
  actions_[step_].copy_(actions);
  log_probs_[step_].copy_(log_probs.gather(1, actions.unsqueeze(1)).squeeze(1));
  values_[step_].copy_(out.value);
  return actions.to(torch::kCPU);
}

bool PpoTrainer::record(const torch::Tensor& rewards, const torch::Tensor& dones) {
  rewards_[step_].copy_(rewards.to(device_));
  dones_[step_].copy_(dones.to(device_));
  if (net_->recurrent()) last_dones_.copy_(dones_[step_]);
  samples_ += num_arenas_;
  return ++step_ == options_.rollout_steps;
}

// ---- 2-5. The update -----------------------------------------------------------------------------

double PpoTrainer::currentLearningRate() const {
  if (!options_.anneal_learning_rate || total_samples_ <= 0) return options_.learning_rate;
  // samples_ already counts the rows recorded in the buffer; the rate is set when it began.
  const int64_t rollout_start = samples_ - static_cast<int64_t>(step_) * num_arenas_;
  const double left = 1.0 - static_cast<double>(rollout_start) / static_cast<double>(total_samples_);
  return options_.learning_rate * std::clamp(left, 0.0, 1.0);
}

namespace {

// What one minibatch trains on, flattened to [M] samples: the network's logits and values for them
// now, and what the rollout and GAE stored for them.
struct Minibatch {
  torch::Tensor logits, values, actions, old_log_probs, old_values, advantages, returns;
};

// The buffer cut into the units an epoch shuffles. Feed-forward: the T x N samples, each on its
// own. GRU: sequences of sequence_length steps (arena n's rollout cut into C chunks; sequence
// s = c * N + n), re-run through the GRU from the state stored at their first step.
class MinibatchSource {
 public:
  MinibatchSource(const PpoTrainer& trainer, const Gae& gae, const PpoOptions& options, int64_t arenas);
  int64_t units() const { return units_; }
  Minibatch take(HiderNetImpl& net, const torch::Tensor& idx) const;

 private:
  bool recurrent_;
  int64_t units_;
  // Per unit along axis 0 (samples: [T * N, ...]) or along axis 1, time first (sequences:
  // [L, C * N, ...]).
  torch::Tensor observations_, actions_, log_probs_, values_, advantages_, returns_;
  torch::Tensor starts_, first_hidden_;  // GRU only: [L, C * N] episode starts, [C * N, 512] states
};

// Zeroes every gradient, backpropagates `loss`, averages the gradients across ranks (DD-PPO),
// clips their global norm and steps Adam.
void optimiserStep(const torch::Tensor& loss, HiderNet& net, torch::optim::Adam& optimizer, double max_grad_norm,
                   Collective* collective);
void accumulate(UpdateStats& stats, const PpoLoss& loss, const torch::Tensor& old_log_probs, double clip);
void average(UpdateStats& stats, int count, double learning_rate, Collective* collective);

}  // namespace

UpdateStats PpoTrainer::update(const torch::Tensor& next_observations) {
  if (step_ != options_.rollout_steps) throw std::logic_error("PPO: update before the buffer is full");
  const double learning_rate = currentLearningRate();
  for (auto& group : optimizer_.param_groups()) {
    static_cast<torch::optim::AdamOptions&>(group.options()).lr(learning_rate);
  }
  step_ = 0;
  // 2. The value after the last step, bootstrapped into it, and the advantages.
  torch::Tensor next_value;
  {
    const torch::NoGradGuard no_grad;
    const torch::Tensor next = next_observations.to(device_);
    next_value = net_->recurrent()
                     ? net_->forwardSequence(next.unsqueeze(0), hidden_, last_dones_.unsqueeze(0)).value[0]
                     : net_->forward(next).value;
  }
  last_gae_ = computeGae(rewards_, values_, dones_, next_value, options_.gamma, options_.gae_lambda);
  last_minibatches_.clear();
  // 3. Epochs x minibatches.
  const MinibatchSource source(*this, last_gae_, options_, num_arenas_);
  const int64_t per_minibatch = source.units() / options_.minibatches;
  UpdateStats stats;
  int count = 0;
  for (int epoch = 0; epoch < options_.epochs; ++epoch) {
    const torch::Tensor order =
        torch::randperm(source.units(), generator_, torch::TensorOptions().device(device_).dtype(torch::kInt64));
    for (int64_t start = 0; start < source.units(); start += per_minibatch) {
      const torch::Tensor idx = order.slice(0, start, start + per_minibatch);
      last_minibatches_.push_back(idx);
      const Minibatch mb = source.take(*net_, idx);
      // 4. The losses.
      const torch::Tensor advantages =
          options_.normalize_advantages ? normalizeAdvantages(mb.advantages, collective_) : mb.advantages;
      const PpoLoss loss =
          ppoLoss(mb.logits, mb.values, mb.actions, mb.old_log_probs, mb.old_values, advantages, mb.returns, options_);
      // 5. The step.
      optimiserStep(loss.total, net_, optimizer_, options_.max_grad_norm, collective_);
      accumulate(stats, loss, mb.old_log_probs, options_.clip);
      ++count;
    }
  }
  average(stats, count, learning_rate, collective_);
  return stats;
}

// ---- 2. GAE --------------------------------------------------------------------------------------

Gae computeGae(const torch::Tensor& rewards, const torch::Tensor& values, const torch::Tensor& dones,
               const torch::Tensor& next_value, double gamma, double lambda) {
  const int64_t steps = rewards.size(0);
  torch::Tensor advantages = torch::zeros_like(rewards);
  torch::Tensor last = torch::zeros_like(next_value);
  for (int64_t t = steps - 1; t >= 0; --t) {
    const torch::Tensor next_values = t == steps - 1 ? next_value : values[t + 1];
    const torch::Tensor not_done = 1.0 - dones[t];
    const torch::Tensor delta = rewards[t] + gamma * next_values * not_done - values[t];
    last = delta + gamma * lambda * not_done * last;
    advantages[t] = last;
  }
  return {advantages, advantages + values};
}

// ---- 3. Minibatches ------------------------------------------------------------------------------

namespace {

MinibatchSource::MinibatchSource(const PpoTrainer& trainer, const Gae& gae, const PpoOptions& options, int64_t arenas)
    : recurrent_(trainer.recurrent()) {
  const torch::Tensor& obs = trainer.bufferObservations();
  if (!recurrent_) {
    // Time and arenas flattened into one batch of samples.
    units_ = static_cast<int64_t>(options.rollout_steps) * arenas;
    observations_ = obs.reshape({units_, obs.size(2), obs.size(3), 3});
    actions_ = trainer.bufferActions().reshape({units_});
    log_probs_ = trainer.bufferLogProbs().reshape({units_});
    values_ = trainer.bufferValues().reshape({units_});
    advantages_ = gae.advantages.reshape({units_});
    returns_ = gae.returns.reshape({units_});
    return;
  }
  // Every per-step tensor [T, N, ...] becomes [L, C * N, ...], time first.
  const int64_t length = options.sequence_length, chunks = options.rollout_steps / length;
  units_ = chunks * arenas;
  auto bySequence = [&](const torch::Tensor& x) {
    std::vector<int64_t> shape{chunks, length, arenas};
    for (int64_t d = 2; d < x.dim(); ++d) shape.push_back(x.size(d));
    std::vector<int64_t> out{length, units_};
    for (int64_t d = 2; d < x.dim(); ++d) out.push_back(x.size(d));
    return x.reshape(shape).transpose(0, 1).reshape(out);
  };
  observations_ = bySequence(obs);
  actions_ = bySequence(trainer.bufferActions());
  log_probs_ = bySequence(trainer.bufferLogProbs());
  values_ = bySequence(trainer.bufferValues());
  advantages_ = bySequence(gae.advantages);
  returns_ = bySequence(gae.returns);
  starts_ = bySequence(trainer.bufferStarts());
  first_hidden_ = bySequence(trainer.bufferHiddens())[0];  // the state each sequence starts from
}

Minibatch MinibatchSource::take(HiderNetImpl& net, const torch::Tensor& idx) const {
  if (!recurrent_) {
    const HiderOutput out = net.forward(observations_.index_select(0, idx));
    auto pick = [&](const torch::Tensor& x) { return x.index_select(0, idx); };
    return {out.logits, out.value, pick(actions_), pick(log_probs_), pick(values_), pick(advantages_), pick(returns_)};
  }
  const HiderOutput out = net.forwardSequence(observations_.index_select(1, idx), first_hidden_.index_select(0, idx),
                                              starts_.index_select(1, idx));
  auto pick = [&](const torch::Tensor& x) { return x.index_select(1, idx).flatten(0, 1); };
  return {out.logits.flatten(0, 1), out.value.flatten(0, 1), pick(actions_), pick(log_probs_), pick(values_),
          pick(advantages_),        pick(returns_)};
}

}  // namespace

// ---- 4. The losses -------------------------------------------------------------------------------

torch::Tensor normalizeAdvantages(const torch::Tensor& advantages, Collective* collective) {
  if (!collective || collective->worldSize() == 1) return (advantages - advantages.mean()) / (advantages.std() + 1e-8);
  // Sum, sum of squares and count over every rank's minibatch: the union's mean and unbiased std.
  const torch::Tensor a = advantages.to(torch::kFloat64);
  std::vector<torch::Tensor> moments{
      torch::stack({a.sum(), a.pow(2).sum(), torch::tensor(static_cast<double>(a.numel()), torch::kFloat64)})};
  collective->allReduceSum(moments);
  const double sum = moments[0][0].item<double>(), squares = moments[0][1].item<double>(),
               n = moments[0][2].item<double>();
  const double mean = sum / n;
  const double variance = n > 1 ? std::max(0.0, (squares - n * mean * mean) / (n - 1)) : 0.0;
  return (advantages - mean) / (std::sqrt(variance) + 1e-8);
}

PpoLoss ppoLoss(const torch::Tensor& logits, const torch::Tensor& values, const torch::Tensor& actions,
                const torch::Tensor& old_log_prob, const torch::Tensor& old_values, const torch::Tensor& advantages,
                const torch::Tensor& returns, const PpoOptions& options) {
  PpoLoss l;
  const torch::Tensor log_probs_all = torch::log_softmax(logits, 1);
  l.new_log_prob = log_probs_all.gather(1, actions.unsqueeze(1)).squeeze(1);
  l.entropy = -(log_probs_all.exp() * log_probs_all).sum(1).mean();
  l.policy = clippedPolicyLoss(l.new_log_prob, old_log_prob, advantages, options.clip);
  if (options.clip_value_loss) {
    const torch::Tensor clipped = old_values + (values - old_values).clamp(-options.clip, options.clip);
    l.value = 0.5 * torch::max((values - returns).pow(2), (clipped - returns).pow(2)).mean();
  } else {
    l.value = 0.5 * (values - returns).pow(2).mean();
  }
  l.total = l.policy - options.entropy_coef * l.entropy + options.value_coef * l.value;
  return l;
}

torch::Tensor clippedPolicyLoss(const torch::Tensor& new_log_prob, const torch::Tensor& old_log_prob,
                                const torch::Tensor& advantages, double clip) {
  const torch::Tensor ratio = (new_log_prob - old_log_prob).exp();
  const torch::Tensor unclipped = -advantages * ratio;
  const torch::Tensor clipped = -advantages * ratio.clamp(1.0 - clip, 1.0 + clip);
  return torch::max(unclipped, clipped).mean();
}

// ---- 5. The step, and what the update reports ----------------------------------------------------

namespace {

void optimiserStep(const torch::Tensor& loss, HiderNet& net, torch::optim::Adam& optimizer, double max_grad_norm,
                   Collective* collective) {
  optimizer.zero_grad();
  loss.backward();
  // DD-PPO: the ranks' minibatches are of one size, so the mean of their gradients is the
  // gradient of the loss over their union; every rank then clips and steps identically.
  if (collective && collective->worldSize() > 1) averageGradients(*collective, net->parameters());
  torch::nn::utils::clip_grad_norm_(net->parameters(), max_grad_norm);
  optimizer.step();
}

// Adds one minibatch's losses and diagnostics to stats.
void accumulate(UpdateStats& stats, const PpoLoss& loss, const torch::Tensor& old_log_probs, double clip) {
  const torch::NoGradGuard no_grad;
  const torch::Tensor log_ratio = loss.new_log_prob - old_log_probs;
  stats.policy_loss += loss.policy.item<double>();
  stats.value_loss += loss.value.item<double>();
  stats.entropy += loss.entropy.item<double>();
  stats.approx_kl += ((log_ratio.exp() - 1.0) - log_ratio).mean().item<double>();
  stats.clip_fraction += ((log_ratio.exp() - 1.0).abs() > clip).to(torch::kFloat32).mean().item<double>();
}

// The update's means over its minibatches and, with several ranks, over the ranks.
void average(UpdateStats& stats, int count, double learning_rate, Collective* collective) {
  double divisor = count;
  if (collective && collective->worldSize() > 1) {
    std::vector<torch::Tensor> sums{torch::tensor(
        {stats.policy_loss, stats.value_loss, stats.entropy, stats.approx_kl, stats.clip_fraction}, torch::kFloat64)};
    collective->allReduceSum(sums);
    stats.policy_loss = sums[0][0].item<double>();
    stats.value_loss = sums[0][1].item<double>();
    stats.entropy = sums[0][2].item<double>();
    stats.approx_kl = sums[0][3].item<double>();
    stats.clip_fraction = sums[0][4].item<double>();
    divisor *= collective->worldSize();
  }
  stats.policy_loss /= divisor;
  stats.value_loss /= divisor;
  stats.entropy /= divisor;
  stats.approx_kl /= divisor;
  stats.clip_fraction /= divisor;
  stats.learning_rate = learning_rate;
}

}  // namespace

// ---- The arithmetic, and the options file --------------------------------------------------------

double trainingFlopsPerSample(const HiderNetImpl& net, const PpoOptions& options) {
  const HiderNetImpl::Flops f = net.forwardFlops();
  return f.total * (1.0 + 1.0 / options.rollout_steps) + options.epochs * (3.0 * f.total - f.first_conv);
}

PpoOptions loadPpoOptions(const std::string& path) {
  const YAML::Node root = hideseek_game::loadYamlFile(path);
  hideseek_game::YamlFields f(root, path, "");
  PpoOptions o;
  o.rollout_steps = f.integer("rollout_steps", 1, 100000);
  o.epochs = f.integer("epochs", 1, 1000);
  o.minibatches = f.integer("minibatches", 1, 100000);
  o.learning_rate = f.number("learning_rate", 1e-8, 1.0);
  o.anneal_learning_rate = f.boolean("anneal_learning_rate");
  o.adam_epsilon = f.number("adam_epsilon", 1e-12, 1.0);
  o.gamma = f.number("gamma", 0.0, 1.0);
  o.gae_lambda = f.number("gae_lambda", 0.0, 1.0);
  o.clip = f.number("clip", 0.0, 10.0);
  o.clip_value_loss = f.boolean("clip_value_loss");
  o.value_coef = f.number("value_coef", 0.0, 100.0);
  o.entropy_coef = f.number("entropy_coef", 0.0, 100.0);
  o.max_grad_norm = f.number("max_grad_norm", 1e-6, 1e6);
  o.normalize_advantages = f.boolean("normalize_advantages");
  o.sequence_length = f.integer("sequence_length", 1, 100000);
  f.rejectUnknown();
  return o;
}

}  // namespace hideseek_hider
