#include "hideseek_hider/ppo.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>

#include "hideseek_game/config_error.h"
#include "hideseek_hider/checkpoint.h"
#include "shipped_ppo.h"

namespace hideseek_hider {

TEST(Gae, MatchesHandComputedValues) {
  // One arena, three steps; step 1 ended its episode. gamma 0.9, lambda 0.8, V(next) = 0.2:
  //   t=2: delta = 2 + 0.9*0.2 - 0.3 = 1.88                  adv = 1.88
  //   t=1: delta = 0 - 0.4 (no bootstrap past the end) = -0.4 adv = -0.4
  //   t=0: delta = 1 + 0.9*0.4 - 0.5 = 0.86                  adv = 0.86 + 0.72*(-0.4) = 0.572
  const torch::Tensor rewards = torch::tensor({1.0f, 0.0f, 2.0f}).unsqueeze(1);
  const torch::Tensor values = torch::tensor({0.5f, 0.4f, 0.3f}).unsqueeze(1);
  const torch::Tensor dones = torch::tensor({0.0f, 1.0f, 0.0f}).unsqueeze(1);
  const Gae gae = computeGae(rewards, values, dones, torch::tensor({0.2f}), 0.9, 0.8);
  EXPECT_NEAR(gae.advantages[0][0].item<float>(), 0.572f, 1e-5);
  EXPECT_NEAR(gae.advantages[1][0].item<float>(), -0.4f, 1e-5);
  EXPECT_NEAR(gae.advantages[2][0].item<float>(), 1.88f, 1e-5);
  EXPECT_NEAR(gae.returns[0][0].item<float>(), 1.072f, 1e-5);
}

TEST(ClippedPolicyLoss, MatchesHandComputedValues) {
  // Ratio 1.5 for both samples, clip 0.2. A = +1: -min(1.5, 1.2) = -1.2. A = -1: -min(-1.5, -1.2) = 1.5.
  const torch::Tensor old_lp = torch::zeros({2});
  const torch::Tensor new_lp = torch::full({2}, std::log(1.5f));
  EXPECT_NEAR(clippedPolicyLoss(new_lp, old_lp, torch::tensor({1.0f, -1.0f}), 0.2).item<float>(), 0.15f, 1e-6);
  // Ratio 0.5: A = +1 gives -min(0.5, 0.8) = -0.5.
  EXPECT_NEAR(
      clippedPolicyLoss(torch::full({1}, std::log(0.5f)), torch::zeros({1}), torch::ones({1}), 0.2).item<float>(),
      -0.5f, 1e-6);
}

TEST(PpoOptions, ShippedConfigLoadsAndTyposAreRejected) {
  const PpoOptions o = loadPpoOptions(std::string(HIDESEEK_CONFIG_DIR) + "/ppo.yaml");
  EXPECT_DOUBLE_EQ(o.learning_rate, 3e-4);
  EXPECT_EQ(o.rollout_steps * 16, 1024);
  const std::string bad = testing::TempDir() + "ppo_typo.yaml";
  std::ofstream(bad) << "learning_rat: 0.1\n";
  EXPECT_THROW(loadPpoOptions(bad), hideseek_game::ConfigError);
}

// config/ppo.yaml is the one source of PPO's defaults: deleting any of its keys is refused naming
// the file and that key (never a value from elsewhere), and options that were never loaded are
// refused by the trainer.
TEST(PpoOptions, EveryKeyIsRequiredAndUnloadedOptionsAreRefused) {
  const std::string shipped = std::string(HIDESEEK_CONFIG_DIR) + "/ppo.yaml";
  const YAML::Node full = YAML::LoadFile(shipped);
  int keys = 0;
  for (const auto& entry : full) {
    const std::string key = entry.first.as<std::string>();
    YAML::Node cut = YAML::Clone(full);
    cut.remove(key);
    const std::string path = testing::TempDir() + "ppo_without_" + key + ".yaml";
    std::ofstream(path) << cut;
    try {
      loadPpoOptions(path);
      ADD_FAILURE() << "a PPO file without " << key << " loaded";
    } catch (const hideseek_game::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ": field '" + key + "': is missing"), std::string::npos) << e.what();
    }
    ++keys;
  }
  EXPECT_EQ(keys, 15);  // every field of PpoOptions
  EXPECT_THROW(PpoTrainer(HiderNet(36, 36), PpoOptions{}, 2, torch::kCPU), std::invalid_argument);
}

