// Plays seeded episodes of a variant in process (world and seeker cores, the hider's policy on
// rendered images) and writes every step of them to a CSV: the trajectories and distances that
// show a policy's strategy. The same cores, draws and step order as the ROS graph in lockstep.
// usage: play_episodes [--game GAME] --variant VARIANT --policy POLICY --first-seed S --count N
//                      --output OUTPUT.csv [--action greedy|sampled] [--memory memory|memoryless]
//   or, as before, play_episodes [--game GAME] VARIANT POLICY FIRST_SEED COUNT OUTPUT.csv [greedy|sampled]
//   [memory|memoryless] (positional arguments, in that order); --help lists the options.
//   GAME: v2, v1 or v3 (none: config/games.yaml's default), resolved as the nodes resolve ~game.
//   memoryless (GRU policies only, an ablation): every step starts from the zero state, so the
//   trained GRU acts on the current image alone.
//   --seeker-policy CHECKPOINT: a learned seeker's checkpoint plays the seeker (from its own camera,
//   deciding once a decision step, as in the graph), with --action as the hider's; else the
//   variant's scripted seeker. --variant-config FILE: a variant file of one's own, named VARIANT.
//   POLICY: a checkpoint, "random", or scripted/EVADER (backpedal, flee, hide, lap). Columns:
//   seed,step,hider_x,hider_y,hider_yaw,seeker_x, seeker_y,seeker_yaw,S,H,O,distance,hider_action,outcome (outcome on
//   the last step of an episode: captured or survived; empty before). Beside it, OUTPUT_layouts.yaml (OUTPUT's name
//   without .csv) holds each episode's obstacles and arena size, which differ per episode on
//   stochastic maps; plot_trajectories.py draws them.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hideseek_game/agent.h"
#include "hideseek_game/command_line.h"
#include "hideseek_game/game_loop.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/hash_uniform.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_policy.h"
#include "hideseek_seeker/seeker_policy.h"

