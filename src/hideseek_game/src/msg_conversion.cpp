#include "hideseek_game/msg_conversion.h"

#include <cmath>

#include "hideseek_game/free_space_grid.h"
#include "hideseek_game/visibility.h"

namespace hideseek_game {

geometry_msgs::Pose2D toPose2D(const AgentState& agent) {
  geometry_msgs::Pose2D p;
  p.x = agent.position.x;
  p.y = agent.position.y;
  p.theta = agent.yaw;
  return p;
}

hideseek_msgs::ArenaMap toArenaMap(const Layout& layout) {
  hideseek_msgs::ArenaMap m;
  m.half_extent = static_cast<float>(layout.half_extent);
  for (const Box& b : layout.obstacles) {
    hideseek_msgs::Box box;
    box.x = static_cast<float>(b.center.x);
    box.y = static_cast<float>(b.center.y);
    box.size_x = static_cast<float>(b.size.x);
    box.size_y = static_cast<float>(b.size.y);
    box.height = static_cast<float>(b.height);
    box.yaw = static_cast<float>(b.yaw);
    m.obstacles.push_back(box);
  }
  for (const Vec2& w : layout.waypoints) {
    geometry_msgs::Point p;
    p.x = w.x;
    p.y = w.y;
    m.waypoints.push_back(p);
  }
  return m;
}

nav_msgs::OccupancyGrid toOccupancyGrid(const Layout& layout, double resolution, const std::string& frame_id) {
  // A grid inflated by nothing marks exactly the cells whose centre lies in an obstacle.
  const FreeSpaceGrid grid(layout, 0.0, resolution);
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = frame_id;
  msg.info.resolution = static_cast<float>(resolution);
  msg.info.width = grid.width();
  msg.info.height = grid.height();
  msg.info.origin.position.x = grid.originX();
  msg.info.origin.position.y = grid.originY();
  msg.info.origin.orientation.w = 1.0;
  msg.data.resize(static_cast<size_t>(grid.width()) * grid.height());
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) msg.data[grid.index({x, y})] = grid.isFree({x, y}) ? 0 : 100;
  }
  return msg;
}

sensor_msgs::CameraInfo toCameraInfo(const CameraOptions& camera, const std::string& optical_frame) {
  sensor_msgs::CameraInfo info;
  info.header.frame_id = optical_frame;
  info.width = camera.width;
  info.height = camera.height;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  const double fx = 0.5 * camera.width / std::tan(0.5 * camera.horizontal_fov);
  const double fy = 0.5 * camera.height / std::tan(0.5 * camera.verticalFov());
  // ROS puts pixel centres at integer coordinates (image_geometry, OpenCV): the image spans
  // [-0.5, width - 0.5], so a symmetric frustum's principal point is (width - 1) / 2.
  const double cx = 0.5 * (camera.width - 1), cy = 0.5 * (camera.height - 1);
  info.K = {fx, 0, cx, 0, fy, cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0};
  return info;
}

geometry_msgs::TransformStamped agentTransform(const AgentState& agent, const std::string& parent,
                                               const std::string& child, const ros::Time& stamp) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = agent.position.x;
  t.transform.translation.y = agent.position.y;
  t.transform.rotation.z = std::sin(0.5 * agent.yaw);
  t.transform.rotation.w = std::cos(0.5 * agent.yaw);
  return t;
}

