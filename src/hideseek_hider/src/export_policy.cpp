// Writes the policy of a training checkpoint without its optimiser state: what a launch file
// ships and loads (a third of the size).
// usage: export_policy TRAINING_CHECKPOINT OUTPUT
//        export_policy --info CHECKPOINT     prints what the checkpoint holds, one line:
//                                            variant network steps wall_s episodes
#include <cstdio>
#include <exception>

#include "hideseek_game/command_line.h"
#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_net.h"

int main(int argc, char** argv) {
  namespace po = boost::program_options;
  std::string info_of, checkpoint, output;
  hideseek_game::CommandLine line;
  line.tool = "export_policy";
  line.about =
      "export_policy: writes the policy of a training checkpoint without its optimiser state\n"
      "usage: export_policy TRAINING_CHECKPOINT OUTPUT\n"
      "       export_policy --info CHECKPOINT   (prints: variant network steps wall_s episodes)";
  line.options.add_options()                                                                                         //
      ("info", po::value(&info_of), "print what CHECKPOINT holds, one line: variant network steps wall_s episodes")  //
      ("checkpoint", po::value(&checkpoint), "the training checkpoint")                                              //
      ("output", po::value(&output), "the policy file to write");
  line.positional.add("checkpoint", 1).add("output", 1);
  int exit_code = 0;
  if (!hideseek_game::parseCommandLine(argc, argv, line, &exit_code)) return exit_code;
  const bool info_only = !info_of.empty();
  if (info_only ? !(checkpoint.empty() && output.empty()) : (checkpoint.empty() || output.empty())) {
    std::fprintf(stderr, "export_policy: give TRAINING_CHECKPOINT and OUTPUT, or --info CHECKPOINT (--help)\n");
    return 2;
  }
  try {
    if (info_only) {
      const hideseek_hider::CheckpointInfo info = hideseek_hider::readCheckpointInfo(info_of);
      std::printf("%s %s %ld %.1f %ld\n", info.variant.c_str(), hideseek_hider::networkName(info.network),
                  static_cast<long>(info.steps), info.wall_s, static_cast<long>(info.episodes));
      return 0;
    }
    hideseek_hider::CheckpointInfo info = hideseek_hider::readCheckpointInfo(checkpoint);
    // Whichever role it is (a hider's or a seeker's), the policy keeps it.
    hideseek_hider::HiderNet net = hideseek_hider::loadCheckpoint(checkpoint, info.image_height, info.image_width,
                                                                  nullptr, std::nullopt, info.role, info.actions);
    // A shipped policy carries what it is, not the trainer's episode bookkeeping.
    info.recent_lengths.clear();
    info.recent_returns.clear();
    hideseek_hider::saveCheckpoint(output, net, info);
    std::printf("%s: %s policy, network %s, %dx%d images, %ld training steps\n", output.c_str(), info.variant.c_str(),
                hideseek_hider::networkName(info.network), info.image_height, info.image_width,
                static_cast<long>(info.steps));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "export_policy: %s\n", e.what());
    return 1;
  }
  return 0;
}
