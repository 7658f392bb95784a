// The shared probe set, and the features of a network on it.
//
// The probes ask what a hider's mid-level features say about S (the hider sees the seeker) and H
// (the seeker sees the hider). Probed on each policy's own rollouts, the answer mixes what the
// network learned with which images the policy happens to see (label priors from 18 % to 98 %).
// So every policy, trained or randomly initialised, is probed on one set of images, fixed before
// any run is analysed: the random hider's and the scripted evaders' rollouts on every variant,
// balanced on S x H within each variant, and split into train and test by episode.
//
// usage:
//   probe_set make OUT_DIR [--config DIR] [--game GAME|FILE] [--first-seed N] [--episodes N]
//                  [--every N] [--per-cell N] [--test-fraction F] [--seed N]
//       plays every variant (config/variants) with each scripted hider (random, backpedal, flee,
//       hide, lap) on its own seeds, first_seed + 1000 k.. for the k-th variant in name order
//       (default 30000, 40 episodes each: clear of the evaluation seeds 0-99 and the analysis
//       rollouts' 10000..; variants that differ only in their reward would otherwise play the very
//       same episodes, and one trajectory could stand on both sides of the split), keeps every
//       `every`-th step (1), draws
//       `per-cell` steps (150, fewer where a cell holds fewer: then every cell of that variant
//       gets as many as its smallest) of each of the four (S, H) cells per variant, renders each
//       one's hider image from its poses, and writes OUT_DIR/images.npy ([N, H, W, 3] uint8),
//       OUT_DIR/labels.csv (one row per image: variant, hider, seed, step, S, H, O, the episode's
//       id, its split and both poses) and OUT_DIR/composition.md. The same arguments give the
//       same files on any machine.
//   probe_set features PROBE_DIR OUT.npy (--policy CHECKPOINT | --random-init SEED [--network ff|gru])
//       (`probe_set make --help`, `probe_set features --help` list the options) writes the 512 mid-level features ([N,
//       512] float32) of every image of the set through a policy's network, or through a network initialised with torch
//       seed SEED.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "hideseek_analysis/analysis_inputs.h"
#include "hideseek_game/arena.h"
#include "hideseek_game/command_line.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/map.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_game/renderer.h"
#include "hideseek_game/run_registry.h"
#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_net.h"
#include "hideseek_play/scripted_game.h"

namespace hw = hideseek_game;
namespace hh = hideseek_hider;
namespace hp = hideseek_play;

