// A learning seeker, in process: the hider's trainer with the seeker's role, fed the seeker's own
// camera images and rewards (GameLoop with render_seeker), learns to catch a hider that stands
// still. After a few PPO updates it captures more often than the uniformly random seeker, on the
// same seeds.
// Small images (48 x 48) and short episodes keep it a few seconds of a make test.
#include <gtest/gtest.h>
#include <torch/torch.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "hideseek_game/agent.h"
#include "hideseek_game/game_loop.h"
#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/map.h"
#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_policy.h"
#include "hideseek_hider/training_run.h"

namespace hideseek_play {
namespace {

using hideseek_game::Action;
using hideseek_game::GameLoop;

const std::string kConfig = HIDESEEK_CONFIG_DIR;
constexpr int kArenas = 8;
constexpr int kSize = 48;

// Basic's rules in a small empty room (5 m x 5 m) with a long reach (1.5 m), where captures are
// frequent enough for a few updates to learn from: the agents spawn facing each other, so a
// seeker that goes for what it sees catches the hider sooner and more often than a random one.
hideseek_game::VariantConfig learningSeekerGame(const std::string& dir) {
  hideseek_game::VariantConfig v =
      hideseek_game::loadVariantConfig(kConfig + "/game.yaml", kConfig + "/variants/basic.yaml");
  v.game = hideseek_game::withLearnedSeeker(v.game);
  v.game.camera.width = v.game.camera.height = kSize;
  v.game.max_steps = 100;
  v.game.capture_distance = 1.5;  // a reach that a few good steps find, so that captures teach early
  v.game.min_spawn_distance = 2.5;
  std::filesystem::create_directories(dir);
  v.map_file = dir + "/room.yaml";
  std::ofstream(v.map_file) << "name: room\ntype: fixed\nhalf_extent: 2.5\nwall_height: 1.5\nobstacle_height: 1.5\n"
                               "obstacles: []\nwaypoints: [[-1.5, -1.5], [1.5, 1.5]]\n";
  return v;
}

std::shared_ptr<const hideseek_game::MapSpec> mapOf(const hideseek_game::VariantConfig& v) {
  return std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file));
}

GameLoop makeLoop(const hideseek_game::VariantConfig& v, uint32_t seed) {
  hideseek_game::GameLoopOptions o;
  o.num_arenas = kArenas;
  o.seed = seed;
  o.render_seeker = true;
  o.render_threads = 1;
  return GameLoop(v.game, mapOf(v), o);
}

// One step of every arena with the seeker's actions (decided once a step, from its images), the
// hider standing where it spawned, facing the seeker.
void play(GameLoop& loop, const std::vector<uint8_t>& seeker) {
  const std::vector<Action> hider(loop.numArenas(), Action::kStay);
  loop.step(hider,
            [&](int arena, const hideseek_game::SeekerPerception&) { return static_cast<Action>(seeker[arena]); });
}

// Captures in the first `episodes` episodes of the arenas (seeds seed .. seed + episodes - 1 when
// episodes is a multiple of the arenas), the seeker's actions from `decide`.
template <typename Decide>
int captures(const hideseek_game::VariantConfig& v, uint32_t seed, int episodes, Decide decide) {
  GameLoop loop = makeLoop(v, seed);
  int finished = 0, captured = 0;
  std::vector<int> per_arena(kArenas, 0);
  while (finished < episodes) {
    play(loop, decide(loop));
    for (int i = 0; i < kArenas; ++i) {
      if (!loop.done()[i] || per_arena[i] >= episodes / kArenas) continue;
      ++per_arena[i];
      ++finished;
      captured += loop.outcomes()[i] == static_cast<uint8_t>(hideseek_game::Outcome::kCaptured);
    }
  }
  return captured;
}

std::vector<uint32_t> seedsOf(const GameLoop& loop) {
  std::vector<uint32_t> s;
  for (int i = 0; i < loop.numArenas(); ++i) s.push_back(loop.world().arena(i).seed());
  return s;
}
std::vector<uint32_t> stepsOf(const GameLoop& loop) {
  std::vector<uint32_t> s;
  for (int i = 0; i < loop.numArenas(); ++i) s.push_back(static_cast<uint32_t>(loop.world().arena(i).stepCount()));
  return s;
}

}  // namespace

