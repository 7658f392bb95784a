#include "hideseek_game/game_options.h"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <utility>

#include "hideseek_game/yaml_fields.h"

namespace hideseek_game {

double CameraOptions::verticalFov() const {
  return 2.0 * std::atan(std::tan(0.5 * horizontal_fov) * static_cast<double>(height) / width);
}

namespace {

std::string directoryOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// Reads the motion fields of an agent section; the caller checks for unknown keys.
void readMotion(YamlFields& f, MotionOptions& m) {
  const std::string mode =
      f.text("speed_mode", m.mode == SpeedMode::kConstant ? "constant" : "accelerate", {"constant", "accelerate"});
  m.mode = mode == "constant" ? SpeedMode::kConstant : SpeedMode::kAccelerate;
  m.speed = f.number("speed", m.speed, 0.0, 20.0);
  m.max_speed = f.number("max_speed", m.max_speed, 0.0, 20.0);
  m.acceleration = f.number("acceleration", m.acceleration, 0.0, 100.0);
  m.turn_rate = f.number("turn_rate_deg", m.turn_rate * 180.0 / kPi, 1.0, 3600.0) * kPi / 180.0;
  const std::string model = f.text(
      "accelerate_model", m.accelerate_model == AccelerateModel::kBrake ? "brake" : "momentum", {"brake", "momentum"});
  m.accelerate_model = model == "brake" ? AccelerateModel::kBrake : AccelerateModel::kMomentum;
  m.drag = f.number("drag", m.drag, 0.0, 100.0);
}

// Applies one file's fields over opts; unknown keys are errors. A game file that extends none is
// the one source of the game's defaults: it must give every key (`base`). A file that extends
// one, and a variant file, give only what they change.
void applyGameFields(const YAML::Node& root, const std::string& source, GameOptions& g, VariantConfig* variant,
                     std::string* maps_dir = nullptr, bool base = false) {
  YamlFields f(root, source, "");
  // A section of this file, every key required in a base file.
  auto section = [&](const char* name) {
    if (base) f.require(name);
    YamlFields s(f.child(name), source, name);
    if (base) s.requireEveryKey();
    return s;
  };
  if (maps_dir) {
    // Only a game file says where its maps are; `extends` was followed by the caller.
    if (f.has("extends")) f.text("extends", "", {});
    if (base) f.requireEveryKey();
    *maps_dir = f.text("maps_dir", *maps_dir, {});
    g.name = f.text("game", g.name, {});
  }
  if (variant) {
    variant->name = f.text("variant", "", {});
    if (variant->name.empty()) throw ConfigError(source, "variant", "is required");
    variant->map_file = f.text("map", "", {});
    if (variant->map_file.empty()) throw ConfigError(source, "map", "is required");
  }
  {
    YamlFields p = section("physics");
    g.physics_dt = p.number("dt", g.physics_dt, 1e-4, 1.0);
    g.action_repeat = p.integer("action_repeat", g.action_repeat, 1, 1000);
    p.rejectUnknown();
  }
  {
    YamlFields e = section("episode");
    g.max_steps = e.integer("max_steps", g.max_steps, 1, 1000000);
    g.capture_distance = e.number("capture_distance", g.capture_distance, 0.0, 10.0);
    g.min_spawn_distance = e.number("min_spawn_distance", g.min_spawn_distance, 0.0, 50.0);
    e.rejectUnknown();
  }
  {
    YamlFields a = section("agents");
    g.agent_radius = a.number("radius", g.agent_radius, 0.05, 2.0);
    g.agent_height = a.number("height", g.agent_height, 0.1, 5.0);
    a.rejectUnknown();
  }
  {
    YamlFields h = section("hider");
    readMotion(h, g.hider);
    h.rejectUnknown();
  }
  {
    YamlFields s = section("seeker");
    readMotion(s, g.seeker);
    // The policy belongs to the variant; the game defaults file has none.
    if (variant) variant->seeker_policy = s.text("policy", "deterministic", {"deterministic", "stochastic"});
    g.seeker_decision_frames = s.integer("decision_frames", g.seeker_decision_frames, 1, 1000);
    g.seeker_knows_spawn = s.boolean("knows_spawn", g.seeker_knows_spawn);
    const std::string steering =
        s.text("steering", g.seeker_steering == SeekerSteering::kTurnOrMove ? "turn_or_move" : "turn_while_moving",
               {"turn_or_move", "turn_while_moving"});
    g.seeker_steering = steering == "turn_or_move" ? SeekerSteering::kTurnOrMove : SeekerSteering::kTurnWhileMoving;
    g.seeker_move_angle = s.number("move_angle_deg", g.seeker_move_angle * 180.0 / kPi, 0.0, 180.0) * kPi / 180.0;
    const std::string following = s.text(
        "path_following", g.seeker_path_following == SeekerPathFollowing::kNextPoint ? "next_point" : "no_backtrack",
        {"next_point", "no_backtrack"});
    g.seeker_path_following =
        following == "next_point" ? SeekerPathFollowing::kNextPoint : SeekerPathFollowing::kNoBacktrack;
    s.rejectUnknown();
  }
  {
    YamlFields c = section("camera");
    g.camera.width = c.integer("width", g.camera.width, 8, 1024);
    g.camera.height = c.integer("height", g.camera.height, 8, 1024);
    g.camera.horizontal_fov =
        c.number("horizontal_fov_deg", g.camera.horizontal_fov * 180.0 / kPi, 10.0, 170.0) * kPi / 180.0;
    g.camera.mount_height = c.number("mount_height", g.camera.mount_height, 0.05, 5.0);
    g.camera.near_clip = c.number("near_clip", g.camera.near_clip, 1e-3, 1.0);
    g.camera.far_clip = c.number("far_clip", g.camera.far_clip, 1.0, 1000.0);
    c.rejectUnknown();
  }
  for (auto [name, rewards] : {std::pair{"rewards", &g.rewards}, std::pair{"seeker_rewards", &g.seeker_rewards}}) {
    YamlFields r = section(name);
    rewards->survive = r.number("survive", rewards->survive, -10.0, 10.0);
    rewards->capture = r.number("capture", rewards->capture, -100.0, 100.0);
    rewards->visibility = r.boolean("visibility", rewards->visibility);
    rewards->unseen = r.number("unseen", rewards->unseen, -10.0, 10.0);
    rewards->seen = r.number("seen", rewards->seen, -10.0, 10.0);
    r.rejectUnknown();
  }
  f.rejectUnknown();
  if (g.camera.mount_height >= g.agent_height) {
    throw ConfigError(source, "camera.mount_height", "must be below agents.height");
  }
  // Spawns are min_spawn_distance apart: within capture_distance an episode would end at its spawn.
  if (g.min_spawn_distance <= g.capture_distance) {
    std::ostringstream m;
    m << "(" << g.min_spawn_distance << " m) must exceed episode.capture_distance (" << g.capture_distance
      << " m), or the agents may spawn captured; a file that sets either must keep the two apart";
    throw ConfigError(source, "episode.min_spawn_distance", m.str());
  }
  if (g.action_repeat % g.seeker_decision_frames != 0) {
    throw ConfigError(source, "seeker.decision_frames",
                      "must divide physics.action_repeat (" + std::to_string(g.action_repeat) + ")");
  }
}

constexpr int kMaxExtends = 8;  // a longer chain of game files is a loop

// Applies a game file and, first, the files it extends; returns its maps folder.
std::string applyGameFile(const std::string& path, GameOptions& g, int depth) {
  if (depth > kMaxExtends) throw ConfigError(path, "extends", "is a chain of more than 8 files (a loop?)");
  const YAML::Node root = loadYamlFile(path);
  std::string maps_dir = "maps";
  if (root.IsMap() && root["extends"]) {
    if (!root["extends"].IsScalar()) throw ConfigError(path, "extends", "must be a file name");
    std::string base = root["extends"].Scalar();
    if (base.empty() || base.front() != '/') base = directoryOf(path) + "/" + base;
    maps_dir = applyGameFile(base, g, depth + 1);
    // The base's maps_dir is relative to the base; re-anchor it for this file.
    if (maps_dir.front() != '/') maps_dir = directoryOf(base) + "/" + maps_dir;
  }
  applyGameFields(root, path, g, nullptr, &maps_dir, !(root.IsMap() && root["extends"]));
  if (maps_dir.empty()) throw ConfigError(path, "maps_dir", "must not be empty");
  return maps_dir;
}

}  // namespace

GameOptions withLearnedSeeker(GameOptions game) {
  game.seeker_decision_frames = game.action_repeat;
  return game;
}

VariantConfig loadVariantConfig(const std::string& game_file, const std::string& variant_file) {
  VariantConfig v;
  std::string maps_dir;
  // Resolved from an absolute path: an extended file's maps_dir is re-anchored at its own folder,
  // which for a relative game file (config/game_v3.yaml) is relative too, and was prefixed twice.
  const std::string game_path = std::filesystem::absolute(game_file).lexically_normal().string();
  try {
    maps_dir = applyGameFile(game_path, v.game, 0);
  } catch (const YAML::Exception& e) {  // what the fields' checks did not foresee still names the file
    throw ConfigError(game_file, "<file>", e.what());
  }
  if (maps_dir.front() != '/') maps_dir = directoryOf(game_path) + "/" + maps_dir;
  try {
    applyGameFields(loadYamlFile(variant_file), variant_file, v.game, &v);
  } catch (const YAML::Exception& e) {
    throw ConfigError(variant_file, "<file>", e.what());
  }
  v.source = variant_file;
  v.game_file = game_file;
  if (v.map_file.front() != '/') v.map_file = maps_dir + "/" + v.map_file;
  return v;
}

}  // namespace hideseek_game
