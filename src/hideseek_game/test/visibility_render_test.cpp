#include <gtest/gtest.h>

#include <random>

#include "hideseek_game/visibility.h"
#include "hideseek_game/world.h"
#include "test_util.h"

namespace hideseek_game {

namespace {

// Random states where the agents stand anywhere free, facing anywhere.
void randomState(const Layout& layout, const GameOptions& g, std::mt19937& rng, AgentState& a, AgentState& b) {
  std::uniform_real_distribution<double> pos(-layout.half_extent + g.agent_radius, layout.half_extent - g.agent_radius);
  std::uniform_real_distribution<double> yaw(-kPi, kPi);
  auto fits = [&](Vec2 p) {
    for (const Box& box : layout.obstacles) {
      if (footprintDistance(box, p) < g.agent_radius) return false;
    }
    return true;
  };
  do {
    a.position = {pos(rng), pos(rng)};
  } while (!fits(a.position));
  do {
    b.position = {pos(rng), pos(rng)};
  } while (!fits(b.position) || distance(a.position, b.position) < g.capture_distance);
  a.yaw = yaw(rng);
  b.yaw = yaw(rng);
}

}  // namespace

// SPEC: the geometric visibility must agree with "B covers at least one pixel of A's image".
TEST(VisibilityVsRendering, AgreeOnAtLeast99PercentOfRandomStates) {
  for (const std::string variant : {"basic", "stochasticmaps"}) {
    const VariantConfig v = test::loadVariant(variant);
    auto map = std::make_shared<const MapSpec>(loadMapFile(v.map_file));
    Renderer renderer(rendererOptionsFor(v.game, map->colors, 1));
    std::mt19937 rng(2024);
    std::vector<uint8_t> image(renderer.imageBytes());
    int agree = 0, visible = 0, only_geometric = 0, only_pixels = 0;
    constexpr int kStates = 1000;
    Arena arena(v.game, map);
    for (int i = 0; i < kStates; ++i) {
      arena.reset(static_cast<uint32_t>(i));  // a fresh layout for stochastic maps
      renderer.setScene(0, arena.layout());
      AgentState viewer, target;
      randomState(arena.layout(), v.game, rng, viewer, target);
      renderer.render({{0, viewer, target, true}}, RenderMode::kSegmentation, image.data());
      bool pixel = false;
      for (size_t p = 0; p < image.size() && !pixel; p += 3) pixel = image[p] > 128;
      const bool geometric = agentSeesAgent(viewer, target, arena.layout(), v.game);
      agree += pixel == geometric;
      only_geometric += geometric && !pixel;
      only_pixels += pixel && !geometric;
      visible += pixel;
    }
    EXPECT_GE(agree, 990) << variant << ": agreement " << agree << " / " << kStates << " (seen only geometrically "
                          << only_geometric << ", only in pixels " << only_pixels << ")";
    // Both outcomes must be common, or agreement would say little.
    EXPECT_GT(visible, 100) << variant;
    EXPECT_LT(visible, 900) << variant;
  }
}

TEST(Rendering, ImagesShowTheOtherAgentInItsColour) {
  const VariantConfig v = test::loadVariant("basic");
  auto map = test::loadMap("deterministic");
  World world(v.game, map, 1, 0, true);
  Renderer renderer(test::rendererOptions(v, *map));
  // Find a seed where the hider sees the seeker at the start; render the view with the seeker and
  // with the seeker moved behind the hider: the pixels that differ are the seeker's, and they are
  // in its colours (red body, yellow front: far redder than blue, even through the haze).
  for (uint32_t seed = 0; seed < 50; ++seed) {
    world.resetArena(0, seed);
    const Arena& a = world.arena(0);
    if (!a.labels().hider_sees_seeker) continue;
    renderer.setScene(0, a.layout());
    std::vector<uint8_t> with(world.imageBytes()), without(world.imageBytes());
    renderer.render({{0, a.hider(), a.seeker(), false}}, RenderMode::kColor, with.data());
    AgentState behind = a.hider();
    behind.position = behind.position - 0.5 * Vec2{std::cos(a.hider().yaw), std::sin(a.hider().yaw)};
    renderer.render({{0, a.hider(), behind, false}}, RenderMode::kColor, without.data());
    int differ = 0, reddish = 0;
    for (size_t p = 0; p < with.size(); p += 3) {
      if (with[p] == without[p] && with[p + 1] == without[p + 1] && with[p + 2] == without[p + 2]) continue;
      ++differ;
      reddish += with[p] > 1.5 * with[p + 2];
    }
    EXPECT_GT(differ, 0) << "seed " << seed;
    EXPECT_GE(reddish, 0.9 * differ) << "seed " << seed << ": " << reddish << " of " << differ;
    return;
  }
  FAIL() << "no seed in 0..49 starts with the seeker in view";
}

}  // namespace hideseek_game