TEST(SeekerLearning, AFewUpdatesCaptureMoreThanTheRandomSeeker) {
  torch::set_num_threads(2);
  torch::manual_seed(0);
  const std::string dir = std::filesystem::temp_directory_path() / ("seeker_learning_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  const hideseek_game::VariantConfig v = learningSeekerGame(dir + "_map");
  const int actions = hideseek_game::actionCount(v.game, true);

  hideseek_hider::PpoOptions ppo = hideseek_hider::loadPpoOptions(kConfig + "/ppo.yaml");
  ppo.rollout_steps = 32;  // 8 arenas x 32 steps = 256 samples per update
  ppo.learning_rate = 1e-3;
  ppo.anneal_learning_rate = false;
  hideseek_hider::TrainingOptions t;
  t.output_dir = dir;
  t.total_steps = 256 * 36;  // 36 updates
  t.checkpoint_interval_s = 1e9;
  t.variant = v.name;
  t.game = v.game.name;
  t.image_height = t.image_width = kSize;
  t.role = "seeker";
  t.actions = actions;
  hideseek_hider::TrainingRun run(t, ppo, kArenas, torch::kCPU);
  // Training seeds 5000 on; the comparison below plays other seeds.
  GameLoop loop = makeLoop(v, 5000);
  while (!run.finished()) {
    std::optional<hideseek_hider::UpdateReport> report;
    const std::vector<uint8_t> seeker =
        run.step(loop.seekerImages().data(), loop.seekerRewards(), loop.done(), &report);
    if (report) {
      std::cout << "update " << report->update << ": " << report->episodes << " episodes, length "
                << report->mean_length << ", return " << report->mean_return << ", entropy " << report->ppo.entropy
                << "\n";
    }
    if (run.finished()) break;
    play(loop, seeker);
  }
  run.saveCheckpoint();

  // The trained seeker (sampled, as it trained) against the random seeker, both against the
  // standing hider on seeds 0-79.
  hideseek_hider::CheckpointInfo info;
  hideseek_hider::HiderNet net =
      hideseek_hider::loadCheckpoint(run.checkpointPath(), kSize, kSize, &info, std::nullopt, "seeker", actions);
  EXPECT_EQ(info.role, "seeker");
  hideseek_hider::NetworkHiderPolicy trained(net, torch::kCPU, false, hideseek_game::kSaltSampledSeekerPolicy);
  const int learned = captures(v, 0, 80, [&](const GameLoop& l) {
    std::vector<hideseek_hider::ArenaObservation> batch(kArenas);
    const auto seeds = seedsOf(l);
    const auto steps = stepsOf(l);
    for (int i = 0; i < kArenas; ++i) {
      batch[i] = {l.seekerImages().data() + i * static_cast<size_t>(kSize) * kSize * 3, seeds[i], steps[i], {}, {}};
    }
    return trained.act(batch);
  });
  const int random = captures(v, 0, 80, [&](const GameLoop& l) {
    std::vector<uint8_t> a(kArenas);
    const auto seeds = seedsOf(l);
    const auto steps = stepsOf(l);
    for (int i = 0; i < kArenas; ++i) {
      a[i] = hideseek_game::hashAction(seeds[i], steps[i], hideseek_game::kSaltRandomSeeker, actions);
    }
    return a;
  });
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(dir + "_map");
  EXPECT_GT(learned, random) << "captures in 80 episodes: trained " << learned << ", random " << random;
  std::cout << "captures in 80 episodes against a hider that stands: trained seeker " << learned << ", random seeker "
            << random << "\n";

  // The seeker's checkpoint is no hider's: a hider's loader refuses it, naming the roles.
  try {
    hideseek_hider::saveCheckpoint(dir + ".pt", net, info);
    hideseek_hider::loadCheckpoint(dir + ".pt", kSize, kSize);
    ADD_FAILURE() << "a hider loaded a seeker's checkpoint";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("is a seeker's policy (role seeker), not a hider's"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove(dir + ".pt");
}

}  // namespace hideseek_play
