// Shortest collision-free paths for the seeker: A* on the map inflated by its radius.
#pragma once

#include <random>
#include <vector>

#include "hideseek_world/free_space_grid.h"

namespace hideseek_seeker {

using hideseek_world::GridCell;
using hideseek_world::Layout;
using hideseek_world::Vec2;

// Whether two layouts have the same arena and obstacle footprints: all a planner's grid depends on.
bool sameFootprints(const Layout& a, const Layout& b);

class GridPlanner {
 public:
  GridPlanner(const Layout& layout, double inflation, double resolution);

  // Waypoints from `from` to `to` (both snapped to the nearest free cell), shortened to the
  // corners where the straight line would leave free space. Empty when no path exists.
  std::vector<Vec2> plan(Vec2 from, Vec2 to) const;
  // True when the straight segment stays in free cells.
  bool lineOfSight(Vec2 a, Vec2 b) const;
  // A uniformly drawn free cell centre reachable from `from`.
  Vec2 randomReachablePoint(Vec2 from, std::mt19937& rng) const;
  bool isFree(Vec2 p) const { return grid_.isFree(grid_.cellOf(p)); }
  const hideseek_world::FreeSpaceGrid& grid() const { return grid_; }

 private:
  GridCell nearestFree(GridCell c) const;

  hideseek_world::FreeSpaceGrid grid_;
};

}  // namespace hideseek_seeker
