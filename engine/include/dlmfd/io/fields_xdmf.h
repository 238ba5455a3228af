// fields.xmf (design.md 3.2): an XDMF 3 temporal collection over the field snapshots, so that
// ParaView (XDMF3 reader) opens the whole series. Each time is a spatial collection of two uniform
// grids, 2DCoRectMesh with ORIGIN_DXDY geometry: "velocity_mesh" (u, v, the vector velocity =
// JOIN(u, v), and trA, A11, A12, A22 when present) and "pressure_mesh" (p on the 2h mesh). The
// heavy data stay in the snapshot files, referenced by relative path. Rewritten (temporary name,
// rename) after each snapshot.
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
