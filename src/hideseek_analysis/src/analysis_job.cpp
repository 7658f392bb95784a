#include "hideseek_analysis/analysis_job.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "hideseek_analysis/bag_reader.h"
#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_net.h"

namespace hideseek_analysis {

namespace {

// Single quotes for the shell, so that any path survives std::system.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

void runAnalysis(const AnalysisJob& job) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  std::filesystem::create_directories(job.inputs_dir);
  std::filesystem::create_directories(job.report_dir);

  const int h = job.variant.game.camera.height, w = job.variant.game.camera.width;
  hideseek_hider::CheckpointInfo info;
  hideseek_hider::HiderNet net = hideseek_hider::loadCheckpoint(job.policy, h, w, &info);
  // A bag names neither its variant nor its game: the analysis plays the ones it is given (the
  // random hider's baseline, the maps), which must be the recording's. A policy trained on others
  // may be what was recorded, but is more often a slip.
  if (!info.variant.empty() && (info.variant != job.variant.name || info.game != job.variant.game.name)) {
    std::fprintf(stderr,
                 "analysis: warning: %s was trained on variant '%s', game %s; this analysis is of variant '%s', game "
                 "%s (its random-hider baseline and maps are those): name the variant and game the bag was "
                 "recorded in\n",
                 job.policy.c_str(), info.variant.c_str(), info.game.c_str(), job.variant.name.c_str(),
                 job.variant.game.name.c_str());
  }

  std::printf("analysis: reading %s\n", job.bag.c_str());
  std::fflush(stdout);
  const StepLog log = readStepBag(job.bag);
  std::printf("analysis: %zu decisions of %d arenas (%zu steps), %ld images, no step missing\n", log.decisions(),
              log.numArenas(), log.records().size(), static_cast<long>(log.numImages()));
  std::printf(
      "analysis: features of %ld images through %s (network %s, %ld training steps) and a random network "
      "(seed %u)%s\n",
      static_cast<long>(log.numImages()), job.policy.c_str(), hideseek_hider::networkName(net->network()),
      static_cast<long>(info.steps), job.inputs.random_init_seed,
      net->recurrent() ? "; GRU states of every step, re-rendered from the recorded poses" : "");
  std::fflush(stdout);
  const AnalysisInputsSummary s = writeAnalysisInputs(
      log, net, job.variant,
      std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(job.variant.map_file)), job.inputs,
      job.inputs_dir);
  if (net->recurrent()) {
    std::printf(
        "analysis: GRU states replayed; %ld recorded images match their re-rendering (largest pixel "
        "difference %d)\n",
        static_cast<long>(s.memory_images_compared), s.max_pixel_difference);
  }
  std::printf("analysis: %zu episodes; random policy: %zu steps in %zu episodes; inputs in %s (%.0f s)\n", s.episodes,
              s.random_steps, s.random_episodes, job.inputs_dir.c_str(), elapsed());
  std::fflush(stdout);

  const std::string command = "/usr/bin/python3 " + quoted(job.report_script) + " " + quoted(job.inputs_dir) + " " +
                              quoted(job.report_dir) + " --variant " + quoted(job.variant.name) + " --policy " +
                              quoted(std::filesystem::path(job.policy).filename().string()) + " --steps " +
                              std::to_string(info.steps) + " --tsne-samples " + std::to_string(job.tsne_samples) +
                              " --probe-splits " + std::to_string(job.probe_splits);
  const int status = std::system(command.c_str());
  if (status != 0) throw std::runtime_error("the report (" + job.report_script + ") failed; see its output above");
  std::printf("analysis: report in %s (%.0f s in all)\n", job.report_dir.c_str(), elapsed());
}

}  // namespace hideseek_analysis