namespace {

std_msgs::ColorRGBA color(const Rgb& c, float alpha) {
  std_msgs::ColorRGBA out;
  out.r = c.r;
  out.g = c.g;
  out.b = c.b;
  out.a = alpha;
  return out;
}

visualization_msgs::Marker boxMarker(const Box& b, int id, const std::string& ns, const Rgb& c) {
  visualization_msgs::Marker m;
  m.ns = ns;
  m.id = id;
  m.type = visualization_msgs::Marker::CUBE;
  m.pose.position.x = b.center.x;
  m.pose.position.y = b.center.y;
  m.pose.position.z = 0.5 * b.height;
  m.pose.orientation.z = std::sin(0.5 * b.yaw);
  m.pose.orientation.w = std::cos(0.5 * b.yaw);
  m.scale.x = b.size.x;
  m.scale.y = b.size.y;
  m.scale.z = b.height;
  m.color = color(c, 1.f);
  return m;
}

// The view cone on the floor: a fan over the horizontal field of view whose rays stop where the
// camera's sight line meets an obstacle or a wall.
visualization_msgs::Marker coneMarker(const AgentState& a, const CameraOptions& camera, const Layout& layout,
                                      const std::string& ns, bool sees_other) {
  constexpr int kRays = 48;
  constexpr double kMaxRange = 50.0;  // m: beyond any arena; the walls stop every ray first
  visualization_msgs::Marker m;
  m.ns = ns;
  m.type = visualization_msgs::Marker::TRIANGLE_LIST;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  m.color = sees_other ? color({0.1f, 0.85f, 0.2f}, 0.45f) : color({0.6f, 0.6f, 0.6f}, 0.3f);
  geometry_msgs::Point apex;
  apex.x = a.position.x;
  apex.y = a.position.y;
  apex.z = 0.02;
  auto end = [&](int i) {
    const double yaw = a.yaw - 0.5 * camera.horizontal_fov + camera.horizontal_fov * i / kRays;
    const double r = sightRange(a.position, yaw, camera.mount_height, layout, kMaxRange);
    geometry_msgs::Point p = apex;
    p.x += r * std::cos(yaw);
    p.y += r * std::sin(yaw);
    return p;
  };
  geometry_msgs::Point previous = end(0);
  for (int i = 1; i <= kRays; ++i) {
    const geometry_msgs::Point next = end(i);
    m.points.push_back(apex);
    m.points.push_back(previous);
    m.points.push_back(next);
    previous = next;
  }
  return m;
}

visualization_msgs::Marker agentMarker(const AgentState& a, const GameOptions& g, const std::string& ns, const Rgb& c) {
  visualization_msgs::Marker m;
  m.ns = ns;
  m.type = visualization_msgs::Marker::CYLINDER;
  m.pose.position.x = a.position.x;
  m.pose.position.y = a.position.y;
  m.pose.position.z = 0.5 * g.agent_height;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = 2.0 * g.agent_radius;
  m.scale.z = g.agent_height;
  m.color = color(c, 1.f);
  return m;
}

}  // namespace

visualization_msgs::MarkerArray toMarkers(const Arena& arena, const std::string& frame_id, const ros::Time& stamp) {
  visualization_msgs::MarkerArray out;
  const MapColors& colors = arena.map().colors;
  const Layout& layout = arena.layout();
  visualization_msgs::Marker clear;
  clear.action = visualization_msgs::Marker::DELETEALL;
  out.markers.push_back(clear);
  int id = 0;
  for (const Box& b : layout.obstacles) {
    out.markers.push_back(
        boxMarker(b, id++, b.wall ? "wall_cuts" : "obstacles", b.wall ? colors.wall : colors.obstacle));
  }
  id = 0;
  for (const Box& b : wallBoxes(layout.half_extent, layout.wall_height)) {
    out.markers.push_back(boxMarker(b, id++, "walls", colors.wall));
  }
  const GameOptions& g = arena.options();
  out.markers.push_back(agentMarker(arena.hider(), g, "hider", colors.hider));
  out.markers.push_back(agentMarker(arena.seeker(), g, "seeker", colors.seeker));
  out.markers.push_back(
      coneMarker(arena.hider(), g.camera, arena.layout(), "hider_view", arena.labels().hider_sees_seeker));
  out.markers.push_back(
      coneMarker(arena.seeker(), g.camera, arena.layout(), "seeker_view", arena.labels().seeker_sees_hider));
  for (auto& m : out.markers) {
    m.header.frame_id = frame_id;
    m.header.stamp = stamp;
  }
  return out;
}

hideseek_msgs::StepBatch beginStepBatch(const World& world, uint64_t decision, const uint8_t* images, int image_every) {
  const int n = world.numArenas();
  hideseek_msgs::StepBatch b;
  b.decision = decision;
  b.num_arenas = static_cast<uint32_t>(n);
  for (int i = 0; i < n; ++i) {
    const Arena& a = world.arena(i);
    b.episode.push_back(world.episode(i));
    b.seed.push_back(a.seed());
    b.step.push_back(static_cast<uint32_t>(a.stepCount()));
    b.hider_pose.push_back(toPose2D(a.hider()));
    b.seeker_pose.push_back(toPose2D(a.seeker()));
    b.distance.push_back(static_cast<float>(distance(a.hider().position, a.seeker().position)));
    b.hider_sees_seeker.push_back(a.labels().hider_sees_seeker);
    b.seeker_sees_hider.push_back(a.labels().seeker_sees_hider);
    b.obstacle_in_view.push_back(a.labels().obstacle_in_view);
  }
  b.image_every = static_cast<uint32_t>(image_every);
  b.height = static_cast<uint32_t>(world.options().camera.height);
  b.width = static_cast<uint32_t>(world.options().camera.width);
  if (image_every > 0 && decision % static_cast<uint64_t>(image_every) == 0) {
    b.images.assign(images, images + world.imageBytes() * n);
  }
  return b;
}

