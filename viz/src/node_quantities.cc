// Derived node quantities of a snapshot: vorticity by finite differences, speed.
#include "dlmfd/viz/node_quantities.h"

#include <algorithm>
#include <cmath>

namespace dlmfd {
namespace {

// df/ds at node k of a line of n nodes spaced h apart, f(k) = value(k).
template <typename Value>
double Derivative(int k, int n, double h, Value value) {
  if (k == 0) return (-3.0 * value(0) + 4.0 * value(1) - value(2)) / (2.0 * h);
  if (k == n - 1) return (3.0 * value(n - 1) - 4.0 * value(n - 2) + value(n - 3)) / (2.0 * h);
  return (value(k + 1) - value(k - 1)) / (2.0 * h);
}

}  // namespace

const std::vector<std::string>& PictureQuantities() {
  static const std::vector<std::string> kNames = {
      "trA", "trA-2", "log10(trA/2)", "speed", "vorticity", "A11", "A12", "A22", "pressure"};
  return kNames;
}

std::string PictureQuantityList() {
  std::string text;
  for (const std::string& q : PictureQuantities()) text += (text.empty() ? "" : ", ") + q;
  return text;
}

bool IsSignedQuantity(const std::string& quantity) {
  return quantity == "vorticity" || quantity == "A12" || quantity == "pressure";
}

std::string QuantityDimensions(const std::string& quantity) {
  if (quantity == "speed") return "L T-1";
  if (quantity == "vorticity") return "T-1";
  if (quantity == "pressure") return "M L-1 T-2";
  return "1";
}

std::vector<std::string> DatasetsOf(const std::string& quantity) {
  if (quantity == "speed" || quantity == "vorticity") return {"u", "v"};
  if (quantity == "pressure") return {"p"};
  if (quantity == "A11" || quantity == "A12" || quantity == "A22") return {quantity};
  return {"trA"};
}

std::vector<double> NodeVorticity(const Grid& g, const std::vector<double>& u,
                                  const std::vector<double>& v) {
  std::vector<double> omega(g.NodeCount());
  const int nx = g.NodesX();
  const int ny = g.NodesY();
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double dv_dx = Derivative(i, nx, g.h, [&](int a) { return v[g.Index(a, j)]; });
      const double du_dy = Derivative(j, ny, g.h, [&](int b) { return u[g.Index(i, b)]; });
      omega[g.Index(i, j)] = dv_dx - du_dy;
    }
  }
  return omega;
}

std::vector<double> NodeSpeed(const std::vector<double>& u, const std::vector<double>& v) {
  std::vector<double> speed(std::min(u.size(), v.size()));
  for (std::size_t k = 0; k < speed.size(); ++k) speed[k] = std::hypot(u[k], v[k]);
  return speed;
}

}  // namespace dlmfd
