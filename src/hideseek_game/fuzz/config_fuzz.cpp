// Fuzz target: the game, variant and map loaders, YAML text in (issue #49). The first byte picks
// the file the rest replaces: 0 a variant file (over the real game.yaml), 1 a map file (under a
// variant naming it), 2 a game file (under the real basic variant). A file that loads is then
// played: an arena is built and reset and takes a few steps. What must hold: no crash, hang or
// unbounded allocation, and a refusal is a ConfigError, or an error naming the file, never another
// exception. A file that loads must also give what the game relies on (issue #63), checked here by
// code of its own rather than by the loader's checks:
//   - every number of the map and of the game's physics finite, every extent positive;
//   - every obstacle sharing area with the arena's floor (a corner or an edge inside it, or the box
//     covering the floor's centre);
//   - every waypoint inside the arena, outside every obstacle, and on a fixed map clear of every
//     obstacle and wall by the agent radius;
//   - spawns drawable: resets of three seeds each give two agents inside the arena, clear of every
//     obstacle by the agent radius, at least min_spawn_distance apart and farther than the capture
//     distance, and finite after up to three steps.
// A violation prints which and aborts, like a crash. Files are written to a private folder beside
// copies of the real maps.
#include <unistd.h>

#include <algorithm>
#include <cmath>
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

using hideseek_game::Box;
using hideseek_game::Vec2;

[[noreturn]] void violated(const std::string& what) {
  std::fprintf(stderr, "config_fuzz: a file that loads breaks an invariant: %s\n", what.c_str());
  std::abort();
}

void require(bool holds, const std::string& what) {
  if (!holds) violated(what);
}

bool finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// Whether the segment a-b passes through the open square (-h, h)^2 (Liang-Barsky clipping).
bool segmentCrossesSquare(Vec2 a, Vec2 b, double h) {
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-(b.x - a.x), b.x - a.x, -(b.y - a.y), b.y - a.y};
  const double q[4] = {a.x + h, h - a.x, a.y + h, h - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] <= 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) t0 = std::max(t0, t);
    if (p[i] > 0.0) t1 = std::min(t1, t);
  }
  return t0 < t1;
}

// The box shares area with the floor: one of its edges runs through the open square, or it covers
// the square's centre (a box holding the whole floor crosses it with no edge).
bool meetsFloor(const Box& b, double h) {
  const double hx = 0.5 * b.size.x, hy = 0.5 * b.size.y;
  Vec2 corner[4];
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  for (int i = 0; i < 4; ++i) {
    const double u = sx[i] * hx, v = sy[i] * hy;
    corner[i] = {b.center.x + b.cos_yaw * u - b.sin_yaw * v, b.center.y + b.sin_yaw * u + b.cos_yaw * v};
  }
  // A hair of tolerance: the loader's separating-axis test and these rounded corners may disagree
  // on a box that only touches the floor's edge; only a box clearly outside is a violation.
  const double grown = h + 1e-9;
  for (int i = 0; i < 4; ++i) {
    if (segmentCrossesSquare(corner[i], corner[(i + 1) % 4], grown)) return true;
  }
  return hideseek_game::footprintDistance(b, {0.0, 0.0}) < 0.0;
}

void checkMap(const hideseek_game::MapSpec& m) {
  const double h = m.half_extent;
  require(std::isfinite(h) && h > 0.0, "half_extent " + std::to_string(h));
  require(std::isfinite(m.wall_height) && std::isfinite(m.obstacle_height), "a height is not finite");
  for (size_t i = 0; i < m.obstacles.size(); ++i) {
    const Box& b = m.obstacles[i];
    const std::string name = "obstacles[" + std::to_string(i) + "]";
    require(finite(b.center) && finite(b.size) && std::isfinite(b.yaw) && std::isfinite(b.height),
            name + " holds a number that is not finite");
    require(b.size.x > 0.0 && b.size.y > 0.0 && b.height > 0.0, name + " has an extent that is not positive");
    require(meetsFloor(b, h), name + " shares no area with the arena's floor");
  }
  for (size_t i = 0; i < m.waypoints.size(); ++i) {
    const Vec2 w = m.waypoints[i];
    const std::string name = "waypoints[" + std::to_string(i) + "]";
    require(finite(w) && std::abs(w.x) < h && std::abs(w.y) < h, name + " is not inside the arena");
    for (const Box& b : m.obstacles) {
      require(hideseek_game::footprintDistance(b, w) > 0.0, name + " lies in an obstacle");
    }
  }
}