void finishStepBatch(const std::vector<ArenaStep>& results, const std::vector<Action>& hider,
                     const std::vector<Action>& seeker, hideseek_msgs::StepBatch& batch) {
  for (size_t i = 0; i < results.size(); ++i) {
    batch.hider_action.push_back(static_cast<uint8_t>(hider[i]));
    batch.seeker_action.push_back(static_cast<uint8_t>(seeker[i]));
    batch.reward.push_back(static_cast<float>(results[i].result.reward));
    batch.outcome.push_back(static_cast<uint8_t>(results[i].result.outcome));
  }
}

hideseek_msgs::ObservationBatch toObservationBatch(const World& world, const std::vector<uint8_t>& images,
                                                   const std::vector<float>& rewards, const std::vector<uint8_t>& done,
                                                   const std::vector<uint8_t>& outcome) {
  hideseek_msgs::ObservationBatch obs;
  const int n = world.numArenas();
  obs.num_arenas = static_cast<uint32_t>(n);
  obs.height = static_cast<uint32_t>(world.options().camera.height);
  obs.width = static_cast<uint32_t>(world.options().camera.width);
  obs.images = images;
  obs.rewards = rewards;
  obs.done = done;
  obs.outcome = outcome;
  for (int i = 0; i < n; ++i) {
    const Arena& a = world.arena(i);
    obs.step.push_back(static_cast<uint32_t>(a.stepCount()));
    obs.episode.push_back(world.episode(i));
    obs.seed.push_back(a.seed());
    obs.hider_sees_seeker.push_back(a.labels().hider_sees_seeker);
    obs.seeker_sees_hider.push_back(a.labels().seeker_sees_hider);
    obs.obstacle_in_view.push_back(a.labels().obstacle_in_view);
    obs.hider_pose.push_back(toPose2D(a.hider()));
    obs.seeker_pose.push_back(toPose2D(a.seeker()));
  }
  return obs;
}

const std::vector<hideseek_msgs::ArenaMap>& ArenaMapCache::update(const World& world) {
  const size_t n = static_cast<size_t>(world.numArenas());
  if (maps_.size() != n) {
    maps_.assign(n, {});
    versions_.assign(n, ~uint64_t{0});  // no map built yet
  }
  for (size_t i = 0; i < n; ++i) {
    const Arena& a = world.arena(static_cast<int>(i));
    if (versions_[i] != a.layoutVersion()) {
      maps_[i] = toArenaMap(a.layout());
      versions_[i] = a.layoutVersion();
    }
  }
  return maps_;
}

hideseek_msgs::SeekerObservationBatch toSeekerObservationBatch(const World& world, const std::vector<uint8_t>& done,
                                                               const std::vector<hideseek_msgs::ArenaMap>& maps,
                                                               const std::vector<float>& rewards,
                                                               const std::vector<uint8_t>& outcome,
                                                               const std::vector<uint8_t>& images) {
  hideseek_msgs::SeekerObservationBatch seen;
  const int n = world.numArenas();
  seen.num_arenas = static_cast<uint32_t>(n);
  seen.done = done;
  seen.maps = maps;
  seen.rewards = rewards;
  seen.outcome = outcome;
  seen.height = static_cast<uint32_t>(world.options().camera.height);
  seen.width = static_cast<uint32_t>(world.options().camera.width);
  seen.images = images;
  for (int i = 0; i < n; ++i) {
    const Arena& a = world.arena(i);
    const SeekerPerception perception = seekerPerception(a);
    seen.pose.push_back(toPose2D(perception.pose));
    seen.sees_hider.push_back(perception.hider_position.has_value());
    geometry_msgs::Point hider;
    if (perception.hider_position) {
      hider.x = perception.hider_position->x;
      hider.y = perception.hider_position->y;
    }
    seen.hider_position.push_back(hider);
    seen.step.push_back(world.seekerDecisionId(i));
    seen.episode.push_back(world.episode(i));
    seen.seed.push_back(a.seed());
  }
  return seen;
}

