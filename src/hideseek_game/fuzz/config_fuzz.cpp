// Fuzz target: the game, variant and map loaders, YAML text in (issue #49). The first byte picks
// the file the rest replaces: 0 a variant file (over the real game.yaml), 1 a map file (under a
// variant naming it), 2 a game file (under the real basic variant). A file that loads is then
// played: an arena is built and reset and takes a few steps. What must hold: no crash, hang or
// unbounded allocation, and a refusal is a ConfigError, or an error naming the file, never another
// exception. Files are written to a private folder beside copies of the real maps.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "hideseek_game/arena.h"
#include "hideseek_game/config_error.h"
#include "hideseek_game/game_options.h"
#include "hideseek_game/map.h"

namespace fs = std::filesystem;

namespace {

// A private config folder: the real game.yaml and maps, and the files the inputs replace; removed
// at exit.
struct Folder {
  fs::path path;
  ~Folder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

const fs::path& folder() {
  static const Folder dir{[] {
    char pattern[] = "/tmp/hideseek_config_fuzz.XXXXXX";
    const char* made = mkdtemp(pattern);
    if (!made) std::abort();
    const fs::path d(made), config(HIDESEEK_CONFIG_DIR);
    fs::copy(config / "maps", d / "maps", fs::copy_options::recursive);
    fs::copy_file(config / "game.yaml", d / "game.yaml");
    fs::copy_file(config / "variants" / "basic.yaml", d / "basic.yaml");
    std::ofstream(d / "map_variant.yaml") << "variant: fuzz\nmap: fuzz.yaml\n";
    return d;
  }()};
  return dir.path;
}

void write(const fs::path& path, const uint8_t* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

void play(const hideseek_game::VariantConfig& v) {
  auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file));
  hideseek_game::Arena arena(v.game, map);
  arena.reset(1);
  for (int i = 0; i < 3; ++i) arena.step(hideseek_game::Action::kForward, hideseek_game::Action::kTurnLeft);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 64 * 1024) return 0;
  const fs::path& d = folder();
  const int kind = data[0] % 3;
  fs::path game = d / "game.yaml", variant = d / "basic.yaml", written;
  if (kind == 0) written = variant = d / "fuzz_variant.yaml";
  if (kind == 1) {
    written = d / "maps" / "fuzz.yaml";
    variant = d / "map_variant.yaml";
  }
  if (kind == 2) written = game = d / "fuzz_game.yaml";
  write(written, data + 1, size - 1);
  try {
    play(hideseek_game::loadVariantConfig(game.string(), variant.string()));
  } catch (const hideseek_game::ConfigError&) {
  } catch (const std::exception& e) {
    // Anything else must at least name a file it read.
    const std::string what = e.what();
    if (what.find(d.string()) == std::string::npos) {
      std::fprintf(stderr, "config_fuzz: an error that names no file: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}

#ifdef HIDESEEK_FUZZ_REPLAY
#include "hideseek_game/fuzz_replay.h"
#endif