void checkGame(const hideseek_game::GameOptions& g) {
  for (const double v : {g.physics_dt, g.agent_radius, g.agent_height, g.capture_distance, g.min_spawn_distance,
                         g.hider.speed, g.hider.max_speed, g.hider.acceleration, g.hider.turn_rate, g.seeker.speed,
                         g.seeker.max_speed, g.seeker.acceleration, g.seeker.turn_rate}) {
    require(std::isfinite(v), "a game number is not finite");
  }
  require(g.physics_dt > 0.0 && g.action_repeat > 0 && g.max_steps > 0 && g.agent_radius > 0.0,
          "a game step, radius or length is not positive");
}

// Spawns lie in the arena, clear of every obstacle, min_spawn_distance apart.
void checkSpawns(const hideseek_game::Arena& arena, uint32_t seed) {
  const auto& o = arena.options();
  const double limit = arena.layout().half_extent - o.agent_radius;
  const std::string at = " (seed " + std::to_string(seed) + ")";
  for (const auto* agent : {&arena.hider(), &arena.seeker()}) {
    const Vec2 p = agent->position;
    require(finite(p) && std::abs(p.x) <= limit && std::abs(p.y) <= limit, "a spawn outside the arena" + at);
    for (const Box& b : arena.layout().obstacles) {
      require(hideseek_game::footprintDistance(b, p) >= o.agent_radius, "a spawn inside an obstacle" + at);
    }
  }
  require(hideseek_game::distance(arena.hider().position, arena.seeker().position) >= o.min_spawn_distance,
          "spawns closer than min_spawn_distance" + at);
}

// A fixed map's waypoints are where an agent stands: clear of every obstacle and wall by its radius.
void checkWaypointsFitAnAgent(const hideseek_game::Arena& arena) {
  const auto& o = arena.options();
  const double limit = arena.layout().half_extent - o.agent_radius;
  for (const Vec2 w : arena.layout().waypoints) {
    require(std::abs(w.x) <= limit && std::abs(w.y) <= limit, "a waypoint within an agent radius of a wall");
    for (const Box& b : arena.layout().obstacles) {
      require(hideseek_game::footprintDistance(b, w) >= o.agent_radius, "a waypoint within an agent radius of a box");
    }
  }
}

void play(const hideseek_game::VariantConfig& v) {
  auto map = std::make_shared<const hideseek_game::MapSpec>(hideseek_game::loadMapFile(v.map_file));
  checkMap(*map);
  checkGame(v.game);
  hideseek_game::Arena arena(v.game, map);
  if (!map->stochastic) checkWaypointsFitAnAgent(arena);
  for (const uint32_t seed : {1u, 2u, 3u}) {
    arena.reset(seed);
    checkSpawns(arena, seed);
    for (const Box& b : arena.layout().obstacles) require(meetsFloor(b, arena.layout().half_extent), "a drawn box");
    require(hideseek_game::distance(arena.hider().position, arena.seeker().position) > v.game.capture_distance,
            "spawned within capture distance");
    for (int i = 0; i < 3 && !arena.step(hideseek_game::Action::kForward, hideseek_game::Action::kTurnLeft).done();
         ++i) {
    }
    require(finite(arena.hider().position) && finite(arena.seeker().position), "an agent's position after 3 steps");
  }
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