hideseek_msgs::GameState toGameState(const World& world, const std::optional<EpisodeSummary>& finished,
                                     Action hider_action, Action seeker_action, float reward, uint8_t outcome) {
  const Arena& a = world.arena(0);
  hideseek_msgs::GameState state;
  state.arena = 0;
  const AgentState& hider = finished ? finished->hider : a.hider();
  const AgentState& seeker = finished ? finished->seeker : a.seeker();
  const Labels& labels = finished ? finished->labels : a.labels();
  state.episode = finished ? finished->episode : world.episode(0);
  state.seed = finished ? finished->seed : a.seed();
  state.step = static_cast<uint32_t>(finished ? finished->steps : a.stepCount());
  state.hider_pose = toPose2D(hider);
  state.seeker_pose = toPose2D(seeker);
  state.hider_speed = static_cast<float>(hider.speed);
  state.seeker_speed = static_cast<float>(seeker.speed);
  state.hider_action = static_cast<uint8_t>(hider_action);
  state.seeker_action = static_cast<uint8_t>(seeker_action);
  state.hider_sees_seeker = labels.hider_sees_seeker;
  state.seeker_sees_hider = labels.seeker_sees_hider;
  state.obstacle_in_view = labels.obstacle_in_view;
  state.distance = static_cast<float>(distance(hider.position, seeker.position));
  state.reward = reward;
  state.episode_return = static_cast<float>(finished ? finished->episode_return : a.episodeReturn());
  state.outcome = outcome;
  return state;
}

namespace {

// The first array whose length is not the arena count, or "".
std::string firstWrongLength(size_t n, std::initializer_list<std::pair<const char*, size_t>> arrays) {
  for (const auto& [name, size] : arrays) {
    if (size != n)
      return std::string(name) + " has " + std::to_string(size) + " entries for " + std::to_string(n) + " arenas";
  }
  return "";
}

// "" for n RGB8 images of height x width in `images`, as the message says they are; else what is wrong.
std::string imagesProblem(size_t n, uint32_t msg_height, uint32_t msg_width, size_t bytes, int height, int width,
                          const char* who) {
  if (msg_height != static_cast<uint32_t>(height) || msg_width != static_cast<uint32_t>(width)) {
    return "images of " + std::to_string(msg_height) + "x" + std::to_string(msg_width) + ", the " + who + " sees " +
           std::to_string(height) + "x" + std::to_string(width);
  }
  if (bytes != n * static_cast<size_t>(height) * width * 3) {
    return std::to_string(bytes) + " image bytes for " + std::to_string(n) + " RGB8 images";
  }
  return "";
}

}  // namespace

std::string checkObservationBatch(const hideseek_msgs::ObservationBatch& msg, int height, int width,
                                  size_t max_arenas) {
  const size_t n = msg.num_arenas;
  if (n == 0 || n > max_arenas) return "num_arenas " + std::to_string(n) + " (1 to " + std::to_string(max_arenas) + ")";
  const std::string images = imagesProblem(n, msg.height, msg.width, msg.images.size(), height, width, "hider");
  if (!images.empty()) return images;
  return firstWrongLength(n, {{"step", msg.step.size()},
                              {"seed", msg.seed.size()},
                              {"rewards", msg.rewards.size()},
                              {"done", msg.done.size()}});
}

std::string checkSeekerObservationBatch(const hideseek_msgs::SeekerObservationBatch& msg, size_t max_arenas, int height,
                                        int width) {
  const size_t n = msg.num_arenas;
  if (n == 0 || n > max_arenas) return "num_arenas " + std::to_string(n) + " (1 to " + std::to_string(max_arenas) + ")";
  const std::string wrong = firstWrongLength(n, {{"pose", msg.pose.size()},
                                                 {"sees_hider", msg.sees_hider.size()},
                                                 {"hider_position", msg.hider_position.size()},
                                                 {"done", msg.done.size()},
                                                 {"step", msg.step.size()},
                                                 {"episode", msg.episode.size()},
                                                 {"seed", msg.seed.size()},
                                                 {"maps", msg.maps.size()},
                                                 {"rewards", msg.rewards.size()},
                                                 {"outcome", msg.outcome.size()}});
  if (!wrong.empty() || height == 0) return wrong;
  if (msg.images.empty()) {
    return "no images: a learning seeker needs the world's seeker cameras (the world's ~learned_seeker, which the "
           "launch "
           "files set for seeker_mode:=random, policy or train)";
  }
  return imagesProblem(n, msg.height, msg.width, msg.images.size(), height, width, "seeker");
}

}  // namespace hideseek_game
