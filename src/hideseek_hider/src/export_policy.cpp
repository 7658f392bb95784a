// Writes the policy of a training checkpoint without its optimiser state: what a launch file
// ships and loads (a third of the size). usage: export_policy TRAINING_CHECKPOINT OUTPUT
#include <cstdio>
#include <exception>

#include "hideseek_hider/hider_net.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: export_policy TRAINING_CHECKPOINT OUTPUT\n");
    return 2;
  }
  try {
    const hideseek_hider::CheckpointInfo info = hideseek_hider::readCheckpointInfo(argv[1]);
    hideseek_hider::HiderNet net = hideseek_hider::loadCheckpoint(argv[1], info.image_height, info.image_width);
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
