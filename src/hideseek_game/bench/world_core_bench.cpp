// Throughput of the world core in one process: physics, labels and rendering of every arena.
// Prints `world_core_steps_per_s N` (arena-steps per second) for `make bench`.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "hideseek_game/world.h"

using hideseek_game::Action;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: world_core_bench GAME_YAML VARIANT_YAML [arenas=16] [seconds=5] [ppm_out]\n");
    return 2;
  }
  const int arenas = argc > 3 ? std::atoi(argv[3]) : 16;
  const double seconds = argc > 4 ? std::atof(argv[4]) : 5.0;
  const auto variant = hideseek_game::loadVariantConfig(argv[1], argv[2]);
  auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(variant.map_file));
  hideseek_game::World world(variant.game, map, arenas, 0, true);
  std::vector<uint8_t> images(world.imageBytes() * arenas);
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> action(0, hideseek_game::kNumActions - 1);

  auto run = [&](double budget) {
    long steps = 0;
    const auto start = std::chrono::steady_clock::now();
    double elapsed = 0.0;
    while (elapsed < budget) {
      for (int i = 0; i < arenas; ++i) world.stepArena(i, Action(action(rng)), Action(action(rng)));
      world.renderHiderViews(images.data());
      steps += arenas;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return steps / elapsed;
  };
  run(0.5);  // warm-up: llvmpipe compiles its shaders on first use
  const double rate = run(seconds);
  if (argc > 5) {
    FILE* f = std::fopen(argv[5], "wb");
    std::fprintf(f, "P6 %d %d 255\n", variant.game.camera.width, variant.game.camera.height);
    std::fwrite(images.data(), 1, world.imageBytes(), f);
    std::fclose(f);
  }
  std::printf("world_core_steps_per_s %.0f\n", rate);
  return 0;
}
