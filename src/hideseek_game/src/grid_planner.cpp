#include "hideseek_game/grid_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace hideseek_game {

bool sameFootprints(const Layout& a, const Layout& b) {
  if (a.half_extent != b.half_extent || a.obstacles.size() != b.obstacles.size()) return false;
  for (size_t i = 0; i < a.obstacles.size(); ++i) {
    const Box& p = a.obstacles[i];
    const Box& q = b.obstacles[i];
    if (p.center.x != q.center.x || p.center.y != q.center.y || p.size.x != q.size.x || p.size.y != q.size.y ||
        p.yaw != q.yaw) {
      return false;
    }
  }
  return true;
}

GridPlanner::GridPlanner(const Layout& layout, double inflation, double resolution)
    : grid_(layout, inflation, resolution) {}

GridCell GridPlanner::nearestFree(GridCell c) const {
  c.x = std::clamp(c.x, 0, grid_.width() - 1);
  c.y = std::clamp(c.y, 0, grid_.height() - 1);
  if (grid_.isFree(c)) return c;
  // Rings of growing radius: an agent pressed against an obstacle stands just inside the inflation.
  for (int r = 1; r < std::max(grid_.width(), grid_.height()); ++r) {
    GridCell best{-1, -1};
    double best_d = std::numeric_limits<double>::max();
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        if (std::max(std::abs(dx), std::abs(dy)) != r) continue;
        const GridCell n{c.x + dx, c.y + dy};
        const double d = dx * dx + dy * dy;
        if (grid_.isFree(n) && d < best_d) {
          best = n;
          best_d = d;
        }
      }
    }
    if (best.x >= 0) return best;
  }
  return c;
}

bool GridPlanner::lineOfSight(Vec2 a, Vec2 b) const {
  const double len = hideseek_game::distance(a, b);
  const int samples = std::max(1, static_cast<int>(std::ceil(len / (0.5 * grid_.resolution()))));
  for (int i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) / samples;
    if (!isFree({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)})) return false;
  }
  return true;
}

std::vector<Vec2> GridPlanner::plan(Vec2 from, Vec2 to) const {
  const GridCell start = nearestFree(grid_.cellOf(from));
  const GridCell goal = nearestFree(grid_.cellOf(to));
  if (!grid_.isFree(start) || !grid_.isFree(goal) || grid_.component(start) != grid_.component(goal)) return {};
  const int n = grid_.width() * grid_.height();
  std::vector<double> cost(n, std::numeric_limits<double>::infinity());
  std::vector<int> parent(n, -1);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  auto heuristic = [&](GridCell c) {
    const double dx = std::abs(c.x - goal.x), dy = std::abs(c.y - goal.y);
    return std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy);  // octile
  };
  const int s = grid_.index(start), g = grid_.index(goal);
  cost[s] = 0.0;
  open.push({heuristic(start), s});
  while (!open.empty()) {
    // Plain copies, not a structured binding: the lambda below captures them (clang 14 refuses a
    // captured binding).
    const double f = open.top().first;
    const int i = open.top().second;
    open.pop();
    if (i == g) break;
    const GridCell c{i % grid_.width(), i / grid_.width()};
    if (f - heuristic(c) > cost[i] + 1e-9) continue;  // stale entry
    forEachNeighbour(c, [&](GridCell nb, double step) {
      const int j = grid_.index(nb);
      const double next = cost[i] + step;
      if (next < cost[j]) {
        cost[j] = next;
        parent[j] = i;
        open.push({next + heuristic(nb), j});
      }
    });
  }
  if (parent[g] < 0 && g != s) return {};
  std::vector<Vec2> cells;
  for (int i = g; i != -1; i = parent[i]) cells.push_back(grid_.centerOf({i % grid_.width(), i / grid_.width()}));
  std::reverse(cells.begin(), cells.end());
  // String pulling: keep only the cells where a straight line from the last kept one breaks.
  std::vector<Vec2> path;
  Vec2 anchor = cells.front();
  for (size_t k = 1; k < cells.size(); ++k) {
    if (!lineOfSight(anchor, cells[k])) {
      anchor = cells[k - 1];
      path.push_back(anchor);
    }
  }
  path.push_back(cells.back());
  return path;
}

std::vector<float> GridPlanner::distancesFrom(Vec2 from) const {
  std::vector<float> out(static_cast<size_t>(grid_.width()) * grid_.height(), std::numeric_limits<float>::infinity());
  const GridCell start = nearestFree(grid_.cellOf(from));
  if (!grid_.isFree(start)) return out;
  // Dijkstra over the same moves as plan().
  using Entry = std::pair<float, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const float resolution = static_cast<float>(grid_.resolution());
  out[grid_.index(start)] = 0.f;
  open.push({0.f, grid_.index(start)});
  while (!open.empty()) {
    const float d = open.top().first;
    const int i = open.top().second;
    open.pop();
    if (d > out[i]) continue;
    forEachNeighbour({i % grid_.width(), i / grid_.width()}, [&](GridCell nb, double step) {
      const float next = d + resolution * static_cast<float>(step);
      const int j = grid_.index(nb);
      if (next < out[j]) {
        out[j] = next;
        open.push({next, j});
      }
    });
  }
  return out;
}

Vec2 GridPlanner::randomReachablePoint(Vec2 from, std::mt19937& rng) const {
  const int component = grid_.component(nearestFree(grid_.cellOf(from)));
  std::uniform_int_distribution<int> x(0, grid_.width() - 1), y(0, grid_.height() - 1);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const GridCell c{x(rng), y(rng)};
    if (grid_.component(c) == component) return grid_.centerOf(c);
  }
  return from;
}

}  // namespace hideseek_game
