#include "hideseek_game/free_space_grid.h"

#include <algorithm>
#include <cmath>

namespace hideseek_game {

FreeSpaceGrid::FreeSpaceGrid(const Layout& layout, double inflation, double resolution)
    : half_extent_(layout.half_extent),
      resolution_(resolution),
      width_(static_cast<int>(std::ceil(2.0 * layout.half_extent / resolution))),
      height_(width_),
      free_(static_cast<size_t>(width_) * height_, 1) {
  const double limit = half_extent_ - inflation;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const Vec2 c = centerOf({x, y});
      if (std::abs(c.x) > limit || std::abs(c.y) > limit) free_[index({x, y})] = 0;
    }
  }
  // Only cells inside each box's grown bounds need the exact test.
  for (const Box& box : layout.obstacles) {
    const Bounds b = footprintBounds(box, inflation);
    const GridCell lo = cellOf({b.min_x, b.min_y});
    const GridCell hi = cellOf({b.max_x, b.max_y});
    for (int y = std::max(lo.y, 0); y <= std::min(hi.y, height_ - 1); ++y) {
      for (int x = std::max(lo.x, 0); x <= std::min(hi.x, width_ - 1); ++x) {
        if (footprintDistance(box, centerOf({x, y})) < inflation) free_[index({x, y})] = 0;
      }
    }
  }
}

GridCell FreeSpaceGrid::cellOf(Vec2 p) const {
  return {static_cast<int>(std::floor((p.x + half_extent_) / resolution_)),
          static_cast<int>(std::floor((p.y + half_extent_) / resolution_))};
}

Vec2 FreeSpaceGrid::centerOf(GridCell c) const {
  return {-half_extent_ + (c.x + 0.5) * resolution_, -half_extent_ + (c.y + 0.5) * resolution_};
}

void FreeSpaceGrid::labelComponents() const {
  component_.assign(free_.size(), -1);
  std::vector<int> stack;
  int label = 0;
  for (int start = 0; start < static_cast<int>(free_.size()); ++start) {
    if (!free_[start] || component_[start] >= 0) continue;
    component_[start] = label;
    stack.push_back(start);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      const int cx = i % width_, cy = i / width_;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const GridCell n{cx + dx, cy + dy};
          if (!isFree(n)) continue;
          // A diagonal move must not cut an occupied corner.
          if (dx != 0 && dy != 0 && (!isFree({cx + dx, cy}) || !isFree({cx, cy + dy}))) continue;
          const int j = index(n);
          if (component_[j] >= 0) continue;
          component_[j] = label;
          stack.push_back(j);
        }
      }
    }
    ++label;
  }
}

int FreeSpaceGrid::component(GridCell c) const {
  if (!isFree(c)) return -1;
  if (component_.empty()) labelComponents();
  return component_[index(c)];
}

bool FreeSpaceGrid::connected(Vec2 a, Vec2 b) const {
  const int ca = component(cellOf(a));
  return ca >= 0 && ca == component(cellOf(b));
}

}  // namespace hideseek_game