namespace {

namespace hw = hideseek_game;

// The hider that plays: "random", a scripted evader's name, or a checkpoint.
std::unique_ptr<hideseek_hider::HiderPolicy> makeHider(const std::string& policy_path, const hw::VariantConfig& variant,
                                                       bool greedy, bool memoryless) {
  if (policy_path == "random") {
    if (memoryless) throw std::runtime_error("memoryless applies to a GRU policy, not to the random hider");
    return std::make_unique<hideseek_hider::RandomHiderPolicy>();
  }
  if (const auto evader = hideseek_hider::scriptedPolicy(policy_path)) {
    if (memoryless) throw std::runtime_error("memoryless applies to a GRU policy, not to " + policy_path);
    return std::make_unique<hideseek_hider::ScriptedHiderPolicy>(*evader, variant);
  }
  const int h = variant.game.camera.height, w = variant.game.camera.width;
  auto policy = std::make_unique<hideseek_hider::NetworkHiderPolicy>(hideseek_hider::loadCheckpoint(policy_path, h, w),
                                                                     torch::kCPU, greedy);
  policy->setMemoryless(memoryless);
  return policy;
}

// OUTPUT_layouts.yaml beside OUTPUT.csv: the layout of each arena's first episode.
void writeLayouts(const hw::World& world, const std::string& csv_path, const std::string& variant_name) {
  std::string layouts_path = csv_path;
  if (layouts_path.size() > 4 && layouts_path.compare(layouts_path.size() - 4, 4, ".csv") == 0) {
    layouts_path.resize(layouts_path.size() - 4);
  }
  layouts_path += "_layouts.yaml";
  std::ofstream layouts(layouts_path);
  if (!layouts) throw std::runtime_error("cannot write " + layouts_path);
  layouts << "# play_episodes: the layout of each episode in " << csv_path << " (variant " << variant_name << ")\n"
          << "episodes:\n";
  for (int i = 0; i < world.numArenas(); ++i) {
    const hw::Layout& l = world.arena(i).layout();
    layouts << "  - seed: " << world.arena(i).seed() << "\n    half_extent: " << l.half_extent << "\n    obstacles:";
    if (l.obstacles.empty()) layouts << " []";
    layouts << "\n";
    for (const auto& b : l.obstacles) {
      layouts << "      - {center: [" << b.center.x << ", " << b.center.y << "], size: [" << b.size.x << ", "
              << b.size.y << "], yaw: " << b.yaw << "}\n";
    }
  }
}

// A learned seeker: a seeker's checkpoint (its role and the game's seeker actions checked) on
// the seeker's camera images, with the learned seeker's own stream of sampled actions.
std::unique_ptr<hideseek_hider::NetworkHiderPolicy> makeLearnedSeeker(const std::string& path,
                                                                      const hw::VariantConfig& variant, bool greedy) {
  return std::make_unique<hideseek_hider::NetworkHiderPolicy>(
      hideseek_hider::loadCheckpoint(path, variant.game.camera.height, variant.game.camera.width, nullptr, std::nullopt,
                                     "seeker", hw::actionCount(variant.game, true)),
      torch::kCPU, greedy, hw::kSaltSampledSeekerPolicy);
}

// Observations of every arena for a network, `images` the role's camera images, arena after arena.
std::vector<hideseek_hider::ArenaObservation> observations(const hw::World& world, const uint8_t* images) {
  std::vector<hideseek_hider::ArenaObservation> batch(world.numArenas());
  for (int i = 0; i < world.numArenas(); ++i) {
    const hw::Arena& a = world.arena(i);
    batch[i] = {images + i * world.imageBytes(), a.seed(), static_cast<uint32_t>(a.stepCount()), a.hider(), a.seeker()};
  }
  return batch;
}

// Plays every arena to the end of its first episode and writes those steps to `out`, one row per
// step. Every arena plays on after its first episode (the arenas stay in phase, as in the graph).
// The seeker: `learned` where given (it decides once a step, from its images), else `seekers`.
void playFirstEpisodes(hw::GameLoop& game, hideseek_hider::HiderPolicy& hider,
                       std::vector<hideseek_seeker::SeekerPolicy>& seekers, hideseek_hider::HiderPolicy* learned,
                       std::ofstream& out) {
  const hw::World& world = game.world();
  const int n = world.numArenas();
  out << "seed,step,hider_x,hider_y,hider_yaw,seeker_x,seeker_y,seeker_yaw,S,H,O,distance,hider_action,outcome\n";
  std::vector<bool> playing(n, true);
  std::vector<uint8_t> learned_actions;
  const hw::ArenaSeekerDecide decide = [&](int i, const hw::SeekerPerception& p) {
    return learned ? static_cast<hw::Action>(learned_actions[i]) : seekers[i].act(p);
  };
  for (int left = n; left > 0;) {
    if (learned) learned_actions = learned->act(observations(world, game.seekerImages().data()));
    std::vector<hideseek_hider::ArenaObservation> batch(n);
    std::vector<hw::AgentState> hiders(n), seeker_states(n);
    std::vector<hw::Labels> labels(n);
    std::vector<uint32_t> seeds(n);
    std::vector<int> steps(n);
    for (int i = 0; i < n; ++i) {
      const hw::Arena& a = world.arena(i);
      batch[i] = {game.hiderImages().data() + i * world.imageBytes(), a.seed(), static_cast<uint32_t>(a.stepCount()),
                  a.hider(), a.seeker()};
      hiders[i] = a.hider();
      seeker_states[i] = a.seeker();
      labels[i] = a.labels();
      seeds[i] = a.seed();
      steps[i] = a.stepCount();
    }
    const std::vector<uint8_t> actions = hider.act(batch);
    std::vector<hw::Action> hider_actions(n);
    for (int i = 0; i < n; ++i) hider_actions[i] = static_cast<hw::Action>(actions[i]);
    const hw::Decision d = game.step(hider_actions, decide);
    for (int i = 0; i < n; ++i) {
      const std::optional<hw::EpisodeSummary>& finished = d.steps[i].finished;
      if (finished && !learned) seekers[i].reset(world.arena(i).layout(), world.arena(i).seed());
      if (!playing[i]) continue;
      const hw::AgentState &hs = hiders[i], &ss = seeker_states[i];
      const hw::Labels& l = labels[i];
      out << seeds[i] << ',' << steps[i] << ',' << hs.position.x << ',' << hs.position.y << ',' << hs.yaw << ','
          << ss.position.x << ',' << ss.position.y << ',' << ss.yaw << ',' << l.hider_sees_seeker << ','
          << l.seeker_sees_hider << ',' << l.obstacle_in_view << ',' << hw::distance(hs.position, ss.position) << ','
          << static_cast<int>(actions[i]) << ',';
      if (finished) {
        const char* outcome = finished->outcome == hw::Outcome::kSurvived ? "survived" : "captured";
        out << outcome;
        playing[i] = false;
        --left;
        std::printf("seed %u: %s after %d steps\n", seeds[i], outcome, finished->steps);
      }
      out << '\n';
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  namespace po = boost::program_options;
  hideseek_game::CommandLine line;
  line.tool = "play_episodes";
  line.about =
      "play_episodes: plays seeded episodes of a variant in process and writes every step to a CSV\n"
      "usage: play_episodes [--game GAME] --variant VARIANT --policy POLICY --first-seed S --count N --output "
      "OUTPUT.csv\n"
      "       [--action greedy|sampled] [--memory memory|memoryless] [--seeker-policy CHECKPOINT]\n"
      "   or: play_episodes [--game GAME] VARIANT POLICY FIRST_SEED COUNT OUTPUT.csv [greedy|sampled] "
      "[memory|memoryless]";
  long first_seed = 0, count = 0;
  std::string game_name, variant_name, policy_path, csv_path, mode, memory, seeker_path, variant_file;
  line.options.add_options()                                                                           //
      ("game", po::value(&game_name), "v2, v1 or v3 (none: config/games.yaml's default)")              //
      ("variant", po::value(&variant_name)->required(), "the variant (config/variants/VARIANT.yaml)")  //
      ("policy", po::value(&policy_path)->required(),
       "a checkpoint, random, or scripted/EVADER (backpedal, flee, hide, lap)")            //
      ("first-seed", po::value(&first_seed)->required(), "the first episode seed (>= 0)")  //
      ("count", po::value(&count)->required(),
       "episodes, one arena each: seeds first-seed .. first-seed+count-1 (1-64)")                            //
      ("output", po::value(&csv_path)->required(), "the CSV of every step (OUTPUT_layouts.yaml beside it)")  //
      ("action", po::value(&mode)->default_value("greedy"), "greedy (the most likely action) or sampled")    //
      ("memory", po::value(&memory)->default_value("memory"),
       "memory, or memoryless (GRU policies: every step from the zero state, an ablation)")  //
      ("seeker-policy", po::value(&seeker_path),
       "a learned seeker's checkpoint plays the seeker (none: the variant's scripted seeker)")  //
      ("variant-config", po::value(&variant_file),
       "a variant file of one's own, named VARIANT, instead of config/variants/VARIANT.yaml");
  for (const char* name : {"variant", "policy", "first-seed", "count", "output", "action", "memory"}) {
    line.positional.add(name, 1);
  }
  int exit_code = 0;
  if (!hideseek_game::parseCommandLine(argc, argv, line, &exit_code)) return exit_code;
  if ((mode != "greedy" && mode != "sampled") || (memory != "memory" && memory != "memoryless")) {
    std::fprintf(stderr,
                 "play_episodes: --action is greedy or sampled (got %s), --memory memory or memoryless (got %s)\n",
                 mode.c_str(), memory.c_str());
    return 2;
  }
  if (first_seed < 0 || count < 1 || count > 64) {
    std::fprintf(stderr, "play_episodes: --first-seed must be >= 0 and --count in [1, 64]\n");
    return 2;
  }
  try {
    const std::string config = hw::configDirectory();
    // A variant file of one's own must name the variant it is given as (selectGame refuses it otherwise).
    hw::VariantConfig variant = hw::selectGame(config, game_name, variant_name, variant_file).config;
    // A learned seeker decides once a decision step, from its camera, as the graph plays it.
    if (!seeker_path.empty()) variant.game = hw::withLearnedSeeker(variant.game);
    const auto map = std::make_shared<const hw::MapSpec>(hw::loadMapFile(variant.map_file));
    const int n = static_cast<int>(count);
    hw::GameLoopOptions loop_options;
    loop_options.num_arenas = n;
    loop_options.seed = static_cast<uint32_t>(first_seed);
    loop_options.render_seeker = !seeker_path.empty();
    hw::GameLoop game(variant.game, map, loop_options);
    const hw::World& world = game.world();
    const auto hider = makeHider(policy_path, variant, mode == "greedy", memory == "memoryless");
    const auto learned = seeker_path.empty() ? nullptr : makeLearnedSeeker(seeker_path, variant, mode == "greedy");
    std::vector<hideseek_seeker::SeekerPolicy> seekers;
    for (int i = 0; i < n && !learned; ++i) {
      seekers.emplace_back(hideseek_seeker::seekerOptionsFor(variant));
      seekers.back().reset(world.arena(i).layout(), world.arena(i).seed());
    }
    std::ofstream out(csv_path);
    if (!out) throw std::runtime_error("cannot write " + csv_path);
    writeLayouts(world, csv_path, variant_name);
    playFirstEpisodes(game, *hider, seekers, learned.get(), out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "play_episodes: %s\n", e.what());
    return 1;
  }
  return 0;
}
