// Converts a feed-forward policy trained in Python (TorchScript of a network with the hider's layers
// and parameter names, as examples/ppo_python.py saves it) into the project's checkpoint format,
// which the hider node, play_episodes and the evaluation load.
// usage: import_policy TORCHSCRIPT.pt OUTPUT.pt VARIANT [STEPS] [HEIGHT WIDTH]
//   VARIANT and STEPS (environment steps trained) are recorded in the checkpoint; the images are
//   84 x 84 unless HEIGHT and WIDTH say otherwise. Every parameter of the hider's network must be
//   in the file with its shape, and nothing else: a mismatch is refused, naming the parameter.
#include <torch/script.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>

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
  if (argc != 4 && argc != 5 && argc != 7) {
    std::fprintf(stderr, "usage: import_policy TORCHSCRIPT.pt OUTPUT.pt VARIANT [STEPS] [HEIGHT WIDTH]\n");
    return 2;
  }
  try {
    const auto number = [](const char* text, const char* what) {
      char* end = nullptr;
      const long long v = std::strtoll(text, &end, 10);
      if (end == text || *end != '\0')
        throw std::invalid_argument(std::string(what) + " '" + text + "' is not a number");
      return static_cast<int64_t>(v);
    };
    const int64_t steps = argc > 4 ? number(argv[4], "STEPS") : 0;
    const int height = argc > 6 ? static_cast<int>(number(argv[5], "HEIGHT")) : 84;
    const int width = argc > 6 ? static_cast<int>(number(argv[6], "WIDTH")) : 84;
    const std::string variant = argv[3];
    if (variant.empty() || variant.find_first_of("/ ") != std::string::npos)
      throw std::invalid_argument("VARIANT '" + variant + "' is not a variant name (config/variants/NAME.yaml)");
    if (steps < 0 || height < 36 || width < 36)
      throw std::invalid_argument("STEPS must be >= 0, HEIGHT and WIDTH >= 36");
    torch::jit::Module source;
    try {
      source = torch::jit::load(argv[1], torch::kCPU);
    } catch (const c10::Error& e) {
      throw std::runtime_error(std::string(argv[1]) +
                               " is not a TorchScript file (torch.jit.save): " + e.what_without_backtrace());
    }
    std::map<std::string, torch::Tensor> given;
    for (const auto& p : source.named_parameters(true)) given[p.name] = p.value;
    hideseek_hider::HiderNet net(height, width, hideseek_hider::NetworkKind::kFeedForward);
    torch::NoGradGuard no_grad;
    for (auto& p : net->named_parameters(true)) {
      const auto it = given.find(p.key());
      if (it == given.end()) throw std::runtime_error(std::string(argv[1]) + " has no parameter '" + p.key() + "'");
      if (!it->second.sizes().equals(p.value().sizes())) {
        throw std::runtime_error(std::string(argv[1]) + ": parameter '" + p.key() + "' has shape " + shape(it->second) +
                                 ", the hider's network needs " + shape(p.value()));
      }
      p.value().copy_(it->second.to(torch::kFloat32));
      given.erase(it);
    }
    if (!given.empty()) {
      throw std::runtime_error(std::string(argv[1]) + " has a parameter the hider's network lacks: '" +
                               given.begin()->first + "'");
    }
    hideseek_hider::CheckpointInfo info;
    info.architecture = hideseek_hider::kArchitecture;
    info.image_height = height;
    info.image_width = width;
    info.variant = variant;
    info.steps = steps;
    hideseek_hider::saveCheckpoint(argv[2], net, info);
    std::printf("%s: %s policy imported from %s, %dx%d images, %ld training steps\n", argv[2], argv[3], argv[1], height,
                width, static_cast<long>(steps));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "import_policy: %s\n", e.what());
    return 1;
  }
  return 0;
}
