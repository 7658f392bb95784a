// The time of one gradient all-reduce of the hider's network between two ranks (make bench):
// both ranks in this process, a thread each, over c10d's Gloo on loopback, each averaging a full
// set of the feed-forward network's gradients (averageGradients, as every PPO minibatch does).
// Prints the gradient's bytes and the median milliseconds of ROUNDS all-reduces.
//   allreduce_bench [ROUNDS] [PORT]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <vector>

#include "hideseek_hider/collective.h"
#include "hideseek_hider/hider_net.h"

int main(int argc, char** argv) {
  using namespace hideseek_hider;  // NOLINT(google-build-using-namespace): a small bench program
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 20;
  const int port = argc > 2 ? std::atoi(argv[2]) : 29671;
  torch::set_num_threads(1);
  auto rank = [&](int r) {
    RendezvousOptions o;
    o.world_size = 2;
    o.rank = r;
    o.address = "127.0.0.1:" + std::to_string(port);
    o.timeout_s = 60;
    std::unique_ptr<Collective> c = joinRanks(o);
    HiderNet net(84, 84);
    for (torch::Tensor& p : net->parameters()) p.mutable_grad() = torch::randn_like(p);
    std::vector<double> ms;
    for (int i = 0; i < rounds + 2; ++i) {
      const auto start = std::chrono::steady_clock::now();
      averageGradients(*c, net->parameters());
      const double t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      if (i >= 2) ms.push_back(t);  // two to warm up
    }
    std::sort(ms.begin(), ms.end());
    int64_t bytes = 0;
    for (const torch::Tensor& p : net->parameters()) bytes += p.numel() * 4;
    return std::make_pair(ms[ms.size() / 2], bytes);
  };
  try {
    auto r0 = std::async(std::launch::async, rank, 0), r1 = std::async(std::launch::async, rank, 1);
    const auto [ms, bytes] = r0.get();
    r1.get();
    std::printf("gradient_bytes %lld\nallreduce_ms %.2f\n", static_cast<long long>(bytes), ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "allreduce_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