namespace {

struct TinyTaskResult {
  double early = 0.0;  // average reward over the first 2 updates' rollouts
  double late = 0.0;   // average reward over the last 3, after 20 more updates
  int64_t samples = 0;
};

// A tiny seeded task: the image is red or blue; action 0 pays on red, action 1 on blue; every
// episode is one step. A random policy earns 0.2 per step; PPO must learn the rule in seconds.
TinyTaskResult learnTinyColourTask(Precision precision) {
  torch::manual_seed(7);
  PpoOptions o = shippedPpoOptions();
  o.rollout_steps = 16;
  o.minibatches = 4;
  o.learning_rate = 1e-3;
  o.entropy_coef = 0.0;
  constexpr int kArenas = 8, kSize = 36;
  HiderNet net(kSize, kSize);
  net->setPrecision(precision);
  PpoTrainer trainer(net, o, kArenas, torch::kCPU);
  auto observe = [&](const torch::Tensor& red) {
    torch::Tensor images = torch::zeros({kArenas, kSize, kSize, 3}, torch::kUInt8);
    for (int i = 0; i < kArenas; ++i) images[i].select(2, red[i].item<bool>() ? 0 : 2).fill_(255);
    return images;
  };
  torch::Tensor red = torch::randint(0, 2, {kArenas}).to(torch::kBool);
  auto averageReward = [&](int updates) {
    double total = 0.0;
    int steps = 0;
    for (int u = 0; u < updates; ++u) {
      bool full = false;
      while (!full) {
        const torch::Tensor actions = trainer.act(observe(red));
        const torch::Tensor right = torch::where(red, actions == 0, actions == 1);
        const torch::Tensor rewards = right.to(torch::kFloat32);
        total += rewards.sum().item<double>();
        steps += kArenas;
        red = torch::randint(0, 2, {kArenas}).to(torch::kBool);
        full = trainer.record(rewards, torch::ones({kArenas}));
      }
      trainer.update(observe(red));
    }
    return total / steps;
  };
  TinyTaskResult r;
  r.early = averageReward(2);
  averageReward(20);
  r.late = averageReward(3);
  r.samples = trainer.samplesSeen();
  return r;
}

}  // namespace

TEST(PpoTrainer, LearnsATinyColourTaskWithinSeconds) {
  const TinyTaskResult r = learnTinyColourTask(Precision::kFp32);
  EXPECT_LT(r.early, 0.45);
  EXPECT_GT(r.late, 0.85) << "early " << r.early;
  EXPECT_EQ(r.samples, 25 * 16 * 8);
}

// Mixed precision must not cost learning: from the same seed, the bf16 learner ends as close to
// perfect as the fp32 one (within 0.1 of its late reward) and far above where it started.
TEST(PpoTrainer, Bf16LearnsTheTinyTaskAsClearlyAsFp32) {
  const TinyTaskResult fp32 = learnTinyColourTask(Precision::kFp32);
  const TinyTaskResult bf16 = learnTinyColourTask(Precision::kBf16);
  EXPECT_LT(bf16.early, 0.45);
  EXPECT_GT(bf16.late, 0.85) << "bf16 early " << bf16.early;
  EXPECT_GT(bf16.late - bf16.early, 0.35);
  EXPECT_NEAR(bf16.late, fp32.late, 0.1) << "fp32 late " << fp32.late;
}

