// Uniform node grids of the P1-iso-P2 / P1 discretisation (paper section 3).
//
// The domain [x0, x0 + nx h] x [y0, y0 + ny h] is cut into squares of side h, each split by its
// SW-NE diagonal. Velocity and the configuration tensor A live on the nodes of this h-grid; the
// pressure lives on the nodes of the 2h-grid (every other velocity node). Node (i, j), i = 0..nx,
// j = 0..ny, is stored at Index(i, j) = j (nx + 1) + i: x fastest, the layout of every field array
// and of the snapshot files (design.md 3.2). With periodic sides the last node column/row repeats
// the first and is kept equal to it.
#pragma once

#include <cstddef>

namespace dlmfd {

struct Grid {
  int nx = 0;      // cells in x
  int ny = 0;      // cells in y
  double h = 0.0;  // cell size
  double x0 = 0.0;
  double y0 = 0.0;

  int NodesX() const { return nx + 1; }
  int NodesY() const { return ny + 1; }
  std::size_t NodeCount() const { return std::size_t(nx + 1) * std::size_t(ny + 1); }
  std::size_t Index(int i, int j) const {
    return std::size_t(j) * std::size_t(nx + 1) + std::size_t(i);
  }
  double X(int i) const { return x0 + i * h; }
  double Y(int j) const { return y0 + j * h; }
  double Width() const { return nx * h; }
  double Height() const { return ny * h; }
  // The pressure grid: spacing 2h over the same domain (nx and ny must be even).
  Grid Coarse() const { return Grid{nx / 2, ny / 2, 2.0 * h, x0, y0}; }
};

}  // namespace dlmfd
