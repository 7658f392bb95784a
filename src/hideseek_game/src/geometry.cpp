#include "hideseek_game/geometry.h"

#include <algorithm>
#include <limits>

namespace hideseek_game {

double wrapAngle(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

namespace {

Vec2 toBoxFrame(const Box& box, Vec2 p) {
  const Vec2 d = p - box.center;
  const double c = box.cos_yaw, s = box.sin_yaw;
  return {c * d.x + s * d.y, -s * d.x + c * d.y};
}

Vec2 fromBoxFrame(const Box& box, Vec2 q) {
  const double c = box.cos_yaw, s = box.sin_yaw;
  return {box.center.x + c * q.x - s * q.y, box.center.y + s * q.x + c * q.y};
}

}  // namespace

Vec2 closestPointOnFootprint(const Box& box, Vec2 p) {
  const Vec2 q = toBoxFrame(box, p);
  const double hx = 0.5 * box.size.x, hy = 0.5 * box.size.y;
  return fromBoxFrame(box, {std::clamp(q.x, -hx, hx), std::clamp(q.y, -hy, hy)});
}

double footprintDistance(const Box& box, Vec2 p) {
  const Vec2 q = toBoxFrame(box, p);
  const double dx = std::abs(q.x) - 0.5 * box.size.x;
  const double dy = std::abs(q.y) - 0.5 * box.size.y;
  const double outside = std::hypot(std::max(dx, 0.0), std::max(dy, 0.0));
  return outside + std::min(std::max(dx, dy), 0.0);
}

bool footprintOverlapsSquare(const Box& box, double half_extent) {
  const double hx = 0.5 * box.size.x, hy = 0.5 * box.size.y, c = box.cos_yaw, s = box.sin_yaw;
  // The box's half-widths along the world axes, and the square's along the box's axes.
  const double box_x = hx * std::abs(c) + hy * std::abs(s), box_y = hx * std::abs(s) + hy * std::abs(c);
  const double square_u = half_extent * (std::abs(c) + std::abs(s)), square_v = square_u;
  const Vec2 q = toBoxFrame(box, {0.0, 0.0});  // the square's centre in the box's frame
  return std::abs(box.center.x) < half_extent + box_x && std::abs(box.center.y) < half_extent + box_y &&
         std::abs(q.x) < hx + square_u && std::abs(q.y) < hy + square_v;
}

bool pushCircleOut(const Box& box, double radius, Vec2& center) {
  const Vec2 q = toBoxFrame(box, center);
  const double hx = 0.5 * box.size.x, hy = 0.5 * box.size.y;
  const Vec2 c{std::clamp(q.x, -hx, hx), std::clamp(q.y, -hy, hy)};
  const Vec2 d = q - c;
  const double dist = norm(d);
  if (dist >= radius) return false;
  Vec2 out;
  if (dist > 1e-9) {
    out = c + (radius / dist) * d;
  } else {
    // Centre inside the footprint: leave through the nearest face.
    const double px = hx - std::abs(q.x), py = hy - std::abs(q.y);
    if (px < py) {
      out = {std::copysign(hx + radius, q.x == 0.0 ? 1.0 : q.x), q.y};
    } else {
      out = {q.x, std::copysign(hy + radius, q.y == 0.0 ? 1.0 : q.y)};
    }
  }
  center = fromBoxFrame(box, out);
  return true;
}

double segmentEntry(const Box& box, const Vec3& a, const Vec3& b) {
  // Slab test in the box frame.
  const Vec2 qa = toBoxFrame(box, {a.x, a.y});
  const Vec2 qb = toBoxFrame(box, {b.x, b.y});
  const double o[3] = {qa.x, qa.y, a.z};
  const double d[3] = {qb.x - qa.x, qb.y - qa.y, b.z - a.z};
  const double lo[3] = {-0.5 * box.size.x, -0.5 * box.size.y, 0.0};
  const double hi[3] = {0.5 * box.size.x, 0.5 * box.size.y, box.height};
  double t0 = 0.0, t1 = 1.0;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (o[i] < lo[i] || o[i] > hi[i]) return 2.0;
      continue;
    }
    double ta = (lo[i] - o[i]) / d[i];
    double tb = (hi[i] - o[i]) / d[i];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return 2.0;
  }
  return t0;
}

bool segmentHitsBox(const Box& box, const Vec3& a, const Vec3& b) { return segmentEntry(box, a, b) <= 1.0; }

Bounds footprintBounds(const Box& box, double margin) {
  const double c = std::abs(box.cos_yaw), s = std::abs(box.sin_yaw);
  const double ex = 0.5 * (c * box.size.x + s * box.size.y) + margin;
  const double ey = 0.5 * (s * box.size.x + c * box.size.y) + margin;
  return {box.center.x - ex, box.center.y - ey, box.center.x + ex, box.center.y + ey};
}

}  // namespace hideseek_game
