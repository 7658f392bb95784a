// Shortest collision-free paths on a map inflated by an agent's radius (A* and distance fields):
// the scripted seeker plans with it, and so do the scripted evaders.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "hideseek_game/free_space_grid.h"

namespace hideseek_game {

// Whether two layouts have the same arena and obstacle footprints: all a planner's grid depends on.
bool sameFootprints(const Layout& a, const Layout& b);

class GridPlanner {
 public:
  GridPlanner(const Layout& layout, double inflation, double resolution);

  // Waypoints from `from` to `to` (both snapped to the nearest free cell), shortened to the
  // corners where the straight line would leave free space. Empty when no path exists.
  std::vector<Vec2> plan(Vec2 from, Vec2 to) const;
  // Shortest path lengths (m) from `from` (snapped to the nearest free cell) to every cell, indexed
  // like grid(); infinity where unreachable or occupied.
  std::vector<float> distancesFrom(Vec2 from) const;
  // True when the straight segment stays in free cells.
  bool lineOfSight(Vec2 a, Vec2 b) const;
  // A uniformly drawn free cell centre reachable from `from`.
  Vec2 randomReachablePoint(Vec2 from, std::mt19937& rng) const;
  bool isFree(Vec2 p) const { return grid_.isFree(grid_.cellOf(p)); }
  const FreeSpaceGrid& grid() const { return grid_; }

 private:
  GridCell nearestFree(GridCell c) const;
  // Calls visit(neighbour, step length in cells) for the free 8-neighbours of c; a diagonal step
  // needs both cells beside it free, so paths never cut an obstacle's corner.
  template <typename Visit>
  void forEachNeighbour(GridCell c, Visit visit) const;

  FreeSpaceGrid grid_;
};

template <typename Visit>
void GridPlanner::forEachNeighbour(GridCell c, Visit visit) const {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (!dx && !dy) continue;
      const GridCell nb{c.x + dx, c.y + dy};
      if (!grid_.isFree(nb)) continue;
      if (dx && dy && (!grid_.isFree({c.x + dx, c.y}) || !grid_.isFree({c.x, c.y + dy}))) continue;
      visit(nb, (dx && dy) ? std::sqrt(2.0) : 1.0);
    }
  }
}

}  // namespace hideseek_game
