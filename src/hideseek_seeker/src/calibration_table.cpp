// The calibration table: every scripted hider (the random hider and the evaders) on every variant
// (the files of config/variants/), over seeds 0..99 by default, beside the paper's random-hider
// living steps (config/paper_reference.yaml).
// Usage: calibration_table [--config DIR] [--game FILE] [--csv FILE] [--episodes N] [--first-seed S]
//                          [--evaders random,backpedal,flee,hide,lap] [--lap-radius M] [--episodes-csv FILE]
//                          [VARIANT...]
// --lap-radius: the ring the lap evader aims for (m from the centre; default 5.5, game v2's outer ring).
// --game: the game file (default DIR/game.yaml; DIR/game_v1.yaml is the first game).
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
#include <sstream>
#include <string>
#include <vector>

#include "hideseek_game/config_error.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_seeker/scripted_game.h"

namespace {

constexpr double kTolerance = 0.20;  // the calibration target: the random hider within +-20 % of the paper

int usage(const std::string& why) {
  std::cerr << "calibration_table: " << why
            << "\nusage: calibration_table [--config DIR] [--game FILE] [--csv FILE] [--episodes N] [--first-seed S] "
               "[--evaders random,backpedal,flee,hide,lap] [--lap-radius M] [--episodes-csv FILE] [VARIANT...]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  namespace hs = hideseek_seeker;
  std::string config_dir;  // --config DIR, else hideseek_game's installed config/
  std::string game_file, csv_path, episodes_csv_path;
  int episodes = 100;
  long first_seed = 0;
  std::vector<std::string> variants;
  std::vector<hs::EvaderKind> evaders(std::begin(hs::kAllEvaders), std::end(hs::kAllEvaders));
  hs::EvaderOptions evader_options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--config" && has_value) {
      config_dir = argv[++i];
    } else if (a == "--game" && has_value) {
      game_file = argv[++i];
    } else if (a == "--csv" && has_value) {
      csv_path = argv[++i];
    } else if (a == "--episodes-csv" && has_value) {
      episodes_csv_path = argv[++i];
    } else if (a == "--episodes" && has_value) {
      episodes = std::atoi(argv[++i]);
      if (episodes < 1) return usage("--episodes must be at least 1");
    } else if (a == "--first-seed" && has_value) {
      first_seed = std::atol(argv[++i]);
      if (first_seed < 0) return usage("--first-seed must not be negative");
    } else if (a == "--lap-radius" && has_value) {
      evader_options.lap_radius = std::atof(argv[++i]);
      if (!(evader_options.lap_radius > 0.0)) return usage("--lap-radius must be positive (m)");
    } else if (a == "--evaders" && has_value) {
      evaders.clear();
      std::stringstream list(argv[++i]);
      for (std::string name; std::getline(list, name, ',');) {
        const auto kind = hs::evaderKind(name);
        if (!kind) return usage("--evaders: unknown evader '" + name + "' (random, backpedal, flee, hide, lap)");
        evaders.push_back(*kind);
      }
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option or missing value: " + a);
    } else {
      variants.push_back(a);
    }
  }
  if (config_dir.empty()) {
    try {
      config_dir = hideseek_game::configDirectory();
    } catch (const std::exception& e) {
      std::cerr << "calibration_table: " << e.what() << " (or give --config DIR)\n";
      return 2;
    }
  }
  if (game_file.empty()) game_file = config_dir + "/game.yaml";
  if (variants.empty()) variants = hideseek_game::variantNames(config_dir + "/variants");
  if (!episodes_csv_path.empty() && (variants.size() != 1 || evaders.size() != 1)) {
    return usage("--episodes-csv needs exactly one variant and one evader");
  }
  try {
    const YAML::Node paper = YAML::LoadFile(config_dir + "/paper_reference.yaml")["variants"];
    std::ofstream csv;
    if (!csv_path.empty()) {
      csv.open(csv_path);
      if (!csv) return usage("cannot write " + csv_path);
      csv << "variant,evader,episodes,avg_living_steps,paper_random_living_steps,ratio_to_paper,success_rate,"
             "median_living_steps,seen_at_step0\n";
    }
    std::printf("Scripted hiders, seeds %ld..%ld, at most the variant's max steps (game: %s)\n\n", first_seed,
                first_seed + episodes - 1, std::filesystem::path(game_file).filename().c_str());
    std::printf(
        "| variant | evader | avg living steps | paper (random) | here / paper | success | median living steps | "
        "seeker sees hider at step 0 |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (const auto& name : variants) {
      const auto v = hideseek_game::loadVariantConfig(game_file, config_dir + "/variants/" + name + ".yaml");
      const auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file));
      const double reference = paper[name] ? paper[name]["living_random"].as<double>() : NAN;
      for (const hs::EvaderKind evader : evaders) {
        const auto played =
            hs::playScriptedHider(v, map, evader, static_cast<uint32_t>(first_seed), episodes, {}, evader_options);
        const auto s = hs::summarize(played);
        if (!episodes_csv_path.empty()) {
          std::ofstream rows(episodes_csv_path);
          rows << "seed,living_steps,outcome\n";
          for (const auto& e : played)
            rows << e.seed << ',' << e.living_steps << ',' << (e.survived ? "survived" : "captured") << '\n';
          if (!rows) return usage("cannot write " + episodes_csv_path);
        }
        const bool random = evader == hs::EvaderKind::kRandom;
        // A variant the paper lacks has no reference: "-" in the table, empty in the CSV.
        const bool has_reference = !std::isnan(reference);
        const double ratio = s.avg_living_steps / reference;
        char versus[64] = "", paper_column[16] = "-";
        if (has_reference) std::snprintf(paper_column, sizeof paper_column, "%.0f", reference);
        if (random && has_reference) {
          std::snprintf(versus, sizeof versus, "%.2f (%s +-20 %%)", ratio,
                        std::abs(ratio - 1.0) <= kTolerance ? "within" : "outside");
        }
        std::printf("| %s | %s | %.1f | %s | %s | %.0f %% | %.1f | %.0f %% |\n", name.c_str(), hs::evaderName(evader),
                    s.avg_living_steps, paper_column, versus, 100.0 * s.success_rate, s.median_living_steps,
                    100.0 * s.seen_at_start_rate);
        std::fflush(stdout);
        if (csv) {
          csv << name << ',' << hs::evaderName(evader) << ',' << s.episodes << ',' << s.avg_living_steps << ',';
          if (has_reference)
            csv << reference << ',' << ratio;
          else
            csv << ',';
          csv << ',' << s.success_rate << ',' << s.median_living_steps << ',' << s.seen_at_start_rate << '\n';
        }
      }
    }
  } catch (const hideseek_game::ConfigError& e) {
    std::cerr << "calibration_table: " << e.what() << '\n';
    return 1;
  } catch (const YAML::Exception& e) {
    std::cerr << "calibration_table: " << config_dir << "/paper_reference.yaml: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
