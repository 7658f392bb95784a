// Analyses an existing recording (one made by analyze.launch, or any bag holding world/steps),
// without a ROS master.
// usage: analyze_bag [--game GAME] [--variant-config FILE] VARIANT POLICY BAG OUTPUT_DIR [REPORT_DIR], or the
//   same as named options (--help lists them).
//   GAME: the game the bag was played in (v2, v1, v3; none: config/games.yaml's default).
//   FILE: a variant file of one's own, named VARIANT (none: config/variants/VARIANT.yaml).
//   HIDESEEK_PIXEL_TOLERANCE (GRU policies): see analyze.launch's pixel_tolerance.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

#include "hideseek_analysis/analysis_job.h"
#include "hideseek_game/command_line.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"

int main(int argc, char** argv) {
  namespace po = boost::program_options;
  // No --game: config/games.yaml's default; no --variant-config: the project's variant file.
  std::string game, variant, variant_config, policy, bag, output_dir, report_dir;
  hideseek_game::CommandLine line;
  line.tool = "analyze_bag";
  line.about =
      "analyze_bag: analyses a recording (analyze.launch's, or any bag holding world/steps) without a ROS master\n"
      "usage: analyze_bag [--game GAME] [--variant-config FILE] --variant VARIANT --policy POLICY --bag BAG "
      "--output OUTPUT_DIR [--report REPORT_DIR]\n"
      "   or: analyze_bag [--game GAME] [--variant-config FILE] VARIANT POLICY BAG OUTPUT_DIR [REPORT_DIR]";
  line.options.add_options()                                                                                          //
      ("game", po::value(&game), "the game the bag was played in: v2, v1 or v3 (none: config/games.yaml's default)")  //
      ("variant", po::value(&variant)->required(), "the variant")                                                     //
      ("variant-config", po::value(&variant_config),
       "a variant file of one's own, named VARIANT (none: the project's config/variants/VARIANT.yaml)")  //
      ("policy", po::value(&policy)->required(),
       "the checkpoint the bag recorded (its network gives the features; random and scripted hiders have none)")  //
      ("bag", po::value(&bag)->required(), "the recording")                                                       //
      ("output", po::value(&output_dir)->required(), "where the arrays go")                                       //
      ("report", po::value(&report_dir), "where the report goes (default: OUTPUT_DIR/report)");
  line.positional.add("variant", 1).add("policy", 1).add("bag", 1).add("output", 1).add("report", 1);
  int exit_code = 0;
  if (!hideseek_game::parseCommandLine(argc, argv, line, &exit_code)) return exit_code;
  try {
    hideseek_analysis::AnalysisJob job;
    job.variant = hideseek_game::selectGame(hideseek_game::configDirectory(), game, variant, variant_config).config;
    job.policy = policy;
    job.bag = bag;
    job.inputs_dir = output_dir;
    job.report_dir = report_dir.empty() ? job.inputs_dir + "/report" : report_dir;
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