namespace {

struct Sample {
  std::string variant;
  hh::EvaderKind evader = hh::EvaderKind::kRandom;
  uint32_t seed = 0;
  int step = 0;
  hw::AgentState hider, seeker;
  hw::Labels labels;
  int episode = 0;  // index of (variant, hider, seed) in play order
  bool test = false;
};

struct MakeOptions {
  std::string out_dir, config_dir, game_file;
  long first_seed = 30000;
  int episodes = 40;
  int every = 1;
  int per_cell = 150;
  double test_fraction = 0.3;
  uint32_t seed = 0;
};

constexpr const char* kUsage =
    "usage: probe_set make OUT_DIR [--config DIR] [--game GAME|FILE] [--first-seed N] [--episodes N] "
    "[--every N] [--per-cell N] [--test-fraction F] [--seed N]\n"
    "       probe_set features PROBE_DIR OUT.npy (--policy CHECKPOINT | --random-init SEED [--network ff|gru])\n"
    "probe_set COMMAND --help says what each option means\n";

int usage(const std::string& why) {
  std::fprintf(stderr, "probe_set: %s\n%s", why.c_str(), kUsage);
  return 2;
}

long inRange(const std::string& flag, long v, long lo, long hi) {
  if (v < lo || v > hi) {
    throw std::invalid_argument(flag + " must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                "], got " + std::to_string(v));
  }
  return v;
}

// Writes a [count, h, w, 3] uint8 array as a NumPy .npy file (format 1.0).
void writeImagesNpy(const std::string& path, const std::vector<uint8_t>& data, int64_t count, int h, int w) {
  std::ostringstream header;
  header << "{'descr': '|u1', 'fortran_order': False, 'shape': (" << count << ", " << h << ", " << w << ", 3), }";
  std::string text = header.str();
  const size_t total = 10 + text.size() + 1;
  text.append((64 - total % 64) % 64, ' ');
  text += '\n';
  std::ofstream out(path, std::ios::binary);
  const uint16_t len = static_cast<uint16_t>(text.size());
  out.write("\x93NUMPY\x01\x00", 8);
  out.write(reinterpret_cast<const char*>(&len), 2);
  out << text;
  out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

// Reads what writeImagesNpy wrote; throws naming the file when it is not such an array.
std::vector<uint8_t> readImagesNpy(const std::string& path, int64_t* count, int* h, int* w) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  char magic[8];
  uint16_t len = 0;
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(&len), 2);
  if (!in || std::memcmp(magic, "\x93NUMPY\x01\x00", 8) != 0 || len > 1024) {
    throw std::runtime_error(path + ": not a NumPy 1.0 array");
  }
  std::string header(len, '\0');
  in.read(header.data(), len);
  long c = 0, hh = 0, ww = 0, ch = 0;
  const auto shape = header.find("'shape': (");
  if (header.find("'descr': '|u1'") == std::string::npos || shape == std::string::npos ||
      std::sscanf(header.c_str() + shape, "'shape': (%ld, %ld, %ld, %ld)", &c, &hh, &ww, &ch) != 4 || ch != 3 ||
      c < 1 || hh < 1 || ww < 1 || hh > 4096 || ww > 4096) {
    throw std::runtime_error(path + ": not a [N, H, W, 3] uint8 image array (header: " + header + ")");
  }
  const auto start = in.tellg();
  in.seekg(0, std::ios::end);
  const int64_t bytes = static_cast<int64_t>(in.tellg() - start);
  if (bytes != c * hh * ww * 3) {
    throw std::runtime_error(path + ": holds " + std::to_string(bytes) + " bytes of images, its header says " +
                             std::to_string(c * hh * ww * 3));
  }
  in.seekg(start);
  std::vector<uint8_t> data(static_cast<size_t>(bytes));
  in.read(reinterpret_cast<char*>(data.data()), bytes);
  *count = c;
  *h = static_cast<int>(hh);
  *w = static_cast<int>(ww);
  return data;
}

int cell(const hw::Labels& l) { return 2 * int(l.hider_sees_seeker) + int(l.seeker_sees_hider); }

