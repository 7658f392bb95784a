#include "hideseek_game/map.h"

#include <filesystem>
#include <sstream>

#include "hideseek_game/yaml_fields.h"

namespace hideseek_game {

namespace {

MapSpec readMapFile(const std::string& path) {
  const YAML::Node root = loadYamlFile(path);
  YamlFields f(root, path, "");
  MapSpec spec;
  spec.source = path;
  spec.name = f.text("name", "", {});
  if (spec.name.empty()) throw ConfigError(path, "name", "is required");
  spec.stochastic = f.text("type", "fixed", {"fixed", "stochastic"}) == "stochastic";
  spec.half_extent = f.number("half_extent", 7.0, 2.0, 100.0);
  spec.wall_height = f.number("wall_height", 1.5, 0.1, 10.0);
  spec.obstacle_height = f.number("obstacle_height", 1.5, 0.1, 10.0);

  const YAML::Node obstacles = f.child("obstacles");
  if (obstacles.IsDefined() && !obstacles.IsNull()) {
    if (!obstacles.IsSequence()) throw ConfigError(path, "obstacles", "must be a list of boxes");
    for (size_t i = 0; i < obstacles.size(); ++i) {
      const std::string name = "obstacles[" + std::to_string(i) + "]";
      YamlFields b(obstacles[i], path, name);
      for (const char* key : {"center", "size"}) {
        if (!b.has(key)) {
          // A misspelt key ("centre") is the likelier cause: say it beside the missing one.
          std::string unknown;
          for (const auto& kv : obstacles[i]) {
            const std::string k = kv.first.as<std::string>();
            if (k != "center" && k != "size" && k != "yaw" && k != "height" && k != "wall") unknown += " '" + k + "'";
          }
          throw ConfigError(path, name + "." + key,
                            "is required" + (unknown.empty() ? "" : " (the box has an unknown field" + unknown + ")"));
        }
      }
      // Ranges in units of the arena: a centre within three half-extents of the middle, sides from
      // kMinObstacleSide up to the arena's width twice over; then the box must overlap the arena.
      const double h = spec.half_extent;
      const Vec2 center = b.vec2(b.child("center"), b.field("center"), -3.0 * h, 3.0 * h);
      const Vec2 size = b.vec2(b.child("size"), b.field("size"), kMinObstacleSide, 4.0 * h);
      const double yaw = b.number("yaw", 0.0, -2.0 * kPi, 2.0 * kPi);
      const double height = b.number("height", spec.obstacle_height, 0.1, 10.0);
      Box box = Box::make(center, size, height, yaw);
      if (!footprintOverlapsSquare(box, h)) {
        std::ostringstream m;
        m << "lies wholly outside the arena, whose floor spans [" << -h << ", " << h << "] m on both axes";
        throw ConfigError(path, name, m.str());
      }
      box.wall = b.boolean("wall", false);
      b.rejectUnknown();
      spec.obstacles.push_back(box);
    }
  }
  if (spec.stochastic && !spec.obstacles.empty()) {
    throw ConfigError(path, "obstacles", "a stochastic map draws its obstacles; list none");
  }

  YamlFields g(f.child("generator"), path, "generator");
  spec.generator.min_boxes = g.integer("min_boxes", 0, 0, 100);
  spec.generator.max_boxes = g.integer("max_boxes", 8, 0, 100);
  spec.generator.min_size = g.number("min_size", 0.5, 0.05, 50.0);
  spec.generator.max_size = g.number("max_size", 3.0, 0.05, 50.0);
  g.rejectUnknown();
  if (spec.generator.max_boxes < spec.generator.min_boxes) {
    throw ConfigError(path, "generator.max_boxes", "must not be below generator.min_boxes");
  }
  if (spec.generator.max_size < spec.generator.min_size) {
    throw ConfigError(path, "generator.max_size", "must not be below generator.min_size");
  }
  // The largest draw may cover at most half the floor, so that every episode leaves room for the
  // spawns (a generator that can fill the arena would be searched for a layout at every reset).
  const double largest = spec.generator.max_boxes * spec.generator.max_size * spec.generator.max_size;
  const double floor_area = 4.0 * spec.half_extent * spec.half_extent;
  if (spec.stochastic && largest > 0.5 * floor_area) {
    std::ostringstream m;
    m << "max_boxes x max_size^2 (" << largest << " m^2) must be at most half the floor (" << 0.5 * floor_area
      << " m^2)";
    throw ConfigError(path, "generator", m.str());
  }

  const YAML::Node waypoints = f.child("waypoints");
  if (waypoints.IsDefined() && !waypoints.IsNull()) {
    if (!waypoints.IsSequence()) throw ConfigError(path, "waypoints", "must be a list of [x, y]");
    for (size_t i = 0; i < waypoints.size(); ++i) {
      const std::string name = "waypoints[" + std::to_string(i) + "]";
      const Vec2 w = f.vec2(waypoints[i], name, -spec.half_extent, spec.half_extent);
      if (std::abs(w.x) >= spec.half_extent || std::abs(w.y) >= spec.half_extent) {
        throw ConfigError(path, name, "lies outside the arena");
      }
      for (const Box& b : spec.obstacles) {
        if (footprintDistance(b, w) <= 0.0) throw ConfigError(path, name, "lies inside an obstacle");
      }
      spec.waypoints.push_back(w);
    }
  }
  if (!spec.stochastic && spec.waypoints.empty()) {
    throw ConfigError(path, "waypoints", "a fixed map needs at least one patrol waypoint");
  }

  YamlFields c(f.child("colors"), path, "colors");
  const MapColors defaults;
  spec.colors.floor = c.rgb("floor", defaults.floor);
  spec.colors.wall = c.rgb("wall", defaults.wall);
  spec.colors.obstacle = c.rgb("obstacle", defaults.obstacle);
  spec.colors.hider = c.rgb("hider", defaults.hider);
  spec.colors.seeker = c.rgb("seeker", defaults.seeker);
  spec.colors.sky = c.rgb("sky", defaults.sky);
  if (c.has("hider_front")) spec.colors.hider_front = c.rgb("hider_front", defaults.hider);
  if (c.has("seeker_front")) spec.colors.seeker_front = c.rgb("seeker_front", defaults.seeker);
  c.rejectUnknown();
  f.rejectUnknown();
  return spec;
}

}  // namespace

MapSpec loadMapFile(const std::string& path) {
  std::error_code unreadable;  // a folder that cannot be searched: left to the reader's own message
  if (!std::filesystem::exists(path, unreadable) && !unreadable) {
    throw ConfigError(path, "<file>",
                      "no such file (a variant file's relative map name is taken from its game's maps folder; "
                      "give a map of your own by its absolute path)");
  }
  try {
    return readMapFile(path);
  } catch (const YAML::Exception& e) {  // what the fields' checks did not foresee still names the file
    throw ConfigError(path, "<file>", e.what());
  }
}

Layout makeLayout(const MapSpec& spec, std::mt19937& rng) {
  Layout layout;
  layout.half_extent = spec.half_extent;
  layout.wall_height = spec.wall_height;
  layout.waypoints = spec.waypoints;
  if (!spec.stochastic) {
    layout.obstacles = spec.obstacles;
    return layout;
  }
  const StochasticObstacles& g = spec.generator;
  std::uniform_int_distribution<int> count(g.min_boxes, g.max_boxes);
  std::uniform_real_distribution<double> size(g.min_size, g.max_size);
  std::uniform_real_distribution<double> pos(-spec.half_extent, spec.half_extent);
  std::uniform_real_distribution<double> yaw(0.0, kPi);
  const int n = count(rng);
  for (int i = 0; i < n; ++i) {
    const double sx = size(rng), sy = size(rng), a = yaw(rng);
    const double x = pos(rng), y = pos(rng);
    layout.obstacles.push_back(Box::make({x, y}, {sx, sy}, spec.obstacle_height, a));
  }
  // Waypoints buried by this episode's boxes are dropped.
  std::vector<Vec2> kept;
  for (const Vec2& w : layout.waypoints) {
    bool free = true;
    for (const Box& b : layout.obstacles) free = free && footprintDistance(b, w) > 0.0;
    if (free) kept.push_back(w);
  }
  layout.waypoints = kept;
  return layout;
}

std::vector<Box> wallBoxes(double half_extent, double height) {
  constexpr double kThickness = 0.2;
  const double h = half_extent, t = kThickness, span = 2.0 * (half_extent + kThickness);
  return {Box::make({h + 0.5 * t, 0.0}, {t, span}, height, 0.0), Box::make({-h - 0.5 * t, 0.0}, {t, span}, height, 0.0),
          Box::make({0.0, h + 0.5 * t}, {span, t}, height, 0.0),
          Box::make({0.0, -h - 0.5 * t}, {span, t}, height, 0.0)};
}

}  // namespace hideseek_game
