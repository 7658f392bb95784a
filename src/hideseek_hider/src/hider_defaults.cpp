#include "hideseek_hider/hider_defaults.h"

#include "hideseek_game/yaml_fields.h"

namespace hideseek_hider {

HiderDefaults loadHiderDefaults(const std::string& path) {
  const YAML::Node root = hideseek_game::loadYamlFile(path);
  hideseek_game::YamlFields f(root, path, "");
  f.requireEveryKey();  // the file is the defaults' one source: no fallback is ever used
  HiderDefaults d;
  d.threads = f.integer("threads", 1, 64);
  d.precision = f.text("precision", "", {"auto", "fp32", "bf16"});
  d.memory_format = f.text("memory_format", "", {"auto", "channels_last", "nchw"});
  d.device = f.text("device", "", {"cpu", "cuda"});
  d.network = f.text("network", "", {"auto", "ff", "gru"});
  d.greedy = f.boolean("greedy");
  d.memoryless = f.boolean("memoryless");
  d.total_steps = f.number("total_steps", 1.0, 1e12);
  d.checkpoint_interval_s = f.number("checkpoint_interval", 1e-3, 1e6);
  f.rejectUnknown();
  return d;
}

}  // namespace hideseek_hider
