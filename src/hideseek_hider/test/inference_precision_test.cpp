// bf16 inference must act like fp32 inference: the shipped basic policy, run greedily in both
// precisions on 10,000 observations of its own games, picks the same action on >= 99 % of them.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/world.h"
#include "hideseek_hider/hider_net.h"

namespace hideseek_hider {

TEST(InferencePrecision, Bf16AndFp32PickTheSameGreedyActionOn99PercentOf10000Observations) {
  const std::string config = HIDESEEK_CONFIG_DIR;
  const auto variant = hideseek_game::loadVariantConfig(config + "/game.yaml", config + "/variants/basic.yaml");
  const auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(variant.map_file));
  constexpr int kArenas = 16, kObservations = 10000;
  hideseek_game::World world(variant.game, map, kArenas, 0, true, 1);
  const int h = variant.game.camera.height, w = variant.game.camera.width;

  HiderNet fp32 = loadCheckpoint(std::string(HIDESEEK_POLICY_DIR) + "/basic.pt", h, w);
  HiderNet bf16 = loadCheckpoint(std::string(HIDESEEK_POLICY_DIR) + "/basic.pt", h, w);
  bf16->setPrecision(Precision::kBf16);
  fp32->eval();
  bf16->eval();
  const torch::NoGradGuard no_grad;

  torch::Tensor images = torch::empty({kArenas, h, w, 3}, torch::kUInt8);
  int agree = 0, seen = 0;
  while (seen < kObservations) {
    world.renderHiderViews(images.data_ptr<uint8_t>());
    const torch::Tensor a = fp32->forward(images).logits.argmax(1);
    const torch::Tensor b = bf16->forward(images).logits.argmax(1);
    agree += (a == b).sum().item<int>();
    seen += kArenas;
    // The policy plays its own games (fp32 greedy) against a randomly walking seeker.
    for (int i = 0; i < kArenas; ++i) {
      const auto& arena = world.arena(i);
      const auto seeker = hideseek_game::hashAction(arena.seed(), static_cast<uint32_t>(arena.stepCount()), 0x5e);
      world.stepArena(i, static_cast<hideseek_game::Action>(a[i].item<int64_t>()),
                      static_cast<hideseek_game::Action>(seeker));
    }
  }
  const double agreement = static_cast<double>(agree) / seen;
  RecordProperty("agreement", std::to_string(agreement));
  EXPECT_GE(agreement, 0.99) << agree << " of " << seen << " greedy actions agree";
}

}  // namespace hideseek_hider
