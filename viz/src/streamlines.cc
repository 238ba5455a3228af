// Streamlines: seeds on a lattice, RK2 in arc length, an occupancy grid for even spacing.
#include "dlmfd/viz/streamlines.h"

#include <algorithm>
#include <cmath>

#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

struct Occupancy {
  int nx = 0, ny = 0;
  double cell = 1.0, x0 = 0.0, y0 = 0.0;
  std::vector<int> owner;  // line index + 1, 0 free
  std::vector<long> when;  // the step count at which the owner entered the cell
  long clock = 0;          // steps taken so far, all lines
  long Index(double x, double y) const {
    const int i = int(std::floor((x - x0) / cell));
    const int j = int(std::floor((y - y0) / cell));
    if (i < 0 || j < 0 || i >= nx || j >= ny) return -1;
    return long(j) * nx + i;
  }
  int* At(double x, double y) {
    const long k = Index(x, y);
    return k < 0 ? nullptr : &owner[std::size_t(k)];
  }
};

// The unit direction of the velocity at (x, y), or false where it has none.
bool Direction(const NodeVelocity& f, double x, double y, double& dx, double& dy) {
  const double u = InterpolateP1(f.u, x, y);
  const double v = InterpolateP1(f.v, x, y);
  const double speed = std::hypot(u, v);
  if (!std::isfinite(speed) || !(speed > 1e-300)) return false;
  dx = u / speed;
  dy = v / speed;
  return true;
}

// Points from (x, y) along +-u (sign), until a stop rule holds; (x, y) itself is not included.
std::vector<double> Trace(const NodeVelocity& f, Occupancy& grid, int line, double x, double y,
                          double sign, double step, int max_steps) {
  const Grid& g = f.u.grid;
  std::vector<double> points;
  for (int k = 0; k < max_steps; ++k) {
    double ax, ay, bx, by;
    if (!Direction(f, x, y, ax, ay)) break;
    const double mx = x + 0.5 * sign * step * ax, my = y + 0.5 * sign * step * ay;
    if (!Direction(f, mx, my, bx, by)) break;
    const double nx = x + sign * step * bx, ny = y + sign * step * by;
    if (nx < g.x0 || ny < g.y0 || nx > g.x0 + g.Width() || ny > g.y0 + g.Height()) break;
    const long at = grid.Index(nx, ny);
    if (at < 0) break;
    int& owner = grid.owner[std::size_t(at)];
    long& when = grid.when[std::size_t(at)];
    ++grid.clock;
    // Another line's cell, or its own entered long ago (a closed line has come round).
    if ((owner != 0 && owner != line + 1) || (owner == line + 1 && grid.clock - when > 20)) break;
    if (owner == 0) when = grid.clock;
    owner = line + 1;
    points.insert(points.end(), {nx, ny});
    x = nx;
    y = ny;
  }
  return points;
}

}  // namespace

std::vector<std::vector<double>> Streamlines(const NodeVelocity& velocity, int columns) {
  const Grid& g = velocity.u.grid;
  const Grid& gv = velocity.v.grid;
  if (columns < 1) throw InvalidParameter("streamlines", std::to_string(columns), "1 or more");
  if (g.nx != gv.nx || g.ny != gv.ny || g.h != gv.h || g.x0 != gv.x0 || g.y0 != gv.y0 ||
      velocity.u.values.size() != g.NodeCount() || velocity.v.values.size() != g.NodeCount()) {
    throw InvalidParameter("streamlines", "u and v on different grids", "u and v on one grid");
  }
  const double d = g.Width() / columns;
  Occupancy grid;
  grid.cell = 0.5 * d;
  grid.x0 = g.x0;
  grid.y0 = g.y0;
  grid.nx = std::max(1, int(std::ceil(g.Width() / grid.cell)));
  grid.ny = std::max(1, int(std::ceil(g.Height() / grid.cell)));
  grid.owner.assign(std::size_t(grid.nx) * std::size_t(grid.ny), 0);
  grid.when.assign(grid.owner.size(), 0);
  const double step = d / 10.0;
  const int max_steps = int(40.0 * (g.Width() + g.Height()) / d);
  const int rows = std::max(1, int(std::floor(g.Height() / d)));
  const double y_start = g.y0 + 0.5 * (g.Height() - rows * d);
  std::vector<std::vector<double>> lines;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      const double x = g.x0 + (i + 0.5) * d;
      const double y = y_start + (j + 0.5) * d;
      int* seed = grid.At(x, y);
      if (seed == nullptr || *seed != 0) continue;
      const int line = int(lines.size());
      *seed = line + 1;
      grid.when[std::size_t(grid.Index(x, y))] = ++grid.clock;
      const std::vector<double> back = Trace(velocity, grid, line, x, y, -1.0, step, max_steps);
      grid.when[std::size_t(grid.Index(x, y))] = grid.clock;  // forwards starts afresh here
      const std::vector<double> ahead = Trace(velocity, grid, line, x, y, 1.0, step, max_steps);
      std::vector<double> points;
      for (std::size_t k = back.size(); k >= 2; k -= 2)
        points.insert(points.end(), {back[k - 2], back[k - 1]});
      points.insert(points.end(), {x, y});
      points.insert(points.end(), ahead.begin(), ahead.end());
      if (points.size() >= 6) {
        lines.push_back(std::move(points));
      } else {
        lines.emplace_back();  // keeps the line index of its cells; dropped below
      }
    }
  }
  lines.erase(std::remove_if(lines.begin(), lines.end(),
                             [](const std::vector<double>& l) { return l.empty(); }),
              lines.end());
  return lines;
}

}  // namespace dlmfd
