// One rank of a data-parallel PPO training on synthetic rollouts (test/dd_ppo_synthetic.h), for
// the checks that need separate processes or hosts: a rank killed mid-run, and two ranks in two
// network namespaces. Prints "weights <sum> <sum of squares>" and writes the final weights to
// --out; a rank that fails prints the error and exits 3.
//   dd_ppo_check --rank R --world W --address HOST:PORT [--updates K] [--out FILE]
//                [--die-after U] [--freeze-after U] [--interface ADDR] [--timeout S] [--fingerprint KEY=VALUE]
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "dd_ppo_synthetic.h"

int main(int argc, char** argv) {
  using namespace hideseek_hider;  // NOLINT(google-build-using-namespace): a small test program
  RendezvousOptions r;
  r.world_size = 2;
  r.timeout_s = 30;
  r.fingerprint["check"] = "synthetic";
  int updates = 3, die_after = -1, freeze_after = -1;
  std::string out;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "dd_ppo_check: " << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--rank")
      r.rank = std::atoi(value().c_str());
    else if (a == "--world")
      r.world_size = std::atoi(value().c_str());
    else if (a == "--address")
      r.address = value();
    else if (a == "--updates")
      updates = std::atoi(value().c_str());
    else if (a == "--die-after")
      die_after = std::atoi(value().c_str());
    else if (a == "--freeze-after")
      freeze_after = std::atoi(value().c_str());
    else if (a == "--interface")
      r.interface_host = value();
    else if (a == "--timeout")
      r.timeout_s = std::atof(value().c_str());
    else if (a == "--out")
      out = value();
    else if (a == "--fingerprint") {
      const std::string kv = value();
      r.fingerprint[kv.substr(0, kv.find('='))] = kv.substr(kv.find('=') + 1);
    } else {
      std::cerr << "dd_ppo_check: unknown argument " << a << "\n";
      return 2;
    }
  }
  torch::set_num_threads(1);
  try {
    std::unique_ptr<Collective> c = joinRanks(r);
    const torch::Tensor w = trainSynthetic(SyntheticSetup{}, c.get(), r.rank, updates, nullptr, nullptr, [&](int u) {
      std::cout << "rank " << r.rank << ": update " << u << " done" << std::endl;
      if (u == die_after) {
        std::cout << "rank " << r.rank << ": killing itself" << std::endl;
        kill(getpid(), SIGKILL);
      }
      if (u == freeze_after) {
        std::cout << "rank " << r.rank << ": freezing" << std::endl;
        kill(getpid(), SIGSTOP);  // every thread stops, its heartbeat too: a hung host
      }
    });
    std::printf("weights %.9g %.9g\n", w.sum().item<double>(), w.pow(2).sum().item<double>());
    if (!out.empty()) torch::save(w, out);
  } catch (const std::exception& e) {
    std::cout << "rank " << r.rank << " failed: " << e.what() << std::endl;
    return 3;
  }
  return 0;
}
