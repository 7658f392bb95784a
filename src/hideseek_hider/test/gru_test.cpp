// The recurrent hider (network gru): the sequence pass equals the step-by-step one, the state
// resets where an episode starts, checkpoints say which network they hold, recurrent PPO re-runs
// exactly what the rollout computed, and a GRU learns a memory task a feed-forward net cannot.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/gru_sequence.h"
#include "hideseek_hider/hider_net.h"
#include "hideseek_hider/hider_policy.h"
#include "hideseek_hider/ppo.h"
#include "shipped_ppo.h"

namespace hideseek_hider {

namespace {

constexpr int kSize = 36;  // the smallest image the encoder takes: fast tests

torch::Tensor randomImages(std::vector<int64_t> leading) {
  leading.insert(leading.end(), {kSize, kSize, 3});
  return torch::randint(0, 256, leading, torch::kUInt8);
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

void expectClose(const torch::Tensor& a, const torch::Tensor& b, const std::string& what) {
  ASSERT_EQ(a.sizes(), b.sizes()) << what;
  EXPECT_LT((a - b).abs().max().item<double>(), 1e-5) << what;
}

}  // namespace

TEST(GruNet, SequencePassEqualsStepByStepPass) {
  torch::manual_seed(1);
  HiderNet net(kSize, kSize, NetworkKind::kGru);
  const int64_t steps = 6, batch = 3;
  const torch::Tensor images = randomImages({steps, batch});
  torch::Tensor starts = torch::zeros({steps, batch});
  starts[0].fill_(1.0);
  starts[3][1] = 1.0;  // arena 1 begins an episode at step 3
  const torch::Tensor h0 = torch::randn({batch, kHidden});
  torch::Tensor h_seq;
  const HiderOutput seq = net->forwardSequence(images, h0, starts, &h_seq);
  ASSERT_EQ(seq.logits.sizes(), (std::vector<int64_t>{steps, batch, kActions}));
  ASSERT_EQ(seq.memory.sizes(), (std::vector<int64_t>{steps, batch, kHidden}));
  torch::Tensor h = h0;
  for (int64_t t = 0; t < steps; ++t) {
    const HiderOutput one = net->forwardSequence(images.slice(0, t, t + 1), h, starts.slice(0, t, t + 1), &h);
    expectClose(one.logits[0], seq.logits[t], "logits at step " + std::to_string(t));
    expectClose(one.value[0], seq.value[t], "value at step " + std::to_string(t));
    expectClose(one.memory[0], seq.memory[t], "state at step " + std::to_string(t));
  }
  expectClose(h, h_seq, "final state");
}

TEST(GruNet, StateIsTorchGruCellOfTheFeatures) {
  // forwardSequence writes the GRU's equations out (its input side batched over the steps): a
  // torch::nn::GRUCell holding the same weights, run step by step over the same features with
  // the same resets, must give the same states.
  torch::manual_seed(11);
  HiderNet net(kSize, kSize, NetworkKind::kGru);
  const int64_t steps = 5, batch = 2;
  const torch::Tensor images = randomImages({steps, batch});
  torch::Tensor starts = torch::zeros({steps, batch});
  starts[2][0] = 1.0;
  const torch::Tensor h0 = torch::randn({batch, kHidden});
  const HiderOutput seq = net->forwardSequence(images, h0, starts);
  torch::nn::GRUCell cell(torch::nn::GRUCellOptions(512, kHidden));
  {
    const torch::NoGradGuard no_grad;
    const auto params = net->named_parameters();
    cell->weight_ih.copy_(params["gru.weight_ih"]);
    cell->weight_hh.copy_(params["gru.weight_hh"]);
    cell->bias_ih.copy_(params["gru.bias_ih"]);
    cell->bias_hh.copy_(params["gru.bias_hh"]);
  }
  torch::Tensor h = h0;
  for (int64_t t = 0; t < steps; ++t) {
    h = cell->forward(seq.features[t], h * (1.0 - starts[t]).unsqueeze(1));
    expectClose(seq.memory[t], h, "state at step " + std::to_string(t));
  }
}

namespace {

// gruSequence (fused in fp32 on the CPU, by ATen operators otherwise) against torch::nn::GRUCell
// under autograd: the cell's input weights are the identity, so that its input
// side is the gates given. States and every gradient must agree, resets inside the sequence and a
// state carried in from before it included, at a toy size and at the size the hider trains with.
void expectGruSequenceMatchesGruCell(int64_t steps, int64_t batch, int64_t hidden, uint64_t seed,
                                     torch::Dtype dtype = torch::kFloat32) {
  torch::manual_seed(seed);
  const auto f = torch::TensorOptions().dtype(dtype);
  const torch::Tensor gates = torch::randn({steps, batch, 3 * hidden}, f).requires_grad_(true);
  torch::Tensor keep = torch::ones({steps, batch}, f);
  keep[steps / 2][0] = 0.0;
  keep[1][batch - 1] = 0.0;
  const torch::Tensor h0 = torch::randn({batch, hidden}, f).requires_grad_(true);
  torch::nn::GRUCell cell(torch::nn::GRUCellOptions(3 * hidden, hidden));
  cell->to(dtype);
  {
    const torch::NoGradGuard no_grad;
    cell->weight_ih.copy_(torch::eye(3 * hidden, f));
    cell->bias_ih.zero_();
  }
  const torch::Tensor weight_hh = cell->weight_hh.detach().clone().requires_grad_(true);
  const torch::Tensor bias_hh = cell->bias_hh.detach().clone().requires_grad_(true);
  const torch::Tensor probe = torch::randn({steps, batch, hidden}, f);  // a loss that weighs every state

  const torch::Tensor fused = gruSequence(gates, keep, h0, weight_hh, bias_hh);
  (fused * probe).sum().backward();

  const torch::Tensor gates_ref = gates.detach().clone().requires_grad_(true);
  const torch::Tensor h0_ref = h0.detach().clone().requires_grad_(true);
  torch::Tensor h = h0_ref;
  std::vector<torch::Tensor> states;
  for (int64_t t = 0; t < steps; ++t) {
    h = cell->forward(gates_ref[t], h * keep[t].unsqueeze(1));
    states.push_back(h);
  }
  const torch::Tensor reference = torch::stack(states);
  (reference * probe).sum().backward();

  auto close = [](const torch::Tensor& a, const torch::Tensor& b, const std::string& what) {
    ASSERT_EQ(a.sizes(), b.sizes()) << what;
    const double scale = std::max(1.0, b.abs().max().item<double>());
    EXPECT_LT((a - b).abs().max().item<double>() / scale, 2e-5) << what;
  };
  close(fused, reference, "states");
  close(gates.grad(), gates_ref.grad(), "gradient of the gates' input side");
  close(h0.grad(), h0_ref.grad(), "gradient of the initial state");
  close(weight_hh.grad(), cell->weight_hh.grad(), "gradient of weight_hh");
  close(bias_hh.grad(), cell->bias_hh.grad(), "gradient of bias_hh");
}

}  // namespace

TEST(GruSequence, FusedPassAndGradientsEqualTorchGruCell) {
  expectGruSequenceMatchesGruCell(7, 5, 16, 3);
  expectGruSequenceMatchesGruCell(32, 8, kHidden, 4);  // a minibatch of recurrent PPO
}

TEST(GruSequence, OperatorPathOffTheFusedTypeEqualsTorchGruCell) {
  // fp64 is not the fused path's type: gruSequence steps the equations by ATen operators.
  expectGruSequenceMatchesGruCell(7, 5, 16, 6, torch::kFloat64);
}

TEST(GruSequence, ResetStopsTheGradientFromReachingEarlierSteps) {
  torch::manual_seed(5);
  const int64_t steps = 6, batch = 2, hidden = 8;
  const torch::Tensor gates = torch::randn({steps, batch, 3 * hidden}).requires_grad_(true);
  torch::Tensor keep = torch::ones({steps, batch});
  keep[3][0] = 0.0;  // arena 0 starts an episode at step 3
  const torch::Tensor h0 = torch::randn({batch, hidden}).requires_grad_(true);
  const torch::Tensor w = torch::randn({3 * hidden, hidden}).requires_grad_(true);
  const torch::Tensor b = torch::randn({3 * hidden}).requires_grad_(true);
  gruSequence(gates, keep, h0, w, b)[steps - 1].sum().backward();
  // Arena 0's last state depends on steps 3.. only; arena 1's on every step and on h0.
  EXPECT_EQ(gates.grad().slice(0, 0, 3).select(1, 0).abs().sum().item<double>(), 0.0);
  EXPECT_EQ(h0.grad()[0].abs().sum().item<double>(), 0.0);
  EXPECT_GT(gates.grad().slice(0, 0, 3).select(1, 1).abs().sum().item<double>(), 0.0);
  EXPECT_GT(h0.grad()[1].abs().sum().item<double>(), 0.0);
}

TEST(GruSequence, RecurrentWeightsChangedBeforeTheBackwardPassAreAnError) {
  // As with any autograd operation: a gradient from weights an optimiser step already changed
  // would be silently wrong.
  torch::manual_seed(7);
  const int64_t steps = 4, batch = 2, hidden = 8;
  const torch::Tensor gates = torch::randn({steps, batch, 3 * hidden}).requires_grad_(true);
  const torch::Tensor w = torch::randn({3 * hidden, hidden}).requires_grad_(true);
  const torch::Tensor b = torch::randn({3 * hidden}).requires_grad_(true);
  const torch::Tensor states = gruSequence(gates, torch::ones({steps, batch}), torch::zeros({batch, hidden}), w, b);
  {
    const torch::NoGradGuard no_grad;
    w.add_(1.0);
  }
  EXPECT_THROW(states.sum().backward(), c10::Error);
}

TEST(GruNet, StateResetsWhereAnEpisodeStartsInsideASequence) {
  torch::manual_seed(2);
  HiderNet net(kSize, kSize, NetworkKind::kGru);
  const int64_t steps = 6, batch = 2;
  const torch::Tensor images = randomImages({steps, batch});
  torch::Tensor starts = torch::zeros({steps, batch});
  starts[3][0] = 1.0;  // arena 0's new episode begins at step 3; arena 1 goes on
  const torch::Tensor h0 = torch::randn({batch, kHidden});
  const HiderOutput seq = net->forwardSequence(images, h0, starts);
  // Arena 0 from step 3 on is what a fresh episode from a zero state gives...
  const HiderOutput fresh =
      net->forwardSequence(images.slice(0, 3).slice(1, 0, 1), net->initialHidden(1), torch::zeros({3, 1}));
  expectClose(seq.logits.slice(0, 3).slice(1, 0, 1), fresh.logits, "arena 0 after its reset");
  // ... and not what carrying the old state gives: the reset changed something.
  const HiderOutput carried = net->forwardSequence(images, h0, torch::zeros({steps, batch}));
  EXPECT_GT((carried.memory[3][0] - seq.memory[3][0]).abs().max().item<double>(), 1e-3);
  // Arena 1 never reset: the same either way.
  expectClose(seq.memory.slice(1, 1, 2), carried.memory.slice(1, 1, 2), "arena 1 without a reset");
}

TEST(GruNet, FeedForwardPassIsRefusedWithoutAState) {
  HiderNet net(kSize, kSize, NetworkKind::kGru);
  EXPECT_NE(errorOf([&] { net->forward(randomImages({1})); }).find("needs its state"), std::string::npos);
}

TEST(GruNet, Bf16RunsAndStaysCloseToFp32) {
  torch::manual_seed(4);
  HiderNet net(kSize, kSize, NetworkKind::kGru);
  const torch::Tensor images = randomImages({4, 2});
  const torch::Tensor starts = torch::zeros({4, 2});
  const HiderOutput fp32 = net->forwardSequence(images, net->initialHidden(2), starts);
  net->setPrecision(Precision::kBf16);
  const HiderOutput bf16 = net->forwardSequence(images, net->initialHidden(2), starts);
  EXPECT_EQ(bf16.logits.scalar_type(), torch::kFloat32);
  EXPECT_EQ(bf16.memory.scalar_type(), torch::kFloat32);
  EXPECT_TRUE(bf16.logits.isfinite().all().item<bool>());
  EXPECT_LT((bf16.logits - fp32.logits).abs().max().item<double>(), 0.05);
}

TEST(GruCheckpoint, SaysWhichNetworkItHoldsAndTheOtherIsRefused) {
  torch::manual_seed(5);
  HiderNet gru(kSize, kSize, NetworkKind::kGru);
  HiderNet ff(kSize, kSize);
  const std::string gru_path = testing::TempDir() + "gru.pt", ff_path = testing::TempDir() + "ff.pt";
  saveCheckpoint(gru_path, gru, {gru->architecture(), kSize, kSize, "basic", 10});
  saveCheckpoint(ff_path, ff, {ff->architecture(), kSize, kSize, "basic", 10});
  EXPECT_EQ(readCheckpointInfo(gru_path).network, NetworkKind::kGru);
  EXPECT_EQ(readCheckpointInfo(ff_path).network, NetworkKind::kFeedForward);
  // Asked for the other kind: refused, naming the file, both kinds and the fix.
  const std::string into_ff =
      errorOf([&] { loadCheckpoint(gru_path, kSize, kSize, nullptr, NetworkKind::kFeedForward); });
  EXPECT_NE(into_ff.find(gru_path), std::string::npos) << into_ff;
  EXPECT_NE(into_ff.find("recurrent (GRU) hider (network gru), but network ff was asked"), std::string::npos)
      << into_ff;
  EXPECT_NE(into_ff.find("network:=gru"), std::string::npos) << into_ff;
  const std::string into_gru = errorOf([&] { loadCheckpoint(ff_path, kSize, kSize, nullptr, NetworkKind::kGru); });
  EXPECT_NE(into_gru.find("feed-forward hider (network ff), but network gru was asked"), std::string::npos) << into_gru;
  // Not asked: the checkpoint's own network, weights and all.
  HiderNet loaded = loadCheckpoint(gru_path, kSize, kSize);
  ASSERT_TRUE(loaded->recurrent());
  const torch::Tensor images = randomImages({3, 2});
  expectClose(loaded->forwardSequence(images, loaded->initialHidden(2), torch::zeros({3, 2})).logits,
              gru->forwardSequence(images, gru->initialHidden(2), torch::zeros({3, 2})).logits, "reloaded GRU");
}

TEST(RecurrentPpo, UpdateReRunsEachSequenceExactlyAsTheRolloutRanIt) {
  // One epoch, one minibatch: the update's losses are computed before its only optimiser step,
  // so re-running the stored sequences from their stored start states must reproduce the
  // rollout's log-probabilities exactly (ratio 1, no KL). A wrong start state, a missed reset or
  // a mis-assembled sequence would show as KL.
  torch::manual_seed(6);
  PpoOptions o = shippedPpoOptions();
  o.rollout_steps = 8;
  o.sequence_length = 4;
  o.epochs = 1;
  o.minibatches = 1;
  const int arenas = 3;
  PpoTrainer trainer(HiderNet(kSize, kSize, NetworkKind::kGru), o, arenas, torch::kCPU);
  for (int rollout = 0; rollout < 2; ++rollout) {  // the second rollout starts mid-episode
    for (int t = 0; t < o.rollout_steps; ++t) {
      trainer.act(randomImages({arenas}));
      torch::Tensor dones = torch::zeros({arenas});
      if (t == 1) dones[0] = 1.0;  // an episode ends inside the first sequence
      if (t == 5) dones[2] = 1.0;  // and inside the second
      trainer.record(torch::full({arenas}, 0.001f), dones);
    }
    const UpdateStats stats = trainer.update(randomImages({arenas}));
    EXPECT_LT(stats.approx_kl, 1e-9) << "rollout " << rollout;
    EXPECT_EQ(stats.clip_fraction, 0.0) << "rollout " << rollout;
  }
}

TEST(RecurrentPpo, TrainerStartsAFreshStateAfterAnEpisodeEnds) {
  torch::manual_seed(8);
  PpoOptions o = shippedPpoOptions();
  o.rollout_steps = 4;
  o.sequence_length = 4;
  o.minibatches = 1;
  PpoTrainer trainer(HiderNet(kSize, kSize, NetworkKind::kGru), o, 2, torch::kCPU);
  const torch::Tensor a = randomImages({2}), b = randomImages({2});
  trainer.act(a);
  trainer.record(torch::zeros({2}), torch::tensor({1.0f, 0.0f}));  // arena 0's episode ended
  trainer.act(b);
  HiderNet& net = trainer.net();
  const torch::NoGradGuard no_grad;
  // Arena 0: b is the first step of a new episode, from a zero state.
  const torch::Tensor fresh =
      net->forwardSequence(b.slice(0, 0, 1).unsqueeze(0), net->initialHidden(1), torch::zeros({1, 1})).memory[0];
  expectClose(trainer.hidden().slice(0, 0, 1), fresh, "arena 0 after its episode ended");
  // Arena 1: a then b in one episode.
  const torch::Tensor carried = net->forwardSequence(torch::stack({a.slice(0, 1, 2), b.slice(0, 1, 2)}),
                                                     net->initialHidden(1), torch::zeros({2, 1}))
                                    .memory[1];
  expectClose(trainer.hidden().slice(0, 1, 2), carried, "arena 1 within its episode");
}

TEST(GruPolicy, StateStartsAfreshAtStepZeroAndAtANewSeed) {
  torch::manual_seed(9);
  HiderNet net(kSize, kSize, NetworkKind::kGru);
  NetworkHiderPolicy policy(net, torch::kCPU, true);
  const torch::Tensor img = randomImages({1}).contiguous();
  const torch::Tensor fresh =
      net->forwardSequence(img.unsqueeze(0), net->initialHidden(1), torch::zeros({1, 1})).memory[0];
  auto act = [&](uint32_t seed, uint32_t step) { policy.act({{img.data_ptr<uint8_t>(), seed, step}}); };
  act(5, 0);
  expectClose(policy.hidden(), fresh, "first step");
  act(5, 1);
  EXPECT_GT((policy.hidden() - fresh).abs().max().item<double>(), 1e-4) << "the state carries within an episode";
  act(5, 0);  // a reset re-plays step 0
  expectClose(policy.hidden(), fresh, "step 0 again");
  act(5, 1);
  act(6, 2);  // another episode's seed mid-way (a reset to another seed)
  expectClose(policy.hidden(), fresh, "a new seed");
}

TEST(GruPolicy, MemorylessStartsEveryStepFromTheZeroState) {
  torch::manual_seed(9);
  HiderNet net(kSize, kSize, NetworkKind::kGru);
  NetworkHiderPolicy with_memory(net, torch::kCPU, true), memoryless(net, torch::kCPU, true);
  memoryless.setMemoryless(true);
  const torch::Tensor a = randomImages({1}).contiguous(), b = randomImages({1}).contiguous();
  const torch::Tensor fresh_b =
      net->forwardSequence(b.unsqueeze(0), net->initialHidden(1), torch::zeros({1, 1})).memory[0];
  for (NetworkHiderPolicy* p : {&with_memory, &memoryless}) {
    p->act({{a.data_ptr<uint8_t>(), 3, 0}});
    p->act({{b.data_ptr<uint8_t>(), 3, 1}});  // the same episode, a step later
  }
  expectClose(memoryless.hidden(), fresh_b, "memoryless: the state after image b alone");
  EXPECT_GT((with_memory.hidden() - fresh_b).abs().max().item<double>(), 1e-4) << "with memory, image a is remembered";
  // A feed-forward policy has no state to zero: asking is refused, not ignored.
  NetworkHiderPolicy feed_forward(HiderNet(kSize, kSize, NetworkKind::kFeedForward), torch::kCPU, true);
  EXPECT_THROW(feed_forward.setMemoryless(true), std::invalid_argument);
}

TEST(RecurrentPpo, SequencesMustDivideTheRolloutAndTheMinibatches) {
  PpoOptions o = shippedPpoOptions();
  o.rollout_steps = 8;
  o.sequence_length = 3;
  EXPECT_NE(errorOf([&] {
              PpoTrainer(HiderNet(kSize, kSize, NetworkKind::kGru), o, 2, torch::kCPU);
            }).find("sequence_length (3) must divide rollout_steps (8)"),
            std::string::npos);
  o.sequence_length = 8;
  o.minibatches = 4;  // 2 arenas x 1 sequence each cannot make 4 minibatches of whole sequences
  EXPECT_NE(errorOf([&] {
              PpoTrainer(HiderNet(kSize, kSize, NetworkKind::kGru), o, 2, torch::kCPU);
            }).find("must divide into minibatches"),
            std::string::npos);
}

namespace {

// A cue shown, then hidden: each episode is three steps. Step 0 shows an all-red or all-blue
// image (the cue), steps 1 and 2 a grey one. At step 2 the hider earns 1 for action 1 after red
// or action 2 after blue; nothing else is rewarded. Only a hider that remembers the cue can do
// better than chance, since step 2 looks the same either way.
struct CueTask {
  static torch::Tensor image(int step, bool red) {
    torch::Tensor img = torch::full({kSize, kSize, 3}, 128, torch::kUInt8);
    if (step == 0) {
      img.fill_(0);
      img.select(2, red ? 0 : 2).fill_(255);
    }
    return img;
  }
  static int answer(bool red) { return red ? 1 : 2; }
};

// Trains `net` with PPO on the cue task for at most `max_updates` updates, stopping once a
// rollout's sampled answers are 95 % right; *used says how many ran. Returns the share of greedy
// episodes the trained net answers right.
double trainOnCueTask(HiderNet net, int max_updates, int* used) {
  torch::manual_seed(7);
  PpoOptions o = shippedPpoOptions();
  o.rollout_steps = 12;  // four episodes per arena
  o.sequence_length = 6;
  o.minibatches = 4;
  o.epochs = 4;
  o.learning_rate = 1e-3;
  o.anneal_learning_rate = false;
  o.entropy_coef = 0.0;
  const int arenas = 16;
  PpoTrainer trainer(net, o, arenas, torch::kCPU);
  std::mt19937 rng(7);
  std::vector<bool> red(arenas);
  int step = 0;
  auto batch = [&] {
    torch::Tensor images = torch::empty({arenas, kSize, kSize, 3}, torch::kUInt8);
    for (int i = 0; i < arenas; ++i) images[i].copy_(CueTask::image(step, red[i]));
    return images;
  };
  for (int i = 0; i < arenas; ++i) red[i] = rng() % 2;
  *used = 0;
  for (double rate = 0.0; *used < max_updates && rate < 0.95; ++*used) {
    bool full = false;
    int answered = 0, right = 0;
    while (!full) {
      const torch::Tensor actions = trainer.act(batch());
      torch::Tensor rewards = torch::zeros({arenas});
      const bool last = step == 2;
      for (int i = 0; i < arenas && last; ++i, ++answered) {
        const bool ok = actions[i].item<int64_t>() == CueTask::answer(red[i]);
        rewards[i] = ok ? 1.0 : 0.0;
        right += ok;
      }
      full = trainer.record(rewards, torch::full({arenas}, last ? 1.0f : 0.0f));
      step = last ? 0 : step + 1;
      if (last) {
        for (int i = 0; i < arenas; ++i) red[i] = rng() % 2;
      }
    }
    trainer.update(batch());
    rate = static_cast<double>(right) / answered;
  }
  // Greedy episodes through the deployed policy, which keeps (and resets) the state itself.
  NetworkHiderPolicy policy(trainer.net(), torch::kCPU, true);
  int right = 0, episodes = 0;
  for (int e = 0; e < 8; ++e) {
    for (int i = 0; i < arenas; ++i) red[i] = rng() % 2;
    std::vector<torch::Tensor> keep;
    for (int t = 0; t < 3; ++t) {
      std::vector<ArenaObservation> obs(arenas);
      keep.clear();
      for (int i = 0; i < arenas; ++i) {
        keep.push_back(CueTask::image(t, red[i]).contiguous());
        obs[i] = {keep.back().data_ptr<uint8_t>(), static_cast<uint32_t>(e * arenas + i), static_cast<uint32_t>(t)};
      }
      const std::vector<uint8_t> actions = policy.act(obs);
      for (int i = 0; i < arenas && t == 2; ++i, ++episodes) right += actions[i] == CueTask::answer(red[i]);
    }
  }
  return static_cast<double>(right) / episodes;
}

}  // namespace

TEST(RecurrentPpo, GruRecallsAHiddenCueThatAFeedForwardNetCannot) {
  torch::set_num_threads(1);
  int gru_updates = 0, ff_updates = 0;
  const double gru = trainOnCueTask(HiderNet(kSize, kSize, NetworkKind::kGru), 150, &gru_updates);
  // The feed-forward net gets the same training (at least 40 updates), same seeds.
  const double ff = trainOnCueTask(HiderNet(kSize, kSize), std::max(gru_updates, 40), &ff_updates);
  RecordProperty("gru_correct", std::to_string(gru));
  RecordProperty("gru_updates", gru_updates);
  RecordProperty("ff_correct", std::to_string(ff));
  EXPECT_GE(gru, 0.9) << "the GRU did not learn to recall the cue in " << gru_updates << " updates";
  EXPECT_LE(ff, 0.7) << "a feed-forward net cannot see the cue at the answer step";
}

}  // namespace hideseek_hider
