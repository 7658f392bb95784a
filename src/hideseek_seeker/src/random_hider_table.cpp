// The calibration table: the uniformly random hider on every variant, over seeds 0..99, beside
// the paper's random-hider living steps (config/paper_reference.yaml).
// Usage: random_hider_table [--config DIR] [--csv FILE] [--episodes N] [--first-seed S]
//                           [--episodes-csv FILE] [VARIANT...]
// --episodes-csv writes one variant's episodes (seed,living_steps,outcome) as evaluate.launch does.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "hideseek_seeker/random_hider_game.h"
#include "hideseek_world/config_error.h"

namespace {

const std::vector<std::string> kVariants = {"basic",          "fasterhider",      "slowerhider",
                                            "stochasticseeker", "stochasticmaps", "visibilityreward",
                                            "visibilityreward_faster"};
constexpr double kTolerance = 0.25;  // the calibration target: within +-25 % of the paper

int usage(const char* why) {
  std::cerr << "random_hider_table: " << why
            << "\nusage: random_hider_table [--config DIR] [--csv FILE] [--episodes N] [--first-seed S] "
               "[--episodes-csv FILE] [VARIANT...]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string config_dir = HIDESEEK_CONFIG_DIR;
  std::string csv_path, episodes_csv_path;
  int episodes = 100;
  long first_seed = 0;
  std::vector<std::string> variants;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--config" && has_value) {
      config_dir = argv[++i];
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
    } else if (!a.empty() && a[0] == '-') {
      return usage(("unknown option or missing value: " + a).c_str());
    } else {
      variants.push_back(a);
    }
  }
  if (variants.empty()) variants = kVariants;
  if (!episodes_csv_path.empty() && variants.size() != 1) return usage("--episodes-csv needs exactly one variant");
  try {
    const YAML::Node paper = YAML::LoadFile(config_dir + "/paper_reference.yaml")["variants"];
    std::ofstream csv;
    if (!csv_path.empty()) {
      csv.open(csv_path);
      if (!csv) return usage(("cannot write " + csv_path).c_str());
      csv << "variant,episodes,avg_living_steps,paper_living_steps,ratio_to_paper,within_25_percent,success_rate,"
             "median_living_steps,seen_at_step0\n";
    }
    std::printf("Random hider, seeds %ld..%ld, at most the variant's max steps\n\n", first_seed, first_seed + episodes - 1);
    std::printf("| variant | avg living steps | paper | here / paper | within +-25 %% | success | median living steps | seeker sees hider at step 0 |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (const auto& name : variants) {
      const auto v = hideseek_world::loadVariantConfig(config_dir + "/game.yaml", config_dir + "/variants/" + name + ".yaml");
      const auto map = std::make_shared<const hideseek_world::MapSpec>(hideseek_world::loadMapFile(v.map_file));
      const auto played = hideseek_seeker::playRandomHider(v, map, static_cast<uint32_t>(first_seed), episodes);
      const auto s = hideseek_seeker::summarize(played);
      if (!episodes_csv_path.empty()) {
        std::ofstream rows(episodes_csv_path);
        rows << "seed,living_steps,outcome\n";
        for (const auto& e : played) rows << e.seed << ',' << e.living_steps << ',' << (e.survived ? "survived" : "captured") << '\n';
        if (!rows) return usage(("cannot write " + episodes_csv_path).c_str());
      }
      const double reference = paper[name] ? paper[name]["living_random"].as<double>() : NAN;
      const double ratio = s.avg_living_steps / reference;
      const bool within = std::abs(ratio - 1.0) <= kTolerance;
      std::printf("| %s | %.1f | %.0f | %.2f | %s | %.0f %% | %.1f | %.0f %% |\n", name.c_str(), s.avg_living_steps,
                  reference, ratio, within ? "yes" : "no", 100.0 * s.success_rate, s.median_living_steps,
                  100.0 * s.seen_at_start_rate);
      std::fflush(stdout);
      if (csv) {
        csv << name << ',' << s.episodes << ',' << s.avg_living_steps << ',' << reference << ',' << ratio << ','
            << (within ? 1 : 0) << ',' << s.success_rate << ',' << s.median_living_steps << ',' << s.seen_at_start_rate
            << '\n';
      }
    }
  } catch (const hideseek_world::ConfigError& e) {
    std::cerr << "random_hider_table: " << e.what() << '\n';
    return 1;
  } catch (const YAML::Exception& e) {
    std::cerr << "random_hider_table: " << config_dir << "/paper_reference.yaml: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
