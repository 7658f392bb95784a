// Analyses an existing recording (one made by analyze.launch, or any bag holding world/steps),
// without a ROS master.
// usage: analyze_bag [--game GAME] VARIANT POLICY BAG OUTPUT_DIR [REPORT_DIR]
//   GAME: the game the bag was played in (v2, v1, v3; none: config/games.yaml's default).
//   HIDESEEK_PIXEL_TOLERANCE (GRU policies): see analyze.launch's pixel_tolerance.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

#include "hideseek_analysis/analysis_job.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"

int main(int argc, char** argv) {
  std::string game;  // no --game: the default game (config/games.yaml)
  if (argc > 2 && std::string(argv[1]) == "--game") {
    game = argv[2];
    argv += 2;
    argc -= 2;
  }
  if (argc < 5 || argc > 6) {
    std::fprintf(stderr,
                 "usage: analyze_bag [--game GAME] VARIANT POLICY BAG OUTPUT_DIR [REPORT_DIR]\n"
                 "  writes the arrays to OUTPUT_DIR and the report to REPORT_DIR (default OUTPUT_DIR/report)\n");
    return 2;
  }
  try {
    hideseek_analysis::AnalysisJob job;
    job.variant = hideseek_game::selectGame(hideseek_game::configDirectory(), game, argv[1]).config;
    job.policy = argv[2];
    job.bag = argv[3];
    job.inputs_dir = argv[4];
    job.report_dir = argc > 5 ? argv[5] : job.inputs_dir + "/report";
    job.report_script = hideseek_game::packageExecutable("hideseek_analysis", "report.py");
    // GRU policies: a bag recorded with another Mesa may differ from its re-rendering by a level or two.
    if (const char* tolerance = std::getenv("HIDESEEK_PIXEL_TOLERANCE")) {
      char* end = nullptr;
      const long value = std::strtol(tolerance, &end, 10);
      if (end == tolerance || *end != '\0' || value < 0 || value > 255) {
        throw std::runtime_error(std::string("HIDESEEK_PIXEL_TOLERANCE is '") + tolerance +
                                 "': it must be a whole number from 0 to 255");
      }
      job.inputs.pixel_tolerance = static_cast<int>(value);
    }
    hideseek_analysis::runAnalysis(job);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "analyze_bag: %s\n", e.what());
    return 1;
  }
  return 0;
}
