// IsolineSegments: marching squares on the SW-NE triangles of the mesh.
#include "dlmfd/viz/isolines.h"

#include <cmath>

namespace dlmfd {
namespace {

struct Vertex {
  double x, y, f;
};

// Appends the segment of {f = c} across the triangle (a, b, d), if it crosses.
void CrossTriangle(const Vertex& a, const Vertex& b, const Vertex& d, double c,
                   std::vector<double>& out) {
  if (!std::isfinite(a.f) || !std::isfinite(b.f) || !std::isfinite(d.f)) return;
  const Vertex* v[3] = {&a, &b, &d};
  double points[4];
  int found = 0;
  for (int e = 0; e < 3 && found < 2; ++e) {
    const Vertex& p = *v[e];
    const Vertex& q = *v[(e + 1) % 3];
    if ((p.f >= c) == (q.f >= c)) continue;
    const double t = (c - p.f) / (q.f - p.f);
    points[2 * found] = p.x + t * (q.x - p.x);
    points[2 * found + 1] = p.y + t * (q.y - p.y);
    ++found;
  }
  if (found == 2) out.insert(out.end(), points, points + 4);
}

}  // namespace

std::vector<double> IsolineSegments(const NodeField& field, double level) {
  const Grid& g = field.grid;
  std::vector<double> segments;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const Vertex sw{g.X(i), g.Y(j), field.values[g.Index(i, j)]};
      const Vertex se{g.X(i + 1), g.Y(j), field.values[g.Index(i + 1, j)]};
      const Vertex ne{g.X(i + 1), g.Y(j + 1), field.values[g.Index(i + 1, j + 1)]};
      const Vertex nw{g.X(i), g.Y(j + 1), field.values[g.Index(i, j + 1)]};
      CrossTriangle(sw, se, ne, level, segments);
      CrossTriangle(sw, ne, nw, level, segments);
    }
  }
  return segments;
}

std::vector<double> Isovalues(double lo, double hi, int count, bool log) {
  std::vector<double> values;
  if (count <= 0 || !(lo < hi) || (log && !(lo > 0.0))) return values;
  const double a = log ? std::log10(lo) : lo;
  const double b = log ? std::log10(hi) : hi;
  for (int k = 1; k <= count; ++k) {
    const double t = a + k * (b - a) / (count + 1);
    values.push_back(log ? std::pow(10.0, t) : t);
  }
  return values;
}

}  // namespace dlmfd
