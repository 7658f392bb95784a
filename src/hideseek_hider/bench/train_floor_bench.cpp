// The floor of training speed: the hider network and PPO update in one process on synthetic
// 84 x 84 observations (no ROS, no rendering).
// Usage: train_floor_bench CONFIG ARENAS UPDATES THREADS PRECISION(auto|fp32|bf16) [NETWORK(ff|gru)]
//        [MEMORY_FORMAT(auto|channels_last|nchw)]
// Prints `# precision: <reason>`, `# memory format: <reason>`, `# peak: <unit: formula>`, `# blas: ...`, `# per update:
// inference, update, other` (seconds per timed update, to set beside the hider's loop profile), then
// `train_floor_<fp32|bf16>_samples_per_s N` (ff) or `train_gru_<fp32|bf16>_samples_per_s N` (gru: recurrent PPO over
// sequences), loop_over_update (the timed loop's seconds over its PPO updates' seconds), and flops_per_sample (counted
// from the layers, trainingFlopsPerSample), gflops (achieved), peak_gflops and peak_fraction (over the peak of the unit
// the precision's kernels run on: the FMA units, or AMX-BF16 tiles in bf16 where the CPU has them; detectCpuPeak). The
// observations, rewards and done flags are drawn once, before the clock starts, and cycled: drawing 16 random images
// per step would be timed as training, which the graph does not pay.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "hideseek_game/heap.h"
#include "hideseek_hider/ppo.h"

int main(int argc, char** argv) {
  const std::string config = argc > 1 ? argv[1] : "config/ppo.yaml";
  const int arenas = argc > 2 ? std::atoi(argv[2]) : 16;
  const int updates = argc > 3 ? std::atoi(argv[3]) : 3;
  const int threads = argc > 4 ? std::atoi(argv[4]) : 2;
  const std::string precision = argc > 5 ? argv[5] : "auto";
  const hideseek_hider::NetworkKind network = hideseek_hider::parseNetwork(argc > 6 ? argv[6] : "ff", "NETWORK");
  const hideseek_hider::MemoryFormatRequest memory_format =
      hideseek_hider::parseMemoryFormat(argc > 7 ? argv[7] : "auto", "MEMORY_FORMAT");
  if (arenas < 1 || updates < 1 || threads < 1) {
    std::fprintf(stderr, "train_floor_bench: ARENAS, UPDATES and THREADS must be positive\n");
    return 2;
  }
  // As the hider node does (hideseek_game/heap.h); HIDESEEK_DEFAULT_HEAP=1 measures without it.
  const char* default_heap = std::getenv("HIDESEEK_DEFAULT_HEAP");
  if (!(default_heap && std::string(default_heap) == "1")) hideseek_game::keepFreedMemoryInHeap();
  torch::set_num_threads(threads);
  torch::manual_seed(0);
  const hideseek_hider::PrecisionChoice choice = hideseek_hider::choosePrecision(
      hideseek_hider::parsePrecision(precision, "PRECISION"), torch::kCPU, hideseek_hider::detectCpuBf16());
  const hideseek_hider::PpoOptions options = hideseek_hider::loadPpoOptions(config);
  hideseek_hider::HiderNet net(84, 84, network);
  net->setPrecision(choice.precision);
  const hideseek_hider::MemoryFormatChoice layout =
      hideseek_hider::chooseMemoryFormat(memory_format, choice.precision, hideseek_hider::detectCpuBf16());
  net->setMemoryFormat(layout.format);
  hideseek_hider::PpoTrainer trainer(net, options, arenas, torch::kCPU);
  // A pool of distinct batches, drawn before timing.
  constexpr int kPool = 8;
  std::vector<torch::Tensor> images, rewards, dones;
  for (int i = 0; i < kPool; ++i) {
    images.push_back(torch::randint(0, 256, {arenas, 84, 84, 3}, torch::kUInt8));
    rewards.push_back(torch::rand({arenas}) * 0.002);
    dones.push_back((torch::rand({arenas}) < 0.005).to(torch::kFloat32));
  }
  int next = 0;
  using Clock = std::chrono::steady_clock;
  double act_s = 0.0, update_s = 0.0;  // the timed updates' shares, as the hider's loop profile splits them
  auto run = [&](int n) {
    for (int u = 0; u < n; ++u) {
      bool full = false;
      while (!full) {
        const Clock::time_point t0 = Clock::now();
        trainer.act(images[next]);
        act_s += std::chrono::duration<double>(Clock::now() - t0).count();
        full = trainer.record(rewards[next], dones[next]);
        next = (next + 1) % kPool;
      }
      const Clock::time_point t0 = Clock::now();
      trainer.update(images[next]);
      update_s += std::chrono::duration<double>(Clock::now() - t0).count();
    }
  };
  run(1);  // warm-up
  act_s = update_s = 0.0;
  const int64_t before = trainer.samplesSeen();
  const auto start = std::chrono::steady_clock::now();
  run(updates);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double samples_per_s = (trainer.samplesSeen() - before) / seconds;
  const double flops = hideseek_hider::trainingFlopsPerSample(*net, options);
  const hideseek_hider::CpuPeak peak = hideseek_hider::detectCpuPeak(threads);
  std::printf("# precision: %s\n", choice.reason.c_str());
  std::printf("# memory format: %s\n", layout.reason.c_str());
  std::printf("# peak: %s\n", peak.describe(choice.precision).c_str());
  std::printf("# blas: %s\n", hideseek_hider::blasDescription().c_str());
  std::printf("# per update: inference %.3f s, update %.3f s, other %.3f s\n", act_s / updates, update_s / updates,
              (seconds - act_s - update_s) / updates);
  std::printf("%s_%s_samples_per_s %.0f\n", network == hideseek_hider::NetworkKind::kGru ? "train_gru" : "train_floor",
              hideseek_hider::precisionName(choice.precision), samples_per_s);
  // The whole loop's seconds over the PPO update's: with the graph's own update time it estimates the
  // floor at the graph's speed (make bench's train_efficiency_own_speed, experiments/throughput/measure_loop.sh).
  std::printf("loop_over_update %.4f\n", seconds / std::max(update_s, 1e-9));
  std::printf("flops_per_sample %.4g\n", flops);
  std::printf("gflops %.1f\n", flops * samples_per_s / 1e9);
  std::printf("peak_gflops %.1f\n", peak.gflops(choice.precision));
  std::printf("peak_fraction %.2f\n", flops * samples_per_s / 1e9 / peak.gflops(choice.precision));
  return 0;
}
