// The calibration table: every scripted hider (the random hider and the evaders) on every variant
// (the files of config/variants/), over seeds 0..99 by default, beside the paper's random-hider
// living steps (config/paper_reference.yaml).
// Usage: calibration_table [--config DIR] [--game GAME|FILE] [--csv FILE] [--episodes N] [--first-seed S]
//                          [--evaders random,backpedal,flee,hide,lap] [--lap-radius M] [--episodes-csv FILE]
//                          [VARIANT...]; --help lists the options.
// --lap-radius: the ring the lap evader aims for (m from the centre; default 5.5, game v2's outer ring).
// --game: the game: a name (v2, v1, v3; none: config/games.yaml's default) or a game file of one's own.
// --episodes-csv writes one variant's episodes of one evader (seed,living_steps,outcome) as
// evaluate.launch does.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "hideseek_game/command_line.h"
#include "hideseek_game/config_error.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_play/scripted_game.h"

namespace {

namespace hh = hideseek_hider;

constexpr double kTolerance = 0.20;  // the calibration target: the random hider within +-20 % of the paper

// A bad command line or output file: the message, and the exit status 2.
int usage(const std::string& why) {
  std::cerr << "calibration_table: " << why << " (--help lists the options)\n";
  return 2;
}

struct Options {
  std::string config_dir;  // --config DIR, else hideseek_game's installed config/
  std::string game_file, csv_path, episodes_csv_path;
  int episodes = 100;
  long first_seed = 0;
  std::vector<std::string> variants;
  std::vector<hh::EvaderKind> evaders{std::begin(hh::kAllEvaders), std::end(hh::kAllEvaders)};
  hh::EvaderOptions evader_options;
};

// The command line into `o`: std::nullopt to go on, else the exit status (--help: 0; a bad command
// line, named with the options: 2).
std::optional<int> parseArgs(int argc, char** argv, Options& o) {
  namespace po = boost::program_options;
  hideseek_game::CommandLine line;
  line.tool = "calibration_table";
  line.about =
      "calibration_table: every scripted hider (the random hider and the evaders) on every variant, beside the\n"
      "paper's random-hider living steps\n"
      "usage: calibration_table [--config DIR] [--game GAME|FILE] [--csv FILE] [--episodes N] [--first-seed S]\n"
      "                         [--evaders random,backpedal,flee,hide,lap] [--lap-radius M] [--episodes-csv FILE] "
      "[VARIANT...]";
  std::string evaders;
  line.options.add_options()                                                                                  //
      ("config", po::value(&o.config_dir), "the config folder (default: hideseek_game's installed config/)")  //
      ("game", po::value(&o.game_file),
       "a game name (v2, v1, v3; none: config/games.yaml's default) or a game file")  //
      ("csv", po::value(&o.csv_path), "also write the table as CSV")                  //
      ("episodes-csv", po::value(&o.episodes_csv_path),
       "write one variant's episodes of one evader (seed,living_steps,outcome) as evaluate.launch does")      //
      ("episodes", po::value(&o.episodes)->default_value(100), "episodes per variant and evader")             //
      ("first-seed", po::value(&o.first_seed)->default_value(0), "the first episode seed")                    //
      ("evaders", po::value(&evaders), "comma-separated: random, backpedal, flee, hide, lap (default: all)")  //
      ("lap-radius", po::value(&o.evader_options.lap_radius)->default_value(o.evader_options.lap_radius),
       "the ring the lap evader aims for (m from the centre)")  //
      ("variant", po::value(&o.variants), "variants (default: every config/variants file)");
  line.positional.add("variant", -1);
  int exit_code = 0;
  if (!hideseek_game::parseCommandLine(argc, argv, line, &exit_code)) return exit_code;
  const auto fail = usage;
  if (o.episodes < 1) return fail("--episodes must be at least 1");
  if (o.first_seed < 0) return fail("--first-seed must not be negative");
  if (!(o.evader_options.lap_radius > 0.0)) return fail("--lap-radius must be positive (m)");
  if (!evaders.empty()) {
    o.evaders.clear();
    std::stringstream list(evaders);
    for (std::string name; std::getline(list, name, ',');) {
      const auto kind = hh::evaderKind(name);
      if (!kind) return fail("--evaders: unknown evader '" + name + "' (random, backpedal, flee, hide, lap)");
      o.evaders.push_back(*kind);
    }
  }
  return std::nullopt;
}

// The defaults that need the config directory: the game file and every variant.
void resolveDefaults(Options& o) {
  if (o.config_dir.empty()) o.config_dir = hideseek_game::configDirectory();
  o.game_file = hideseek_game::gameArgument(o.config_dir, o.game_file);
  if (o.variants.empty()) o.variants = hideseek_game::variantNames(o.config_dir + "/variants");
}

// One variant's episodes of one evader (seed,living_steps,outcome), as evaluate.launch writes them.
bool writeEpisodesCsv(const std::string& path, const std::vector<hideseek_play::ScriptedEpisode>& played) {
  std::ofstream rows(path);
  rows << "seed,living_steps,outcome\n";
  for (const auto& e : played)
    rows << e.seed << ',' << e.living_steps << ',' << (e.survived ? "survived" : "captured") << '\n';
  return static_cast<bool>(rows);
}

// One row of the table (stdout) and of the CSV, when one is written. `reference` is the paper's
// random-hider living steps, NaN where the paper lacks the variant ("-" in the table, empty in the CSV).
void writeRow(const std::string& variant, hh::EvaderKind evader, const hideseek_play::ScriptedSummary& s,
              double reference, std::ofstream& csv) {
  const bool has_reference = !std::isnan(reference);
  const double ratio = s.avg_living_steps / reference;
  char versus[64] = "", paper_column[16] = "-";
  if (has_reference) std::snprintf(paper_column, sizeof paper_column, "%.0f", reference);
  if (evader == hh::EvaderKind::kRandom && has_reference) {
    std::snprintf(versus, sizeof versus, "%.2f (%s +-20 %%)", ratio,
                  std::abs(ratio - 1.0) <= kTolerance ? "within" : "outside");
  }
  std::printf("| %s | %s | %.1f | %s | %s | %.0f %% | %.1f | %.0f %% |\n", variant.c_str(), hh::evaderName(evader),
              s.avg_living_steps, paper_column, versus, 100.0 * s.success_rate, s.median_living_steps,
              100.0 * s.seen_at_start_rate);
  std::fflush(stdout);
  if (!csv.is_open()) return;
  csv << variant << ',' << hh::evaderName(evader) << ',' << s.episodes << ',' << s.avg_living_steps << ',';
  if (has_reference)
    csv << reference << ',' << ratio;
  else
    csv << ',';
  csv << ',' << s.success_rate << ',' << s.median_living_steps << ',' << s.seen_at_start_rate << '\n';
}

// Every evader on every variant, into the table and the CSVs.
int playTable(const Options& o) {
  const YAML::Node paper = YAML::LoadFile(o.config_dir + "/paper_reference.yaml")["variants"];
  std::ofstream csv;
  if (!o.csv_path.empty()) {
    csv.open(o.csv_path);
    if (!csv) return usage("cannot write " + o.csv_path);
    csv << "variant,evader,episodes,avg_living_steps,paper_random_living_steps,ratio_to_paper,success_rate,"
           "median_living_steps,seen_at_step0\n";
  }
  std::printf("Scripted hiders, seeds %ld..%ld, at most the variant's max steps (game: %s)\n\n", o.first_seed,
              o.first_seed + o.episodes - 1, std::filesystem::path(o.game_file).filename().c_str());
  std::printf(
      "| variant | evader | avg living steps | paper (random) | here / paper | success | median living steps | "
      "seeker sees hider at step 0 |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const auto& name : o.variants) {
    const auto v = hideseek_game::loadVariantConfig(o.game_file, o.config_dir + "/variants/" + name + ".yaml");
    const auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file));
    const double reference = paper[name] ? paper[name]["living_random"].as<double>() : NAN;
    for (const hh::EvaderKind evader : o.evaders) {
      const auto played = hideseek_play::playScriptedHider(v, map, evader, static_cast<uint32_t>(o.first_seed),
                                                           o.episodes, {}, o.evader_options);
      if (!o.episodes_csv_path.empty() && !writeEpisodesCsv(o.episodes_csv_path, played)) {
        return usage("cannot write " + o.episodes_csv_path);
      }
      writeRow(name, evader, hideseek_play::summarize(played), reference, csv);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto exit_code = parseArgs(argc, argv, o)) return *exit_code;
  try {
    resolveDefaults(o);
  } catch (const std::exception& e) {
    std::cerr << "calibration_table: " << e.what() << " (or give --config DIR)\n";
    return 2;
  }
  if (!o.episodes_csv_path.empty() && (o.variants.size() != 1 || o.evaders.size() != 1)) {
    return usage("--episodes-csv needs exactly one variant and one evader");
  }
  try {
    return playTable(o);
  } catch (const hideseek_game::ConfigError& e) {
    std::cerr << "calibration_table: " << e.what() << '\n';
    return 1;
  } catch (const YAML::Exception& e) {
    std::cerr << "calibration_table: " << o.config_dir << "/paper_reference.yaml: " << e.what() << '\n';
    return 1;
  }
}
