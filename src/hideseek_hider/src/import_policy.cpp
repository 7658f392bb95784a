// Converts a feed-forward policy trained in Python (TorchScript of a network with the hider's layers
// and parameter names, as examples/ppo_python.py saves it) into the project's checkpoint format,
// which the hider node, play_episodes and the evaluation load.
// usage: import_policy TORCHSCRIPT.pt OUTPUT.pt VARIANT [STEPS] [HEIGHT WIDTH] [--game GAME]
//   VARIANT, STEPS (environment steps trained) and GAME (default: config/games.yaml's, the game
//   hideseek.make_vec plays unless told otherwise) are recorded in the checkpoint; the images are
//   84 x 84 unless HEIGHT and WIDTH say otherwise. Every parameter of the hider's network must be
//   in the file with its shape, and nothing else: a mismatch is refused, naming the parameter.
#include <torch/script.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>

#include "hideseek_game/command_line.h"
#include "hideseek_game/game_selection.h"
#include "hideseek_game/package_paths.h"
#include "hideseek_hider/checkpoint.h"
#include "hideseek_hider/hider_net.h"

namespace {

std::string shape(const torch::Tensor& t) {
  std::string s = "[";
  for (int64_t i = 0; i < t.dim(); ++i) s += (i ? ", " : "") + std::to_string(t.size(i));
  return s + "]";
}

}  // namespace

int main(int argc, char** argv) {
  namespace po = boost::program_options;
  std::string torchscript, output, variant_name, game;
  int64_t steps = 0;
  int height = 84, width = 84;
  hideseek_game::CommandLine line;
  line.tool = "import_policy";
  line.about =
      "import_policy: converts a feed-forward policy trained in Python (TorchScript with the hider's layers and\n"
      "parameter names) into the project's checkpoint format\n"
      "usage: import_policy TORCHSCRIPT.pt OUTPUT.pt VARIANT [STEPS] [HEIGHT WIDTH] [--game GAME], or the same as\n"
      "named options";
  line.options.add_options()                                                                             //
      ("torchscript", po::value(&torchscript)->required(), "the TorchScript file")                       //
      ("output", po::value(&output)->required(), "the checkpoint to write")                              //
      ("variant", po::value(&variant_name)->required(), "the variant it was trained on (recorded)")      //
      ("steps", po::value(&steps)->default_value(0), "environment steps it was trained for (recorded)")  //
      ("height", po::value(&height)->default_value(84), "image height (at least 36)")                    //
      ("width", po::value(&width)->default_value(84), "image width (at least 36)")                       //
      ("game", po::value(&game), "the game it was trained on (recorded; default: config/games.yaml's)");
  line.positional.add("torchscript", 1)
      .add("output", 1)
      .add("variant", 1)
      .add("steps", 1)
      .add("height", 1)
      .add("width", 1);
  int exit_code = 0;
  const auto given_options = hideseek_game::parseCommandLine(argc, argv, line, &exit_code);
  if (!given_options) return exit_code;
  try {
    // One of the two alone would import a network for a shape the policy was not trained on.
    if (given_options->at("height").defaulted() != given_options->at("width").defaulted())
      throw std::invalid_argument("HEIGHT and WIDTH go together: give both, or neither for 84 x 84");
    const std::string& variant = variant_name;
    if (variant.empty() || variant.find_first_of("/ ") != std::string::npos)
      throw std::invalid_argument("VARIANT '" + variant + "' is not a variant name (config/variants/NAME.yaml)");
    if (steps < 0 || height < 36 || width < 36)
      throw std::invalid_argument("STEPS must be >= 0, HEIGHT and WIDTH >= 36");
    const std::string config = hideseek_game::configDirectory();
    if (game.empty()) game = hideseek_game::defaultGame(config);
    hideseek_game::gameFile(config, game);  // an unknown game is refused, naming the games there are
    torch::jit::Module source;
    try {
      source = torch::jit::load(torchscript, torch::kCPU);
    } catch (const c10::Error& e) {
      throw std::runtime_error(torchscript +
                               " is not a TorchScript file (torch.jit.save): " + e.what_without_backtrace());
    }
    std::map<std::string, torch::Tensor> given;
    for (const auto& p : source.named_parameters(true)) given[p.name] = p.value;
    hideseek_hider::HiderNet net(height, width, hideseek_hider::NetworkKind::kFeedForward);
    torch::NoGradGuard no_grad;
    for (auto& p : net->named_parameters(true)) {
      const auto it = given.find(p.key());
      if (it == given.end()) throw std::runtime_error(torchscript + " has no parameter '" + p.key() + "'");
      if (!it->second.sizes().equals(p.value().sizes())) {
        throw std::runtime_error(torchscript + ": parameter '" + p.key() + "' has shape " + shape(it->second) +
                                 ", the hider's network needs " + shape(p.value()));
      }
      p.value().copy_(it->second.to(torch::kFloat32));
      given.erase(it);
    }
    if (!given.empty()) {
      throw std::runtime_error(torchscript + " has a parameter the hider's network lacks: '" + given.begin()->first +
                               "'");
    }
    hideseek_hider::CheckpointInfo info;
    info.architecture = hideseek_hider::kArchitecture;
    info.image_height = height;
    info.image_width = width;
    info.variant = variant;
    info.steps = steps;
    info.game = game;
    hideseek_hider::saveCheckpoint(output, net, info);
    std::printf("%s: %s policy of game %s imported from %s, %dx%d images, %ld training steps\n", output.c_str(),
                variant.c_str(), game.c_str(), torchscript.c_str(), height, width, static_cast<long>(steps));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "import_policy: %s\n", e.what());
    return 1;
  }
  return 0;
}