TEST(PpoTrainer, CheckpointRestoresNetworkOptimiserAndRandomState) {
  torch::manual_seed(1);
  PpoOptions o = shippedPpoOptions();
  o.rollout_steps = 4;
  o.minibatches = 2;
  PpoTrainer trainer(HiderNet(36, 36), o, 2, torch::kCPU);
  auto images = [] { return torch::randint(0, 256, {2, 36, 36, 3}, torch::kUInt8); };
  for (int s = 0; s < 4; ++s) {
    trainer.act(images());
    trainer.record(torch::ones({2}), torch::zeros({2}));
  }
  trainer.update(images());
  const std::string path = testing::TempDir() + "training.pt";
  saveCheckpoint(path, trainer.net(), {kArchitecture, 36, 36, "basic", trainer.samplesSeen()}, &trainer.optimizer());
  const torch::Tensor after_save = torch::rand({3});

  CheckpointInfo info;
  PpoTrainer resumed(loadCheckpoint(path, 36, 36, &info), o, 2, torch::kCPU);
  loadTrainingState(path, resumed.optimizer());
  EXPECT_EQ(info.steps, 8);
  EXPECT_TRUE(torch::equal(torch::rand({3}), after_save)) << "random generator restored to the saved point";
  const torch::Tensor probe = images();
  EXPECT_TRUE(torch::equal(trainer.net()->forward(probe).logits, resumed.net()->forward(probe).logits));
  // Adam's moment estimates came back too.
  const auto& a = trainer.optimizer().state();
  const auto& b = resumed.optimizer().state();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (const auto& [key, state] : a) {
    const auto& sa = static_cast<const torch::optim::AdamParamState&>(*state);
    bool found = false;
    for (const auto& [key_b, state_b] : b) {
      const auto& sb = static_cast<const torch::optim::AdamParamState&>(*state_b);
      found = found || (sa.exp_avg().sizes() == sb.exp_avg().sizes() && torch::equal(sa.exp_avg(), sb.exp_avg()) &&
                        torch::equal(sa.exp_avg_sq(), sb.exp_avg_sq()) && sa.step() == sb.step());
    }
    EXPECT_TRUE(found) << "optimiser state of a parameter was not restored";
  }
  // A checkpoint written without training state cannot resume training.
  const std::string plain = testing::TempDir() + "plain.pt";
  saveCheckpoint(plain, trainer.net(), {kArchitecture, 36, 36, "basic", 8});
  EXPECT_THROW(loadTrainingState(plain, resumed.optimizer()), std::runtime_error);
}

// The annealed rate falls linearly with the share of the run done when each rollout began, and a
// resumed run (samples restored from its checkpoint) continues on the same schedule.
TEST(PpoTrainer, LearningRateAnnealsLinearlyOverTheRunAndAcrossResumes) {
  torch::manual_seed(3);
  PpoOptions o = shippedPpoOptions();
  o.rollout_steps = 4;
  o.minibatches = 2;
  o.epochs = 1;
  o.learning_rate = 1e-3;
  auto images = [] { return torch::randint(0, 256, {2, 36, 36, 3}, torch::kUInt8); };
  auto runUpdate = [&](PpoTrainer& trainer) {
    for (int s = 0; s < 4; ++s) {
      trainer.act(images());
      trainer.record(torch::zeros({2}), torch::zeros({2}));
    }
    return trainer.update(images()).learning_rate;
  };
  PpoTrainer trainer(HiderNet(36, 36), o, 2, torch::kCPU);
  trainer.setTotalSamples(32);  // four updates of 8 samples
  EXPECT_DOUBLE_EQ(runUpdate(trainer), 1e-3);
  EXPECT_DOUBLE_EQ(runUpdate(trainer), 0.75e-3);
  EXPECT_DOUBLE_EQ(runUpdate(trainer), 0.5e-3);
  EXPECT_DOUBLE_EQ(static_cast<torch::optim::AdamOptions&>(trainer.optimizer().param_groups()[0].options()).lr(),
                   0.5e-3)
      << "the optimiser steps with the annealed rate";

  PpoTrainer resumed(HiderNet(36, 36), o, 2, torch::kCPU);
  resumed.setTotalSamples(32);
  resumed.setSamplesSeen(trainer.samplesSeen());
  EXPECT_DOUBLE_EQ(runUpdate(resumed), 0.25e-3);

  o.anneal_learning_rate = false;
  PpoTrainer constant(HiderNet(36, 36), o, 2, torch::kCPU);
  constant.setTotalSamples(32);
  runUpdate(constant);
  EXPECT_DOUBLE_EQ(runUpdate(constant), 1e-3);
}

}  // namespace hideseek_hider
