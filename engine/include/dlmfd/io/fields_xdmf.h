// fields.xmf (design.md 3.2): an XDMF temporal collection over the field snapshots, so that
// ParaView opens the whole series in the X-Y plane with the velocity as a vector. Each time is a
// spatial collection of two uniform grids: "velocity_mesh" (u, v, the vector velocity, and trA,
// A11, A12, A22 when present) and "pressure_mesh" (p on the 2h mesh).
//
// Each mesh is a 3DCoRectMesh of one layer, Dimensions "1 ny+1 nx+1" (slowest first, as XDMF
// orders them), with ORIGIN_DXDYDZ geometry "0 y0 x0" and "1 h h" (z first): VTK's XDMF readers
// reverse the order into (x, y, z), so the field has bounds (x0, x0 + W, y0, y0 + H, 0, 0). A
// 2DCoRectMesh would be read with its two axes as y and z (the field edge-on in ParaView's default
// view). The velocity is the snapshot's stored /velocity (u, v, 0): ParaView's readers take a
// vector attribute only with 3 components, and the XDMF3 readers evaluate no Function/JOIN item
// (measured with Debian 12's ParaView 5.11, XDMF Reader, Xdmf3ReaderS and Xdmf3ReaderT:
// docs/results.md). Heavy data of shape (ny+1, nx+1) are declared "1 ny+1 nx+1", the topology's
// shape, which both reader generations accept. The heavy data stay in the snapshot files,
// referenced by relative path. Rewritten (temporary name, rename) after each snapshot.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/grid.h"

namespace dlmfd {

struct XdmfEntry {
  std::string file;  // relative to the folder of fields.xmf, e.g. "fields/snap_000010.h5"
  double time = 0.0;
};

std::string FieldsXdmfText(const Grid& grid, const std::vector<XdmfEntry>& entries,
                           bool has_conformation);
void WriteFieldsXdmf(const std::string& path, const Grid& grid,
                     const std::vector<XdmfEntry>& entries, bool has_conformation);

}  // namespace dlmfd
