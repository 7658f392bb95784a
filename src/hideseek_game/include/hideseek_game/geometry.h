// Planar and 3D geometry shared by physics, visibility and planning.
#pragma once

#include <cmath>

namespace hideseek_game {

constexpr double kPi = 3.14159265358979323846;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }
inline double distance(Vec2 a, Vec2 b) { return norm(a - b); }

// Wraps an angle to (-pi, pi].
double wrapAngle(double a);

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

// An upright box standing on the floor (z from 0 to height), rotated by yaw.
// cos/sin of yaw are cached because every physics and visibility query needs them.
struct Box {
  Vec2 center;
  Vec2 size;  // full extents along the box's own axes
  double height = 1.5;
  double yaw = 0.0;
  double cos_yaw = 1.0;
  double sin_yaw = 0.0;
  // Part of the arena's boundary (drawn in the walls' colour, never counted by the O label);
  // it blocks and hides like any obstacle.
  bool wall = false;

  static Box make(Vec2 center, Vec2 size, double height, double yaw) {
    return {center, size, height, yaw, std::cos(yaw), std::sin(yaw)};
  }
};

// Point of the box's footprint closest to p (p itself when inside).
Vec2 closestPointOnFootprint(const Box& box, Vec2 p);

// Signed distance from p to the footprint: negative inside.
double footprintDistance(const Box& box, Vec2 p);

// Pushes a circle out of the box footprint; returns true if it overlapped.
bool pushCircleOut(const Box& box, double radius, Vec2& center);

// True when the 3D segment a-b passes through the solid box.
bool segmentHitsBox(const Box& box, const Vec3& a, const Vec3& b);

// Parameter t in [0, 1] where the segment a-b first enters the box, or a value > 1 when it misses.
double segmentEntry(const Box& box, const Vec3& a, const Vec3& b);

// True when the footprint and the open square (-half_extent, half_extent)^2 share some area (a box
// that only touches the square's edge does not): separating axes, the square's two and the box's two.
bool footprintOverlapsSquare(const Box& box, double half_extent);

// Axis-aligned bounds of the footprint grown by margin.
struct Bounds {
  double min_x, min_y, max_x, max_y;
};
Bounds footprintBounds(const Box& box, double margin);

}  // namespace hideseek_game