int make(const MakeOptions& o) {
  const std::vector<std::string> variants = hw::variantNames(o.config_dir + "/variants");
  std::vector<Sample> chosen;
  int episode_id = 0;
  std::ostringstream composition;
  composition << "| variant | candidate steps per (S, H) cell: 00 / 01 / 10 / 11 | images per cell | train / test "
                 "episodes | images per hider (random / backpedal / flee / hide / lap) |\n"
                 "| --- | --- | --- | --- | --- |\n";
  std::vector<int> cameras;
  for (size_t vi = 0; vi < variants.size(); ++vi) {
    const std::string& name = variants[vi];
    const auto v = hw::loadVariantConfig(o.game_file, o.config_dir + "/variants/" + name + ".yaml");
    const auto map = std::make_shared<const hw::MapSpec>(hw::loadMapFile(v.map_file));
    std::vector<Sample> candidates;
    std::vector<int> episodes_of_variant;
    const long first_seed = o.first_seed + 1000L * static_cast<long>(vi);
    for (const hh::EvaderKind evader : hh::kAllEvaders) {
      const int first_episode = episode_id;
      hp::playScriptedHider(v, map, evader, static_cast<uint32_t>(first_seed), o.episodes,
                            [&](const hp::ScriptedStep& s) {
                              if (s.step % o.every != 0) return;
                              Sample x;
                              x.variant = name;
                              x.evader = evader;
                              x.seed = s.seed;
                              x.step = s.step;
                              x.hider = s.hider;
                              x.seeker = s.seeker;
                              x.labels = s.labels;
                              x.episode = first_episode + static_cast<int>(s.seed - first_seed);
                              candidates.push_back(x);
                            });
      for (int e = 0; e < o.episodes; ++e) episodes_of_variant.push_back(first_episode + e);
      episode_id += o.episodes;
    }
    // The split by episode: a fixed share of the variant's episodes is held out for the test.
    std::mt19937 rng(o.seed * 1000003u + static_cast<uint32_t>(vi));
    std::shuffle(episodes_of_variant.begin(), episodes_of_variant.end(), rng);
    const size_t n_test = static_cast<size_t>(std::ceil(o.test_fraction * episodes_of_variant.size()));
    std::vector<bool> is_test(static_cast<size_t>(episode_id), false);
    for (size_t k = 0; k < n_test; ++k) is_test[static_cast<size_t>(episodes_of_variant[k])] = true;
    // Balanced on S x H: as many steps of each cell, drawn at random.
    std::vector<std::vector<Sample>> cells(4);
    for (auto& x : candidates) {
      x.test = is_test[static_cast<size_t>(x.episode)];
      cells[static_cast<size_t>(cell(x.labels))].push_back(x);
    }
    size_t take = static_cast<size_t>(o.per_cell);
    for (const auto& c : cells) take = std::min(take, c.size());
    if (take == 0) {
      throw std::runtime_error("variant " + name + ": an (S, H) cell has no step in " + std::to_string(o.episodes) +
                               " episodes per hider; play more episodes (--episodes)");
    }
    std::map<hh::EvaderKind, int> per_evader;
    for (auto& c : cells) {
      std::shuffle(c.begin(), c.end(), rng);
      for (size_t k = 0; k < take; ++k) {
        chosen.push_back(c[k]);
        ++per_evader[c[k].evader];
      }
    }
    composition << "| " << name << " | " << cells[0].size() << " / " << cells[1].size() << " / " << cells[2].size()
                << " / " << cells[3].size() << " | " << take << " | " << episodes_of_variant.size() - n_test << " / "
                << n_test << " | ";
    for (size_t k = 0; k < std::size(hh::kAllEvaders); ++k) {
      composition << (k ? " / " : "") << per_evader[hh::kAllEvaders[k]];
    }
    composition << " |\n";
    cameras.push_back(v.game.camera.height * 10000 + v.game.camera.width);
    std::printf("probe_set: %s: %zu candidate steps, %zu images per (S, H) cell\n", name.c_str(), candidates.size(),
                take);
    std::fflush(stdout);
  }
  if (std::adjacent_find(cameras.begin(), cameras.end(), std::not_equal_to<int>()) != cameras.end()) {
    throw std::runtime_error("the variants' cameras differ in size: one probe set cannot serve them all");
  }

  // The images, rendered from the recorded poses in each episode's own layout.
  std::sort(chosen.begin(), chosen.end(),
            [](const Sample& a, const Sample& b) { return std::tie(a.episode, a.step) < std::tie(b.episode, b.step); });
  int h = 0, w = 0;
  std::vector<uint8_t> images;
  std::unique_ptr<hw::Renderer> renderer;
  std::unique_ptr<hw::Arena> arena;
  std::string current_variant;
  int current_episode = -1;
  for (const Sample& x : chosen) {
    if (x.variant != current_variant) {
      const auto v = hw::loadVariantConfig(o.game_file, o.config_dir + "/variants/" + x.variant + ".yaml");
      const auto map = std::make_shared<const hw::MapSpec>(hw::loadMapFile(v.map_file));
      renderer.reset();
      renderer = std::make_unique<hw::Renderer>(hw::rendererOptionsFor(v.game, map->colors, 1));
      arena = std::make_unique<hw::Arena>(v.game, map);
      h = v.game.camera.height;
      w = v.game.camera.width;
      images.reserve(chosen.size() * static_cast<size_t>(h * w * 3));
      current_variant = x.variant;
      current_episode = -1;
    }
    if (x.episode != current_episode) {
      arena->reset(x.seed);
      renderer->setScene(0, arena->layout());
      current_episode = x.episode;
    }
    hw::ViewRequest view;
    view.scene = 0;
    view.viewer = x.hider;
    view.other = x.seeker;
    view.other_is_hider = false;
    const size_t at = images.size();
    images.resize(at + static_cast<size_t>(h * w * 3));
    renderer->render({view}, hw::RenderMode::kColor, images.data() + at);
  }
  std::filesystem::create_directories(o.out_dir);
  writeImagesNpy(o.out_dir + "/images.npy", images, static_cast<int64_t>(chosen.size()), h, w);
  std::ofstream labels(o.out_dir + "/labels.csv");
  labels
      << "image,variant,hider,seed,step,S,H,O,episode,split,hider_x,hider_y,hider_yaw,seeker_x,seeker_y,seeker_yaw\n";
  labels.precision(6);
  for (size_t k = 0; k < chosen.size(); ++k) {
    const Sample& x = chosen[k];
    labels << k << ',' << x.variant << ',' << hh::evaderName(x.evader) << ',' << x.seed << ',' << x.step << ','
           << x.labels.hider_sees_seeker << ',' << x.labels.seeker_sees_hider << ',' << x.labels.obstacle_in_view << ','
           << x.episode << ',' << (x.test ? "test" : "train") << ',' << x.hider.position.x << ',' << x.hider.position.y
           << ',' << x.hider.yaw << ',' << x.seeker.position.x << ',' << x.seeker.position.y << ',' << x.seeker.yaw
           << '\n';
  }
  if (!labels) throw std::runtime_error("cannot write " + o.out_dir + "/labels.csv");
  std::ofstream md(o.out_dir + "/composition.md");
  md << "# The shared probe set\n\n"
     << chosen.size() << " hider images (" << h << " x " << w << "), "
     << (o.every == 1 ? std::string("every") : "every " + std::to_string(o.every) + "th")
     << " step of the random hider's and the four scripted evaders' episodes on every variant, seeds " << o.first_seed
     << " + 1000 k to " << o.first_seed << " + 1000 k + " << o.episodes - 1 << " for the k-th variant in name order ("
     << o.episodes << " episodes per variant and hider), balanced on S x H within each variant (up to " << o.per_cell
     << " images per cell), split by episode (" << o.test_fraction * 100
     << " % of each variant's episodes held out for the test). Draw seed " << o.seed << ".\n\n"
     << composition.str() << "\nS: the hider sees the seeker; H: the seeker sees the hider. "
     << "Written by `probe_set make` with these arguments; labels.csv lists every image.\n";
  std::printf("probe_set: %zu images into %s\n", chosen.size(), o.out_dir.c_str());
  return 0;
}

