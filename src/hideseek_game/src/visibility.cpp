#include "hideseek_game/visibility.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace hideseek_game {

namespace {

// The viewer's camera: where it is and the tangents of its half fields of view, reduced to the
// centres of the outermost pixels: a point outside them covers no pixel centre of the image.
struct Frustum {
  Vec3 eye;
  Vec2 forward;
  double tan_half_h;
  double tan_half_v;
  double near_clip;
  double half_pixel;  // tangent of half a pixel's angular width at the image centre

  Frustum(const AgentState& viewer, const CameraOptions& camera)
      : eye{viewer.position.x, viewer.position.y, camera.mount_height},
        forward{std::cos(viewer.yaw), std::sin(viewer.yaw)},
        tan_half_h(std::tan(0.5 * camera.horizontal_fov) * (1.0 - 1.0 / camera.width)),
        tan_half_v(std::tan(0.5 * camera.verticalFov()) * (1.0 - 1.0 / camera.height)),
        near_clip(camera.near_clip),
        half_pixel(std::tan(0.5 * camera.horizontal_fov) / camera.width) {}

  double depth(const Vec3& p) const { return (p.x - eye.x) * forward.x + (p.y - eye.y) * forward.y; }

  bool contains(const Vec3& p) const {
    const double dx = p.x - eye.x, dy = p.y - eye.y;
    const double depth = dx * forward.x + dy * forward.y;
    if (depth <= near_clip) return false;
    const double lateral = -dx * forward.y + dy * forward.x;
    return std::abs(lateral) <= tan_half_h * depth && std::abs(p.z - eye.z) <= tan_half_v * depth;
  }
};

bool occluded(const Layout& layout, const Vec3& a, const Vec3& b, const Box* except) {
  for (const Box& box : layout.obstacles) {
    if (&box != except && segmentHitsBox(box, a, b)) return true;
  }
  return false;
}

}  // namespace

bool agentSeesAgent(const AgentState& viewer, const AgentState& target, const Layout& layout,
                    const GameOptions& options) {
  const Frustum frustum(viewer, options.camera);
  const Vec2 to_target = target.position - viewer.position;
  const double d = norm(to_target);
  if (d < 1e-9) return true;
  const Vec2 toward{to_target.x / d, to_target.y / d};
  const Vec2 side{-toward.y, toward.x};
  const double r = options.agent_radius;
  // Silhouette as the viewer sees it: the near face and, slightly inset, both side edges, at
  // several heights. The inset keeps sub-pixel slivers at the rim from counting as seen.
  constexpr std::array<double, 5> kLateral = {0.0, -0.9, 0.9, -0.6, 0.6};
  constexpr std::array<double, 5> kHeight = {0.5, 0.05, 0.95, 0.25, 0.75};
  for (double lateral : kLateral) {
    const double depth = -std::sqrt(1.0 - lateral * lateral) * r;
    const Vec2 base = target.position + (lateral * r) * side + depth * toward;
    for (double h : kHeight) {
      const Vec3 p{base.x, base.y, h * options.agent_height};
      if (!frustum.contains(p)) continue;
      // A sliver narrower than a pixel past an obstacle's edge covers no pixel centre: the sight
      // lines half a pixel to either side must be clear too.
      const double shift = frustum.half_pixel * frustum.depth(p);
      const Vec3 left{p.x + shift * side.x, p.y + shift * side.y, p.z};
      const Vec3 right{p.x - shift * side.x, p.y - shift * side.y, p.z};
      if (!occluded(layout, frustum.eye, p, nullptr) && !occluded(layout, frustum.eye, left, nullptr) &&
          !occluded(layout, frustum.eye, right, nullptr)) {
        return true;
      }
    }
  }
  return false;
}

bool obstacleInView(const AgentState& viewer, const Layout& layout, const GameOptions& options) {
  if (layout.obstacles.empty()) return false;
  const Frustum frustum(viewer, options.camera);
  // Points on each box: corners at the floor and the top, and the side centres at eye height.
  for (const Box& box : layout.obstacles) {
    if (box.wall) continue;
    const double hx = 0.5 * box.size.x, hy = 0.5 * box.size.y;
    const double c = box.cos_yaw, s = box.sin_yaw;
    const std::array<Vec2, 8> local = {Vec2{hx, hy},  Vec2{-hx, hy},  Vec2{-hx, -hy}, Vec2{hx, -hy},
                                       Vec2{hx, 0.0}, Vec2{-hx, 0.0}, Vec2{0.0, hy},  Vec2{0.0, -hy}};
    for (size_t i = 0; i < local.size(); ++i) {
      const Vec2 w{box.center.x + c * local[i].x - s * local[i].y, box.center.y + s * local[i].x + c * local[i].y};
      const std::array<double, 3> heights = {0.0, std::min(box.height, frustum.eye.z), box.height};
      for (double z : heights) {
        const Vec3 p{w.x, w.y, z};
        if (frustum.contains(p) && !occluded(layout, frustum.eye, p, &box)) return true;
      }
    }
  }
  // A box wider than the view shows none of its corners: cast rays across the view instead.
  constexpr int kRays = 15;
  const double reach = 4.0 * layout.half_extent;
  const std::vector<Box> walls = wallBoxes(layout.half_extent, layout.wall_height);
  for (int i = 0; i < kRays; ++i) {
    const double u = -1.0 + 2.0 * i / (kRays - 1);
    const double lateral = u * frustum.tan_half_h;
    const Vec2 dir{frustum.forward.x - lateral * frustum.forward.y, frustum.forward.y + lateral * frustum.forward.x};
    for (double v : {-0.9, 0.0}) {
      const Vec3 end{frustum.eye.x + reach * dir.x, frustum.eye.y + reach * dir.y,
                     frustum.eye.z + v * frustum.tan_half_v * reach};
      double nearest_wall = 2.0;
      for (const Box& w : walls) {
        nearest_wall = std::min(nearest_wall, segmentEntry(w, frustum.eye, end));
      }
      for (const Box& w : layout.obstacles) {
        if (w.wall) nearest_wall = std::min(nearest_wall, segmentEntry(w, frustum.eye, end));
      }
      const double floor_t = end.z < frustum.eye.z ? frustum.eye.z / (frustum.eye.z - end.z) : 2.0;
      const double limit = std::min(nearest_wall, floor_t);
      for (const Box& box : layout.obstacles) {
        if (!box.wall && segmentEntry(box, frustum.eye, end) < limit) return true;
      }
    }
  }
  return false;
}

double sightRange(Vec2 origin, double yaw, double height, const Layout& layout, double max_range) {
  const double dx = std::cos(yaw), dy = std::sin(yaw);
  double range = max_range;
  // The walls: the first of x = +-half_extent, y = +-half_extent the ray reaches.
  const double h = layout.half_extent;
  if (dx > 1e-12) range = std::min(range, (h - origin.x) / dx);
  if (dx < -1e-12) range = std::min(range, (-h - origin.x) / dx);
  if (dy > 1e-12) range = std::min(range, (h - origin.y) / dy);
  if (dy < -1e-12) range = std::min(range, (-h - origin.y) / dy);
  range = std::max(range, 0.0);
  const Vec3 a{origin.x, origin.y, height};
  const Vec3 b{origin.x + range * dx, origin.y + range * dy, height};
  for (const Box& box : layout.obstacles) {
    if (height >= box.height) continue;  // a sight line above the box passes over it
    const double t = segmentEntry(box, a, b);
    if (t <= 1.0) range = std::min(range, std::max(t, 0.0) * std::hypot(b.x - a.x, b.y - a.y));
  }
  return range;
}

}  // namespace hideseek_game
