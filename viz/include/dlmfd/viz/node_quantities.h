// The quantities a field picture can show, derived from the datasets of a snapshot (design.md
// 3.2): trA, trA - 2 (the polymer's stretch above its rest state, trA = 2 for A = I in 2-D),
// log10(trA / 2), the speed |u|, the vorticity, the components A11, A12, A22, and the pressure
// (on the 2h mesh).
//
// Method: the vorticity omega = dv/dx - du/dy at the nodes by second-order finite differences on
// the uniform mesh (centred inside, the one-sided three-point formula on the sides), the other
// quantities node by node. log10(trA / 2) of a non-positive trA (never, for an SPD A) is NaN.
// Signed quantities, whose sign is the physics and whose zero is a state of its own: the vorticity
// (the sense of rotation), A12 (the sign of the shear stretch; 0 in the rest state A = I) and the
// pressure (mean-free, or 0 on an outflow side). Pictures draw them on a diverging map centred on
// zero (colour_scale.h); trA, trA-2, log10(trA/2), the speed, A11 and A22 on a sequential one. Not
// supported: the stream function, polymer stress components.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/grid.h"

namespace dlmfd {

// The names accepted, in the order of the help text.
const std::vector<std::string>& PictureQuantities();
// "trA, trA-2, ..." for messages.
std::string PictureQuantityList();
// True for "vorticity", "A12" and "pressure" (above).
bool IsSignedQuantity(const std::string& quantity);
// The dimensions of a quantity in the scene's units (results_format.h): "L T-1" for the speed,
// "T-1" for the vorticity, "M L-1 T-2" for the pressure, "1" for the conformation's.
std::string QuantityDimensions(const std::string& quantity);
// The snapshot datasets a quantity needs ("trA"; "u", "v"; "p"; "A11" ...).
std::vector<std::string> DatasetsOf(const std::string& quantity);
// omega = dv/dx - du/dy at the nodes of `grid` (at least 2 x 2 cells).
std::vector<double> NodeVorticity(const Grid& grid, const std::vector<double>& u,
                                  const std::vector<double>& v);
// |u| at each node.
std::vector<double> NodeSpeed(const std::vector<double>& u, const std::vector<double>& v);

}  // namespace dlmfd
