#include "hideseek_hider/hider_net.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>

#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_policy.h"

namespace hideseek_hider {

namespace {

torch::Tensor randomImages(int64_t n, int64_t h, int64_t w) {
  torch::manual_seed(3);
  return torch::randint(0, 256, {n, h, w, 3}, torch::kUInt8);
}

std::string tempPath(const std::string& name) { return testing::TempDir() + name; }

CheckpointInfo infoFor(int h, int w) { return {kArchitecture, h, w, "basic", 1234}; }

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(HiderNet, OutputsHaveNamedShapesAndFeaturesOf512) {
  HiderNet net(84, 84);
  const HiderOutput out = net->forward(randomImages(6, 84, 84));
  EXPECT_EQ(out.logits.sizes(), (std::vector<int64_t>{6, 5}));
  EXPECT_EQ(out.value.sizes(), (std::vector<int64_t>{6}));
  EXPECT_EQ(out.features.sizes(), (std::vector<int64_t>{6, 512}));
  EXPECT_TRUE(torch::isfinite(out.logits).all().item<bool>());
}

TEST(HiderNet, OtherImageSizesWorkAndTinyOnesAreRefused) {
  HiderNet net(64, 96);
  EXPECT_EQ(net->forward(randomImages(2, 64, 96)).features.size(1), 512);
  EXPECT_THROW(HiderNet(20, 20), std::invalid_argument);
  EXPECT_THROW(net->forward(randomImages(2, 84, 84)), c10::Error);
}

TEST(HiderNet, ForwardFlopsAreCountedFromEveryLayer) {
  // 84 x 84: conv1 20x20x32 outputs of 8x8x3, conv2 9x9x64 of 4x4x32, conv3 7x7x64 of 3x3x64,
  // fc 3136 -> 512, the two hidden heads 512 -> 512, the outputs 512 -> 5 and 512 -> 1; 2 flops
  // per multiply-add.
  const double conv1 = 2.0 * 20 * 20 * 32 * 8 * 8 * 3;
  const double ff = conv1 + 2.0 * 9 * 9 * 64 * 4 * 4 * 32 + 2.0 * 7 * 7 * 64 * 3 * 3 * 64 + 2.0 * 3136 * 512 +
                    2 * 2.0 * 512 * 512 + 2.0 * 512 * 5 + 2.0 * 512 * 1;
  EXPECT_DOUBLE_EQ(HiderNet(84, 84)->forwardFlops().total, ff);
  EXPECT_DOUBLE_EQ(HiderNet(84, 84)->forwardFlops().first_conv, conv1);
  // The GRU adds its input and recurrent products, each 512 -> 3 x 512.
  EXPECT_DOUBLE_EQ(HiderNet(84, 84, NetworkKind::kGru)->forwardFlops().total, ff + 2 * 2.0 * 512 * 1536);
  // Larger images cost more in the encoder only: 100 x 100 gives conv1 24x24, conv2 11x11, conv3 9x9.
  const HiderNetImpl::Flops big = HiderNet(100, 100)->forwardFlops();
  EXPECT_DOUBLE_EQ(big.first_conv, 2.0 * 24 * 24 * 32 * 8 * 8 * 3);
  EXPECT_DOUBLE_EQ(big.total - big.first_conv - (2.0 * 11 * 11 * 64 * 4 * 4 * 32 + 2.0 * 9 * 9 * 64 * 3 * 3 * 64),
                   2.0 * 64 * 9 * 9 * 512 + 2 * 2.0 * 512 * 512 + 2.0 * 512 * 6);
}

TEST(Checkpoint, RoundTripGivesIdenticalOutputs) {
  HiderNet net(84, 84);
  const std::string path = tempPath("roundtrip.pt");
  saveCheckpoint(path, net, infoFor(84, 84));
  CheckpointInfo info;
  HiderNet loaded = loadCheckpoint(path, 84, 84, &info);
  EXPECT_EQ(info.variant, "basic");
  EXPECT_EQ(info.steps, 1234);
  const torch::Tensor images = randomImages(4, 84, 84);
  const HiderOutput a = net->forward(images), b = loaded->forward(images);
  EXPECT_TRUE(torch::equal(a.logits, b.logits));
  EXPECT_TRUE(torch::equal(a.value, b.value));
  EXPECT_TRUE(torch::equal(a.features, b.features));
}

// A write that runs out of space (here the process's file size limit, which fails a write as a
// full disk does) throws naming the file and the cause, removes its temporary file and leaves the
// previous checkpoint as it was.
TEST(Checkpoint, AWriteThatRunsOutOfSpaceLeavesThePreviousFileIntact) {
  const std::string path = testing::TempDir() + "full_disk_checkpoint.pt";
  writeFileAtomically(path, std::string(1000, 'a'));
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
  rlimit small = old;
  small.rlim_cur = 64 * 1024;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string error;
  try {
    writeFileAtomically(path, std::string(1 << 20, 'b'));
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  EXPECT_NE(error.find("cannot write " + path), std::string::npos) << error;
  EXPECT_NE(error.find("the previous file is left as it was"), std::string::npos) << error;
  std::ifstream in(path);
  const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, std::string(1000, 'a'));
  EXPECT_FALSE(std::ifstream(path + ".tmp").good()) << "the temporary file was left behind";
}

// A checkpoint says whose policy it is; every hider node and tool asks for a hider's and refuses a
// seeker's by name, and a checkpoint from before the field is a hider's.
TEST(Checkpoint, ASeekersCheckpointIsRefusedWhereAHidersIsAsked) {
  HiderNet net(84, 84);
  CheckpointInfo info = infoFor(84, 84);
  EXPECT_EQ(info.role, "hider");
  info.role = "seeker";
  const std::string path = tempPath("seeker.pt");
  saveCheckpoint(path, net, info);
  EXPECT_EQ(readCheckpointInfo(path).role, "seeker");
  const std::string e = errorOf([&] { loadCheckpoint(path, 84, 84); });
  EXPECT_NE(e.find("checkpoint " + path + " is a seeker's policy (role seeker), not a hider's"), std::string::npos)
      << e;
  CheckpointInfo loaded;
  loadCheckpoint(path, 84, 84, &loaded, std::nullopt, "seeker");  // what a seeker's node will ask for
  EXPECT_EQ(loaded.role, "seeker");
  const std::string hider_path = tempPath("hider.pt");
  saveCheckpoint(hider_path, net, infoFor(84, 84));
  const std::string r = errorOf([&] { loadCheckpoint(hider_path, 84, 84, nullptr, std::nullopt, "seeker"); });
  EXPECT_NE(r.find("is a hider's policy (role hider), not a seeker's"), std::string::npos) << r;
}

// Game v3's learning seeker has 7 actions (the two that turn while moving): its actor, its
// architecture string and its checkpoint say so, and a loader asking for another count refuses it.
TEST(Checkpoint, TheActionCountIsPartOfTheArchitecture) {
  HiderNet seeker(84, 84, NetworkKind::kFeedForward, 7);
  EXPECT_EQ(seeker->forward(randomImages(2, 84, 84)).logits.sizes(), (std::vector<int64_t>{2, 7}));
  EXPECT_EQ(seeker->architecture(),
            "hideseek_hider/v1: conv8x8s4x32-conv4x4s2x64-conv3x3s1x64-fc512 | actor fc512-7 | critic fc512-1 | "
            "leaky_relu");
  EXPECT_EQ(HiderNet(84, 84)->architecture(), kArchitecture);  // every hider's checkpoint still reads
  const auto parts = parseArchitecture(architectureName(NetworkKind::kGru, 7));
  ASSERT_TRUE(parts);
  EXPECT_EQ(parts->network, NetworkKind::kGru);
  EXPECT_EQ(parts->actions, 7);
  CheckpointInfo info{seeker->architecture(), 84, 84, "basic", 10};
  info.role = "seeker";
  info.game = "v3";
  const std::string path = tempPath("seeker7.pt");
  saveCheckpoint(path, seeker, info);
  CheckpointInfo loaded;
  HiderNet back = loadCheckpoint(path, 84, 84, &loaded, std::nullopt, "seeker", 7);
  EXPECT_EQ(loaded.actions, 7);
  EXPECT_EQ(back->actions(), 7);
  const std::string e = errorOf([&] { loadCheckpoint(path, 84, 84, nullptr, std::nullopt, "seeker", 5); });
  EXPECT_NE(e.find("chooses among 7 actions, this game gives the seeker 5"), std::string::npos) << e;
  EXPECT_NE(errorOf([] { HiderNet(84, 84, NetworkKind::kFeedForward, 1); }).find("1 actions (2 to 16)"),
            std::string::npos);
}

TEST(Checkpoint, WrongImageSizeIsRefusedSayingWhy) {
  HiderNet net(64, 64);
  const std::string path = tempPath("small.pt");
  saveCheckpoint(path, net, infoFor(64, 64));
  const std::string e = errorOf([&] { loadCheckpoint(path, 84, 84); });
  EXPECT_NE(e.find("trained on 64x64 images, the world renders 84x84"), std::string::npos) << e;
}

TEST(Checkpoint, MismatchedTensorShapesAreRefused) {
  // Metadata claims 84x84 but the weights come from a 96x96 encoder.
  HiderNet net(96, 96);
  const std::string path = tempPath("lying.pt");
  saveCheckpoint(path, net, infoFor(84, 84));
  const std::string e = errorOf([&] { loadCheckpoint(path, 84, 84); });
  EXPECT_NE(e.find("does not match the network"), std::string::npos) << e;
}

TEST(Checkpoint, OtherArchitectureIsRefused) {
  HiderNet net(84, 84);
  const std::string path = tempPath("other.pt");
  CheckpointInfo info = infoFor(84, 84);
  info.architecture = "something else";
  saveCheckpoint(path, net, info);
  EXPECT_NE(errorOf([&] { loadCheckpoint(path, 84, 84); }).find("holds architecture 'something else'"),
            std::string::npos);
}

TEST(Checkpoint, TruncatedFileIsRefused) {
  HiderNet net(84, 84);
  const std::string path = tempPath("whole.pt"), cut = tempPath("cut.pt");
  saveCheckpoint(path, net, infoFor(84, 84));
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const std::string e = errorOf([&] { loadCheckpoint(cut, 84, 84); });
  EXPECT_NE(e.find("cut.pt"), std::string::npos) << e;
  EXPECT_FALSE(e.empty());
  EXPECT_NE(errorOf([&] { loadCheckpoint(tempPath("missing.pt"), 84, 84); }).find("cannot be read"), std::string::npos);
}

// One flipped byte inside the weights, which the archive format does not notice, is refused.
TEST(Checkpoint, FlippedByteIsRefusedByTheChecksum) {
  HiderNet net(84, 84);
  const std::string path = tempPath("flip_whole.pt"), bad = tempPath("flipped.pt");
  saveCheckpoint(path, net, infoFor(84, 84));
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The middle of the file lies in the 9 MB of the features layer's weights.
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
  std::ofstream(bad, std::ios::binary) << bytes;
  const std::string e = errorOf([&] { loadCheckpoint(bad, 84, 84); });
  EXPECT_NE(e.find("flipped.pt"), std::string::npos) << e;
  EXPECT_NE(e.find("checksum"), std::string::npos) << e;
  EXPECT_EQ(errorOf([&] { loadCheckpoint(path, 84, 84); }), "") << "the untouched file still loads";
}

TEST(HiderPolicy, RandomPolicyIsReproducibleAndUsesAllActions) {
  RandomHiderPolicy policy;
  std::vector<ArenaObservation> batch;
  for (uint32_t s = 0; s < 500; ++s) batch.push_back({nullptr, s, s % 7});
  const auto a = policy.act(batch), b = policy.act(batch);
  EXPECT_EQ(a, b);
  std::vector<int> counts(kActions);
  for (uint8_t x : a) counts.at(x)++;
  for (int c : counts) EXPECT_GT(c, 60);
}

TEST(HiderPolicy, NetworkPolicySamplesReproduciblyFromItsLogits) {
  HiderNet net(84, 84);
  NetworkHiderPolicy policy(net, torch::kCPU, false);
  const torch::Tensor images = randomImages(8, 84, 84);
  std::vector<ArenaObservation> batch;
  for (uint32_t i = 0; i < 8; ++i) batch.push_back({images.data_ptr<uint8_t>() + i * 84 * 84 * 3, 9, 4});
  EXPECT_EQ(policy.act(batch), policy.act(batch));
}

// Seed s must give the same episode with 1, 4 or 16 arenas: an arena's draw depends on its
// episode seed and step only, not on where the arena sits in the batch.
TEST(HiderPolicy, DrawsDependOnSeedAndStepNotOnTheArenaIndex) {
  HiderNet net(84, 84);
  NetworkHiderPolicy sampled(net, torch::kCPU, false);
  RandomHiderPolicy random;
  const torch::Tensor images = randomImages(16, 84, 84);
  std::vector<ArenaObservation> batch;
  for (uint32_t i = 0; i < 16; ++i) batch.push_back({images.data_ptr<uint8_t>() + i * 84 * 84 * 3, 100 + i, 7 * i});
  const auto all_random = random.act(batch), all_sampled = sampled.act(batch);
  for (uint32_t i = 0; i < 16; ++i) {
    EXPECT_EQ(random.act({batch[i]})[0], all_random[i]) << "arena " << i;
    EXPECT_EQ(sampled.act({batch[i]})[0], all_sampled[i]) << "arena " << i;
  }
  // Reordering the batch moves the answers with their episodes.
  std::vector<ArenaObservation> reversed(batch.rbegin(), batch.rend());
  const auto r = random.act(reversed);
  for (uint32_t i = 0; i < 16; ++i) EXPECT_EQ(r[15 - i], all_random[i]);
}

}  // namespace hideseek_hider