int features(const std::string& dir, const std::string& out, const std::string& policy, long random_seed,
             const std::string& network) {
  int64_t count = 0;
  int h = 0, w = 0;
  const std::vector<uint8_t> images = readImagesNpy(dir + "/images.npy", &count, &h, &w);
  hideseek_hider::HiderNet net{nullptr};
  if (!policy.empty()) {
    net = hideseek_hider::loadCheckpoint(policy, h, w);
  } else {
    torch::manual_seed(static_cast<uint64_t>(random_seed));
    net = hideseek_hider::HiderNet(h, w, hideseek_hider::parseNetwork(network, "--network"));
  }
  const torch::Tensor f = hideseek_analysis::extractFeatures(net, images.data(), count, h, w);
  const torch::Tensor c = f.contiguous().to(torch::kFloat32);
  hideseek_analysis::writeNpy(out, c.data_ptr<float>(), c.size(0), c.size(1));
  std::printf("probe_set: features of %ld images (%s) into %s\n", static_cast<long>(count),
              policy.empty() ? ("random init, seed " + std::to_string(random_seed)).c_str() : policy.c_str(),
              out.c_str());
  return 0;
}

// A subcommand's command line (argv[0] is the subcommand): std::nullopt to go on, else the exit status.
std::optional<int> parseSubcommand(int argc, char** argv, hw::CommandLine& line) {
  int exit_code = 0;
  if (!hw::parseCommandLine(argc, argv, line, &exit_code)) return exit_code;
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  namespace po = boost::program_options;
  if (argc < 2) return usage("name a command: make or features (probe_set COMMAND --help)");
  const std::string command = argv[1];
  if (command == "--help" || command == "-h") {
    std::printf(
        "probe_set: the shared probe set of the representation study (the scripted and random hiders' images\n"
        "of every variant, labelled S and H) and a network's mid-level features of it\n%s",
        kUsage);
    return 0;
  }
  try {
    if (command == "make") {
      MakeOptions o;
      long seed = o.seed;
      hw::CommandLine line;
      line.tool = "probe_set make";
      line.about =
          "probe_set make: plays every variant with each scripted hider and writes the shared probe set\n"
          "usage: probe_set make OUT_DIR [--config DIR] [--game GAME|FILE] [--first-seed N] [--episodes N] [--every "
          "N]\n"
          "                      [--per-cell N] [--test-fraction F] [--seed N]";
      line.options.add_options()                                                                                  //
          ("out-dir", po::value(&o.out_dir)->required(), "where images.npy, labels.csv and composition.md go")    //
          ("config", po::value(&o.config_dir), "the config folder (default: hideseek_game's installed config/)")  //
          ("game", po::value(&o.game_file), "a game name or file (none: config/games.yaml's default)")            //
          ("first-seed", po::value(&o.first_seed)->default_value(o.first_seed),
           "the first variant's first seed; the k-th variant's start 1000 k later")                                   //
          ("episodes", po::value(&o.episodes)->default_value(o.episodes), "episodes per variant and hider")           //
          ("every", po::value(&o.every)->default_value(o.every), "keep every N-th step")                              //
          ("per-cell", po::value(&o.per_cell)->default_value(o.per_cell), "steps drawn per (S, H) cell and variant")  //
          ("test-fraction", po::value(&o.test_fraction)->default_value(o.test_fraction, "0.3"),
           "the share of episodes in the test split, in (0, 1)")  //
          ("seed", po::value(&seed)->default_value(seed), "the draw's seed");
      line.positional.add("out-dir", 1);
      if (const auto exit_code = parseSubcommand(argc - 1, argv + 1, line)) return *exit_code;
      inRange("--first-seed", o.first_seed, 0, (1L << 31) - 100000);
      inRange("--episodes", o.episodes, 1, 1000);
      inRange("--every", o.every, 1, 1000);
      inRange("--per-cell", o.per_cell, 1, 100000);
      o.seed = static_cast<uint32_t>(inRange("--seed", seed, 0, 1L << 31));
      if (!(o.test_fraction > 0.0 && o.test_fraction < 1.0)) {
        return usage("--test-fraction must be in (0, 1), got " + std::to_string(o.test_fraction));
      }
      if (o.config_dir.empty()) o.config_dir = hw::configDirectory();
      o.game_file = hw::gameArgument(o.config_dir, o.game_file);
      return make(o);
    }
    if (command == "features") {
      std::string probe_dir, out, policy, network;
      long seed = -1;
      hw::CommandLine line;
      line.tool = "probe_set features";
      line.about =
          "probe_set features: the 512 mid-level features of every image of the set through a policy's network,\n"
          "or through a network initialised with torch seed SEED\n"
          "usage: probe_set features PROBE_DIR OUT.npy (--policy CHECKPOINT | --random-init SEED [--network ff|gru])";
      line.options.add_options()                                                                        //
          ("probe-dir", po::value(&probe_dir)->required(), "the probe set (probe_set make's OUT_DIR)")  //
          ("out", po::value(&out)->required(), "the features, [N, 512] float32 (.npy)")                 //
          ("policy", po::value(&policy), "a checkpoint")                                                //
          ("random-init", po::value(&seed), "a network initialised with this torch seed instead")       //
          ("network", po::value(&network)->default_value("ff"), "with --random-init: ff or gru");
      line.positional.add("probe-dir", 1).add("out", 1);
      if (const auto exit_code = parseSubcommand(argc - 1, argv + 1, line)) return *exit_code;
      if (seed != -1) inRange("--random-init", seed, 0, 1L << 31);
      if (policy.empty() == (seed < 0)) return usage("features needs exactly one of --policy and --random-init");
      return features(probe_dir, out, policy, seed, network);
    }
    return usage("unknown command '" + command + "'");
  } catch (const std::invalid_argument& e) {  // a malformed option value
    return usage(e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "probe_set: %s\n", e.what());
    return 1;
  }
}
