#include "hideseek_analysis/analysis_inputs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/world.h"
#include "hideseek_seeker/seeker_policy.h"

namespace hideseek_analysis {
namespace {

namespace hw = hideseek_game;
const std::string kConfig = HIDESEEK_CONFIG_DIR;

hw::VariantConfig variant(const std::string& name) {
  return hw::loadVariantConfig(kConfig + "/game.yaml", kConfig + "/variants/" + name + ".yaml");
}

std::shared_ptr<const hw::MapSpec> mapOf(const hw::VariantConfig& v) {
  return std::make_shared<const hw::MapSpec>(hw::loadMapFile(v.map_file));
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

size_t lines(const std::string& path) {
  const std::string s = slurp(path);
  return static_cast<size_t>(std::count(s.begin(), s.end(), '\n'));
}

struct TempDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("hideseek_analysis_test_" + std::to_string(::getpid()) + "_" +
                                                ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { std::filesystem::create_directories(path); }
  ~TempDir() { std::filesystem::remove_all(path); }
};

TEST(WriteNpy, WritesAFileNumpyReads) {
  TempDir dir;
  const float data[6] = {1, 2, 3, 4, 5, -6.5f};
  writeNpy((dir.path / "a.npy").string(), data, 3, 2);
  const std::string s = slurp((dir.path / "a.npy").string());
  ASSERT_GE(s.size(), 10u);
  EXPECT_EQ(s.substr(0, 6), "\x93NUMPY");
  const size_t header = static_cast<uint8_t>(s[8]) | static_cast<uint8_t>(s[9]) << 8;
  EXPECT_EQ((10 + header) % 64, 0u);  // the format's alignment
  EXPECT_NE(s.find("'descr': '<f4', 'fortran_order': False, 'shape': (3, 2)"), std::string::npos);
  ASSERT_EQ(s.size(), 10 + header + sizeof(data));
  EXPECT_EQ(std::memcmp(s.data() + 10 + header, data, sizeof(data)), 0);
}

TEST(ExtractFeatures, GivesTheNetworksFeaturesWhateverTheBatch) {
  torch::manual_seed(3);
  hideseek_hider::HiderNet net(84, 84);
  const torch::Tensor images = torch::randint(0, 256, {5, 84, 84, 3}, torch::kUInt8);
  const torch::Tensor one_pass = extractFeatures(net, images.data_ptr<uint8_t>(), 5, 84, 84, 256);
  const torch::Tensor batched = extractFeatures(net, images.data_ptr<uint8_t>(), 5, 84, 84, 2);
  ASSERT_EQ(one_pass.sizes(), (std::vector<int64_t>{5, hideseek_hider::kFeatures}));
  EXPECT_TRUE(torch::allclose(one_pass, batched, 1e-5, 1e-5));
  torch::NoGradGuard no_grad;
  EXPECT_TRUE(torch::allclose(one_pass, net->forward(images).features, 1e-5, 1e-5));
}

// A short rollout of the random hider on two rendered arenas, logged as the world node does:
// the state before each decision (image every 5th decision), then the actions and results. The
// log starts at decision `first`; `all_images`, when given, receives every decision's images.
StepLog rollout(const hw::VariantConfig& v, std::shared_ptr<const hw::MapSpec> map, int decisions, int first = 0,
                std::vector<std::vector<uint8_t>>* all_images = nullptr, int image_every = 5) {
  const int n = 2;
  hw::World world(v.game, map, n, 10000, true, 1);
  std::vector<hideseek_seeker::SeekerPolicy> seekers;
  for (int i = 0; i < n; ++i) {
    seekers.emplace_back(hideseek_seeker::seekerOptionsFor(v));
    seekers.back().reset(world.arena(i).layout(), world.arena(i).seed());
  }
  std::vector<uint8_t> images(world.imageBytes() * n);
  StepLog log;
  for (int d = 0; d < decisions; ++d) {
    world.renderHiderViews(images.data());
    if (all_images && d >= first) all_images->push_back(images);
    DecisionRecord r;
    r.decision = static_cast<uint64_t>(d);
    if (image_every > 0 && d % image_every == 0) {
      r.height = v.game.camera.height;
      r.width = v.game.camera.width;
      r.images = images;
    }
    for (int i = 0; i < n; ++i) {
      const hw::Arena& a = world.arena(i);
      ArenaStepRecord s;
      s.seed = a.seed();
      s.step = static_cast<uint32_t>(a.stepCount());
      s.hider_x = a.hider().position.x;
      s.hider_y = a.hider().position.y;
      s.seeker_x = a.seeker().position.x;
      s.seeker_y = a.seeker().position.y;
      s.hider_yaw = a.hider().yaw;
      s.seeker_yaw = a.seeker().yaw;
      s.hider_sees_seeker = a.labels().hider_sees_seeker;
      s.seeker_sees_hider = a.labels().seeker_sees_hider;
      const auto hider = static_cast<hw::Action>(hw::hashAction(a.seed(), s.step, hw::kSaltRandomHider));
      const hw::ArenaStep step =
          world.stepArena(i, hider, [&](const hw::SeekerPerception& p) { return seekers[i].act(p); });
      s.outcome = static_cast<int>(step.result.outcome);
      if (step.finished) seekers[i].reset(world.arena(i).layout(), world.arena(i).seed());
      r.arenas.push_back(s);
    }
    if (d >= first) log.append(r);
  }
  return log;
}

TEST(WriteAnalysisInputs, WritesEveryArrayTheReportReads) {
  TempDir dir;
  const auto v = variant("basic");
  const auto map = mapOf(v);
  const StepLog log = rollout(v, map, 150);
  torch::manual_seed(1);
  hideseek_hider::HiderNet net(v.game.camera.height, v.game.camera.width);
  AnalysisInputsOptions options;
  options.batch = 32;
  const auto s = writeAnalysisInputs(log, net, v, map, options, dir.path.string());
  EXPECT_EQ(s.steps, 300u);
  EXPECT_EQ(s.images, 60);
  EXPECT_GE(s.random_steps, 300u);
  ASSERT_FALSE(s.trajectory_seeds.empty());  // random hiders are caught within 150 steps
  const std::string d = dir.path.string() + "/";
  EXPECT_EQ(lines(d + "steps_trained.csv"), 301u);
  EXPECT_EQ(lines(d + "steps_random.csv"), s.random_steps + 1);
  EXPECT_EQ(lines(d + "features.csv"), 61u);
  for (const char* f : {"features_trained.npy", "features_random.npy"}) {
    const std::string npy = slurp(d + f);
    EXPECT_NE(npy.find("'shape': (60, 512)"), std::string::npos) << f;
  }
  // The random network differs from the trained one: its features are not the same numbers.
  EXPECT_NE(slurp(d + "features_trained.npy"), slurp(d + "features_random.npy"));
  EXPECT_NE(slurp(d + "layouts.csv").find("\n" + std::to_string(s.trajectory_seeds[0]) + ","), std::string::npos);
}

// A recording without images (record_images:=false) is refused by name before anything is written.
TEST(WriteAnalysisInputs, RefusesARecordingWithoutImages) {
  TempDir dir;
  const auto v = variant("basic");
  const auto map = mapOf(v);
  const StepLog log = rollout(v, map, 40, 0, nullptr, 0);
  hideseek_hider::HiderNet net(v.game.camera.height, v.game.camera.width);
  try {
    writeAnalysisInputs(log, net, v, map, {}, dir.path.string());
    FAIL() << "a recording without images was analysed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no hider image (recorded with record_images:=false"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}

TEST(WriteAnalysisInputs, RefusesARecordingOfAnotherMap) {
  TempDir dir;
  const auto basic = variant("basic");
  const auto map = mapOf(basic);
  const StepLog log = rollout(basic, map, 150);
  const auto other = variant("stochasticmaps");
  const auto other_map = mapOf(other);
  hideseek_hider::HiderNet net(basic.game.camera.height, basic.game.camera.width);
  try {
    writeAnalysisInputs(log, net, other, other_map, {}, dir.path.string());
    FAIL() << "a recording of the deterministic map was analysed as stochasticmaps";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("another variant or map"), std::string::npos) << e.what();
  }
}

// The GRU state of every recorded image, replayed from the log, is the state the network reaches
// when it runs over every image of the rollout step by step (as the hider node does), with its
// state zeroed at each episode start; and every recorded image is re-rendered exactly.
TEST(ReplayMemory, GivesTheStateOfAStepByStepRunOverEveryImage) {
  const auto v = variant("basic");
  const auto map = mapOf(v);
  std::vector<std::vector<uint8_t>> all;
  const StepLog log = rollout(v, map, 150, 0, &all);
  torch::manual_seed(5);
  hideseek_hider::HiderNet net(v.game.camera.height, v.game.camera.width, hideseek_hider::NetworkKind::kGru);
  const MemoryReplay replay = replayMemory(log, {&net}, v, map, 0, 1);
  EXPECT_EQ(replay.images_compared, 60);
  EXPECT_EQ(replay.max_pixel_difference, 0);
  ASSERT_EQ(replay.memory.size(), 1u);
  ASSERT_EQ(replay.memory[0].sizes(), (std::vector<int64_t>{60, hideseek_hider::kHidden}));

  torch::NoGradGuard no_grad;
  const int n = log.numArenas(), h = v.game.camera.height, w = v.game.camera.width;
  torch::Tensor hidden = net->initialHidden(n);
  size_t episode_starts_inside = 0;
  for (size_t d = 0; d < log.decisions(); ++d) {
    torch::Tensor starts = torch::zeros({1, n});
    for (int i = 0; i < n; ++i) {
      if (log.records()[d * n + i].step == 0) {
        starts[0][i] = 1.0;
        episode_starts_inside += d > 0;
      }
    }
    const torch::Tensor images = torch::from_blob(all[d].data(), {1, n, h, w, 3}, torch::kUInt8);
    const torch::Tensor memory = net->forwardSequence(images, hidden, starts, &hidden).memory[0];
    for (int i = 0; i < n; ++i) {
      const int64_t image = log.records()[d * n + i].image;
      if (image >= 0) {
        ASSERT_TRUE(torch::allclose(replay.memory[0][image], memory[i], 1e-5, 1e-5))
            << "decision " << d << ", arena " << i;
      }
    }
  }
  EXPECT_GT(episode_starts_inside, 0u);  // random hiders are caught: states were reset inside the log
  // The state carries memory: it is not the state a fresh episode would have for the same image.
  const torch::Tensor fresh = net->forwardSequence(torch::from_blob(all[149].data(), {1, n, h, w, 3}, torch::kUInt8),
                                                   net->initialHidden(n), torch::ones({1, n}))
                                  .memory[0];
  EXPECT_FALSE(torch::allclose(hidden, fresh, 1e-3, 1e-3));
}

TEST(ReplayMemory, RefusesARecordingOfAnotherMap) {
  const auto basic = variant("basic");
  const auto map = mapOf(basic);
  const StepLog log = rollout(basic, map, 30);
  const auto other = variant("stochasticmaps");
  const auto other_map = mapOf(other);
  hideseek_hider::HiderNet net(basic.game.camera.height, basic.game.camera.width, hideseek_hider::NetworkKind::kGru);
  try {
    replayMemory(log, {&net}, other, other_map, 0, 1);
    FAIL() << "a recording of the deterministic map was replayed in the stochastic maps";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("rendered again from the recorded poses differs"), std::string::npos)
        << e.what();
  }
}

TEST(ReplayMemory, RefusesALogThatStartsInsideAnEpisode) {
  const auto v = variant("basic");
  const auto map = mapOf(v);
  const StepLog log = rollout(v, map, 30, 10);
  hideseek_hider::HiderNet net(v.game.camera.height, v.game.camera.width, hideseek_hider::NetworkKind::kGru);
  try {
    replayMemory(log, {&net}, v, map, 0, 1);
    FAIL() << "a log starting at step 10 was replayed as if the GRU state were known";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("is logged from step 10"), std::string::npos) << e.what();
  }
}

TEST(WriteAnalysisInputs, WritesTheGruStatesOfARecurrentPolicy) {
  TempDir dir;
  const auto v = variant("basic");
  const auto map = mapOf(v);
  const StepLog log = rollout(v, map, 50);
  torch::manual_seed(2);
  hideseek_hider::HiderNet net(v.game.camera.height, v.game.camera.width, hideseek_hider::NetworkKind::kGru);
  const auto s = writeAnalysisInputs(log, net, v, map, {}, dir.path.string());
  EXPECT_EQ(s.memory_images_compared, 20);
  const std::string d = dir.path.string() + "/";
  for (const char* f : {"features_trained.npy", "features_random.npy", "memory_trained.npy", "memory_random.npy"}) {
    EXPECT_NE(slurp(d + f).find("'shape': (20, 512)"), std::string::npos) << f;
  }
  EXPECT_NE(slurp(d + "memory_trained.npy"), slurp(d + "memory_random.npy"));
  EXPECT_NE(slurp(d + "memory_trained.npy"), slurp(d + "features_trained.npy"));
}

}  // namespace
}  // namespace hideseek_analysis
