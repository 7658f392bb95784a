// A grid over the arena marking where an agent centre fits, with connectivity.
#pragma once

#include <vector>

#include "hideseek_game/map.h"

namespace hideseek_game {

struct GridCell {
  int x = 0;
  int y = 0;
};

// Cells are free when a disc of `inflation` radius at their centre touches no obstacle or wall.
class FreeSpaceGrid {
 public:
  FreeSpaceGrid(const Layout& layout, double inflation, double resolution);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  double originX() const { return -half_extent_; }
  double originY() const { return -half_extent_; }

  bool inside(GridCell c) const { return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_; }
  bool isFree(GridCell c) const { return inside(c) && free_[index(c)]; }
  GridCell cellOf(Vec2 p) const;
  Vec2 centerOf(GridCell c) const;
  int index(GridCell c) const { return c.y * width_ + c.x; }

  // True when both points lie in free cells of one connected (8-neighbour) region.
  bool connected(Vec2 a, Vec2 b) const;
  // Label of the free region holding the cell, -1 for occupied cells.
  int component(GridCell c) const;

 private:
  void labelComponents() const;

  double half_extent_;
  double resolution_;
  int width_;
  int height_;
  std::vector<char> free_;
  mutable std::vector<int> component_;  // computed on first use
};

}  // namespace hideseek_game
