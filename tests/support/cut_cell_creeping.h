// The creeping fixed disk of the cut-cell studies (docs/work_precision.md, "A second-order
// boundary: the engine's cut cells"): D = 0.1 at (0.2 + s h, 0.2) in a 0.8 x 0.4 channel,
// Poiseuille inflow of maximum 0.3, eta = 1, steady Stokes. Its drag's reference is the Richardson
// limit of the position means of the prototype at D/h = 20-40-80.
#pragma once

namespace dlmfd {

inline constexpr double kCutCreepingReference = 6.487;

}  // namespace dlmfd
