#include "hideseek_hider/ppo.h"

#include <algorithm>
#include <stdexcept>

#include "hideseek_world/yaml_fields.h"

namespace hideseek_hider {

PpoOptions loadPpoOptions(const std::string& path) {
  const YAML::Node root = hideseek_world::loadYamlFile(path);
  hideseek_world::YamlFields f(root, path, "");
  PpoOptions o;
  o.rollout_steps = f.integer("rollout_steps", o.rollout_steps, 1, 100000);
  o.epochs = f.integer("epochs", o.epochs, 1, 1000);
  o.minibatches = f.integer("minibatches", o.minibatches, 1, 100000);
  o.learning_rate = f.number("learning_rate", o.learning_rate, 1e-8, 1.0);
  o.anneal_learning_rate = f.boolean("anneal_learning_rate", o.anneal_learning_rate);
  o.adam_epsilon = f.number("adam_epsilon", o.adam_epsilon, 1e-12, 1.0);
  o.gamma = f.number("gamma", o.gamma, 0.0, 1.0);
  o.gae_lambda = f.number("gae_lambda", o.gae_lambda, 0.0, 1.0);
  o.clip = f.number("clip", o.clip, 0.0, 10.0);
  o.clip_value_loss = f.boolean("clip_value_loss", o.clip_value_loss);
  o.value_coef = f.number("value_coef", o.value_coef, 0.0, 100.0);
  o.entropy_coef = f.number("entropy_coef", o.entropy_coef, 0.0, 100.0);
  o.max_grad_norm = f.number("max_grad_norm", o.max_grad_norm, 1e-6, 1e6);
  o.normalize_advantages = f.boolean("normalize_advantages", o.normalize_advantages);
  f.rejectUnknown();
  return o;
}

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

torch::Tensor clippedPolicyLoss(const torch::Tensor& new_log_prob, const torch::Tensor& old_log_prob,
                                const torch::Tensor& advantages, double clip) {
  const torch::Tensor ratio = (new_log_prob - old_log_prob).exp();
  const torch::Tensor unclipped = -advantages * ratio;
  const torch::Tensor clipped = -advantages * ratio.clamp(1.0 - clip, 1.0 + clip);
  return torch::max(unclipped, clipped).mean();
}

namespace {

// The optimiser must see the parameters where they will live.
HiderNet onDevice(HiderNet net, torch::Device device) {
  net->to(device);
  return net;
}

}  // namespace

PpoTrainer::PpoTrainer(HiderNet net, const PpoOptions& options, int num_arenas, torch::Device device)
    : net_(onDevice(std::move(net), device)),
      options_(options),
      num_arenas_(num_arenas),
      device_(device),
      optimizer_(net_->parameters(), torch::optim::AdamOptions(options.learning_rate).eps(options.adam_epsilon)) {
  const int64_t t = options.rollout_steps, n = num_arenas;
  if ((t * n) % options.minibatches != 0) {
    throw std::invalid_argument("PPO: rollout_steps x arenas (" + std::to_string(t * n) +
                                ") must divide into minibatches (" + std::to_string(options.minibatches) + ")");
  }
  const auto f = torch::TensorOptions().device(device).dtype(torch::kFloat32);
  observations_ = torch::zeros({t, n, net_->imageHeight(), net_->imageWidth(), 3},
                               torch::TensorOptions().device(device).dtype(torch::kUInt8));
  actions_ = torch::zeros({t, n}, torch::TensorOptions().device(device).dtype(torch::kInt64));
  log_probs_ = torch::zeros({t, n}, f);
  values_ = torch::zeros({t, n}, f);
  rewards_ = torch::zeros({t, n}, f);
  dones_ = torch::zeros({t, n}, f);
}

torch::Tensor PpoTrainer::act(const torch::Tensor& observations) {
  const torch::NoGradGuard no_grad;
  const torch::Tensor obs = observations.to(device_);
  const HiderOutput out = net_->forward(obs);
  const torch::Tensor log_probs = torch::log_softmax(out.logits, 1);
  const torch::Tensor actions = torch::multinomial(log_probs.exp(), 1).squeeze(1);
  observations_[step_].copy_(obs);
  actions_[step_].copy_(actions);
  log_probs_[step_].copy_(log_probs.gather(1, actions.unsqueeze(1)).squeeze(1));
  values_[step_].copy_(out.value);
  return actions.to(torch::kCPU);
}

bool PpoTrainer::record(const torch::Tensor& rewards, const torch::Tensor& dones) {
  rewards_[step_].copy_(rewards.to(device_));
  dones_[step_].copy_(dones.to(device_));
  samples_ += num_arenas_;
  return ++step_ == options_.rollout_steps;
}

double PpoTrainer::currentLearningRate() const {
  if (!options_.anneal_learning_rate || total_samples_ <= 0) return options_.learning_rate;
  // samples_ already counts the rows recorded in the buffer; the rate is set when it began.
  const int64_t rollout_start = samples_ - static_cast<int64_t>(step_) * num_arenas_;
  const double left = 1.0 - static_cast<double>(rollout_start) / static_cast<double>(total_samples_);
  return options_.learning_rate * std::clamp(left, 0.0, 1.0);
}

UpdateStats PpoTrainer::update(const torch::Tensor& next_observations) {
  if (step_ != options_.rollout_steps) throw std::logic_error("PPO: update before the buffer is full");
  const double learning_rate = currentLearningRate();
  for (auto& group : optimizer_.param_groups()) {
    static_cast<torch::optim::AdamOptions&>(group.options()).lr(learning_rate);
  }
  step_ = 0;
  torch::Tensor next_value;
  {
    const torch::NoGradGuard no_grad;
    next_value = net_->forward(next_observations.to(device_)).value;
  }
  const Gae gae = computeGae(rewards_, values_, dones_, next_value, options_.gamma, options_.gae_lambda);

  // Flatten time and arenas into one batch of samples.
  const int64_t batch = static_cast<int64_t>(options_.rollout_steps) * num_arenas_;
  const torch::Tensor obs = observations_.reshape({batch, net_->imageHeight(), net_->imageWidth(), 3});
  const torch::Tensor actions = actions_.reshape({batch});
  const torch::Tensor old_log_probs = log_probs_.reshape({batch});
  const torch::Tensor old_values = values_.reshape({batch});
  const torch::Tensor advantages = gae.advantages.reshape({batch});
  const torch::Tensor returns = gae.returns.reshape({batch});

  const int64_t minibatch = batch / options_.minibatches;
  UpdateStats stats;
  int count = 0;
  for (int epoch = 0; epoch < options_.epochs; ++epoch) {
    const torch::Tensor order = torch::randperm(batch, torch::TensorOptions().device(device_).dtype(torch::kInt64));
    for (int64_t start = 0; start < batch; start += minibatch) {
      const torch::Tensor idx = order.slice(0, start, start + minibatch);
      const HiderOutput out = net_->forward(obs.index_select(0, idx));
      const torch::Tensor log_probs_all = torch::log_softmax(out.logits, 1);
      const torch::Tensor new_log_prob = log_probs_all.gather(1, actions.index_select(0, idx).unsqueeze(1)).squeeze(1);
      const torch::Tensor entropy = -(log_probs_all.exp() * log_probs_all).sum(1).mean();

      torch::Tensor adv = advantages.index_select(0, idx);
      if (options_.normalize_advantages) adv = (adv - adv.mean()) / (adv.std() + 1e-8);
      const torch::Tensor old_lp = old_log_probs.index_select(0, idx);
      const torch::Tensor policy_loss = clippedPolicyLoss(new_log_prob, old_lp, adv, options_.clip);

      const torch::Tensor target = returns.index_select(0, idx);
      torch::Tensor value_loss;
      if (options_.clip_value_loss) {
        const torch::Tensor old_v = old_values.index_select(0, idx);
        const torch::Tensor clipped = old_v + (out.value - old_v).clamp(-options_.clip, options_.clip);
        value_loss = 0.5 * torch::max((out.value - target).pow(2), (clipped - target).pow(2)).mean();
      } else {
        value_loss = 0.5 * (out.value - target).pow(2).mean();
      }

      const torch::Tensor loss = policy_loss - options_.entropy_coef * entropy + options_.value_coef * value_loss;
      optimizer_.zero_grad();
      loss.backward();
      torch::nn::utils::clip_grad_norm_(net_->parameters(), options_.max_grad_norm);
      optimizer_.step();

      const torch::NoGradGuard no_grad;
      const torch::Tensor log_ratio = new_log_prob - old_lp;
      stats.policy_loss += policy_loss.item<double>();
      stats.value_loss += value_loss.item<double>();
      stats.entropy += entropy.item<double>();
      stats.approx_kl += ((log_ratio.exp() - 1.0) - log_ratio).mean().item<double>();
      stats.clip_fraction += ((log_ratio.exp() - 1.0).abs() > options_.clip).to(torch::kFloat32).mean().item<double>();
      ++count;
    }
  }
  stats.policy_loss /= count;
  stats.value_loss /= count;
  stats.entropy /= count;
  stats.approx_kl /= count;
  stats.clip_fraction /= count;
  stats.learning_rate = learning_rate;
  return stats;
}

}  // namespace hideseek_hider
