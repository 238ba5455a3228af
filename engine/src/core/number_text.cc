#include "dlmfd/core/number_text.h"

#include <cstdio>
#include <cstdlib>

namespace dlmfd {

std::string ExactText(double x) {
  char buffer[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (std::strtod(buffer, nullptr) == x) break;
  }
  std::string text = buffer;
  // TOML needs a '.' or an exponent to read a float.
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

std::string ShortText(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", x);
  return buffer;
}

std::string VecText(const Eigen::Vector2d& v) {
  return "[" + ExactText(v.x()) + ", " + ExactText(v.y()) + "]";
}

}  // namespace dlmfd
