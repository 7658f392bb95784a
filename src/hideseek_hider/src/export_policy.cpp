// Writes the policy of a training checkpoint without its optimiser state: what a launch file
// ships and loads (a third of the size).
// usage: export_policy TRAINING_CHECKPOINT OUTPUT
//        export_policy --info CHECKPOINT     prints what the checkpoint holds, one line:
//                                            variant network steps wall_s episodes
#include <cstdio>
#include <cstring>
#include <exception>

#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_net.h"

int main(int argc, char** argv) {
  const bool info_only = argc == 3 && std::strcmp(argv[1], "--info") == 0;
  if (argc != 3) {
    std::fprintf(stderr,
                 "usage: export_policy TRAINING_CHECKPOINT OUTPUT\n"
                 "       export_policy --info CHECKPOINT   (prints: variant network steps wall_s episodes)\n");
    return 2;
  }
  try {
    if (info_only) {
      const hideseek_hider::CheckpointInfo info = hideseek_hider::readCheckpointInfo(argv[2]);
      std::printf("%s %s %ld %.1f %ld\n", info.variant.c_str(), hideseek_hider::networkName(info.network),
                  static_cast<long>(info.steps), info.wall_s, static_cast<long>(info.episodes));
      return 0;
    }
    hideseek_hider::CheckpointInfo info = hideseek_hider::readCheckpointInfo(argv[1]);
    hideseek_hider::HiderNet net = hideseek_hider::loadCheckpoint(argv[1], info.image_height, info.image_width);
    // A shipped policy carries what it is, not the trainer's episode bookkeeping.
    info.recent_lengths.clear();
    info.recent_returns.clear();
    hideseek_hider::saveCheckpoint(argv[2], net, info);
    std::printf("%s: %s policy, network %s, %dx%d images, %ld training steps\n", argv[2], info.variant.c_str(),
                hideseek_hider::networkName(info.network), info.image_height, info.image_width,
                static_cast<long>(info.steps));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "export_policy: %s\n", e.what());
    return 1;
  }
  return 0;
}
