// The velocity data of one side of the rectangle (paper (1)-(3): u = u_Gamma on Gamma) as a
// function of the arc-length fraction s in [0, 1] along the side (0 at its bottom or left corner)
// and of the time t:
//   u_Gamma(s, t) = g(t) phi(s).
// Profile phi (`domain.boundary.SIDE.profile`):
//   uniform     phi(s) = value;
//   poiseuille  phi(s) = 4 s (1 - s) max            (the parabola; zero at both corners);
//   quartic     phi(s) = 16 s^2 (1 - s)^2 max       (a regularised lid: value and slope zero at
//                                                    both corners, max at mid-side).
// Ramp g (`...SIDE.ramp_time` T): g = 1 for T = 0 (steady data, the default); for T > 0
//   g(t) = (1 + tanh(4 (t / T - 1))) / 2,
//   half at t = T, 3.4e-4 at t = 0 and 1 - 3.4e-4 at t = 2T.
// The lid-driven cavity of Fattal & Kupferman (2005), u(x, t) = 8 [1 + tanh(8 (t - 1/2))]
//   x^2 (1 - x)^2 on the top of the unit square, is the quartic profile with max = [1, 0] and
//   T = 1/2: 16 x^2 (1 - x)^2 (1 + tanh(4 (2 t - 1))) / 2 is the same function.
// Rules (ValidateBoundaryProfiles, part of the scene validation): ramp_time is finite and >= 0; a
//   quartic side and a ramped side carry tangential data only (normal component 0: [u, 0] on the
//   bottom or top, [0, v] on the left or right). So no liquid enters through them: they need no
//   inflow conformation state (conformation/inflow_state.h knows the steady states of uniform and
//   poiseuille inflows only, and no time-dependent one), and the flux through every side of a
//   closed domain stays zero at every time.
// Reference: R. Fattal & R. Kupferman, Time-dependent simulation of viscoelastic flows at high
//   Weissenberg number using the log-conformation representation, J. Non-Newtonian Fluid Mech. 126
//   (2005) 23-37, section 4 (the lid-driven cavity).
#pragma once

#include "dlmfd/core/params.h"

namespace dlmfd {

// phi(s) of a velocity side (zero for any other side), s in [0, 1].
Vec2 ProfileVelocity(const BoundarySide& side, double s);
// g(t) of a side: 1 without a ramp.
double RampFactor(const BoundarySide& side, double t);
// The largest |phi(s)| over the side (the peak of its data over all times; 0 for a non-velocity
// side).
double ProfilePeakSpeed(const BoundarySide& side);
// The rules above; InvalidParameter naming domain.boundary.SIDE.ramp_time or .max otherwise.
void ValidateBoundaryProfiles(const DomainParams& domain);

}  // namespace dlmfd
