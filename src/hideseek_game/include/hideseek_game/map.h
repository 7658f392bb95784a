// Maps: what a map file describes, and the concrete layout of one episode.
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "hideseek_game/geometry.h"

namespace hideseek_game {

struct Rgb {
  float r = 0.f, g = 0.f, b = 0.f;
};

struct MapColors {
  Rgb floor{0.55f, 0.55f, 0.52f};
  Rgb wall{0.35f, 0.38f, 0.45f};
  Rgb obstacle{0.80f, 0.62f, 0.30f};
  Rgb hider{0.10f, 0.55f, 0.95f};
  Rgb seeker{0.90f, 0.12f, 0.10f};
  Rgb sky{0.62f, 0.75f, 0.88f};
  // The front half of each agent (150 degrees around its heading) in its own colour, so that an
  // 84 x 84 image shows which way the other agent faces. Unset: a thin dark stripe (game v1).
  std::optional<Rgb> hider_front;
  std::optional<Rgb> seeker_front;
};

// Parameters of the per-episode random obstacle generator (SPEC section 2).
struct StochasticObstacles {
  int min_boxes = 0;
  int max_boxes = 8;
  double min_size = 0.5;
  double max_size = 3.0;
};

// The shortest side a map file's obstacle may have, in metres (the longest is twice the arena's
// width): a side must be positive, and 1 cm is less than any obstacle the maps draw.
inline constexpr double kMinObstacleSide = 0.01;

// A map file: fixed obstacles, or a generator that draws them every episode.
struct MapSpec {
  std::string name;
  std::string source;  // the file it was read from
  double half_extent = 7.0;
  double wall_height = 1.5;
  double obstacle_height = 1.5;
  bool stochastic = false;
  std::vector<Box> obstacles;
  StochasticObstacles generator;
  std::vector<Vec2> waypoints;
  MapColors colors;
};

// The obstacles and waypoints of one episode.
struct Layout {
  double half_extent = 7.0;
  double wall_height = 1.5;
  std::vector<Box> obstacles;
  std::vector<Vec2> waypoints;
};

// Reads and validates a map file; throws ConfigError naming the file and field.
MapSpec loadMapFile(const std::string& path);

// Draws the layout of one episode (fixed maps ignore the generator).
Layout makeLayout(const MapSpec& spec, std::mt19937& rng);

// The four walls as boxes just outside the arena.
std::vector<Box> wallBoxes(double half_extent, double height);

}  // namespace hideseek_game
