#include "dlmfd/fluid/boundary_profile.h"

#include <cmath>
#include <string>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/core/side_names.h"

namespace dlmfd {
namespace {

// The normal component of the side's data (value for uniform, max otherwise).
double NormalComponent(Side side, const BoundarySide& b) {
  const Vec2& data = b.profile == Profile::kUniform ? b.value : b.max;
  return (side == Side::kLeft || side == Side::kRight) ? data.x() : data.y();
}

}  // namespace

Vec2 ProfileVelocity(const BoundarySide& side, double s) {
  if (side.type != SideType::kVelocity) return Vec2::Zero();
  switch (side.profile) {
    case Profile::kUniform:
      return side.value;
    case Profile::kPoiseuille:
      return 4.0 * s * (1.0 - s) * side.max;
    case Profile::kQuartic: {
      const double b = s * (1.0 - s);
      return 16.0 * b * b * side.max;
    }
  }
  return Vec2::Zero();
}

double RampFactor(const BoundarySide& side, double t) {
  if (!(side.ramp_time > 0.0)) return 1.0;
  return 0.5 * (1.0 + std::tanh(4.0 * (t / side.ramp_time - 1.0)));
}

double ProfilePeakSpeed(const BoundarySide& side) {
  if (side.type != SideType::kVelocity) return 0.0;
  return side.profile == Profile::kUniform ? side.value.norm() : side.max.norm();
}

void ValidateBoundaryProfiles(const DomainParams& domain) {
  for (int s = 0; s < 4; ++s) {
    const Side side = static_cast<Side>(s);
    const BoundarySide& b = domain.side(side);
    if (b.type != SideType::kVelocity) continue;
    const std::string prefix = std::string("domain.boundary.") + SideName(s);
    if (!(b.ramp_time >= 0.0 && std::isfinite(b.ramp_time))) {
      throw InvalidParameter(prefix + ".ramp_time", ExactText(b.ramp_time),
                             "a finite number >= 0 (0: steady data)");
    }
    const double normal = NormalComponent(side, b);
    const char* tangential = (side == Side::kLeft || side == Side::kRight)
                                 ? "[0, v] on a left or right side"
                                 : "[u, 0] on a bottom or top side";
    if (b.profile == Profile::kQuartic && normal != 0.0) {
      throw InvalidParameter(prefix + ".max", VecText(b.max),
                             std::string("a tangential velocity, ") + tangential +
                                 ", for the quartic profile (a lid: no liquid enters through it)");
    }
    if (b.ramp_time > 0.0 && normal != 0.0) {
      throw InvalidParameter(prefix + ".ramp_time", ExactText(b.ramp_time),
                             std::string("0 on a side whose data have a normal component (") +
                                 (b.profile == Profile::kUniform ? "value = " + VecText(b.value)
                                                                 : "max = " + VecText(b.max)) +
                                 "): only tangential data, " + tangential +
                                 ", may be ramped (inflow states are steady)");
    }
  }
}

}  // namespace dlmfd
