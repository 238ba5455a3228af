// fields.xmf (design.md 3.2): the field snapshots as XDMF, so that ParaView opens the whole series
// in the X-Y plane with the velocity as a vector and the disks as points. A spatial collection
// "fields" of temporal collections, one per grid, each over the snapshots: "velocity_mesh" (u, v,
// the vector velocity, and trA, A11, A12, A22 when present), "pressure_mesh" (p on the 2h mesh)
// and, when a snapshot holds its particles (results format 2) and has some, "particles": one
// Polyvertex point per particle at its centre (x, y, 0) with the attributes radius, velocity
// (u, v, 0), angular_velocity, angle and id, which ParaView's Glyph filter draws as disks (scale by
// radius). A temporal collection of spatial collections (before issue 35) made ParaView 5.11's
// XDMF Reader and Xdmf3ReaderT name the blocks "velocity_mesh[1]" from the second time on, so a
// block selected by name had 0 points there; with one temporal collection per grid the XDMF Reader
// keeps the names at every time and the Xdmf3 readers give the blocks in the same order at every
// time (measured: docs/results.md).
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

#include <cstddef>
#include <string>
#include <vector>

#include "dlmfd/core/grid.h"

namespace dlmfd {

struct XdmfEntry {
  std::string file;  // relative to the folder of fields.xmf, e.g. "fields/snap_000010.h5"
  double time = 0.0;
  std::size_t particles = 0;        // in the snapshot's /particles group (0: no particle grid)
  bool particle_angles = false;     // whether it has /particles/angle
  bool particle_semi_axes = false;  // whether it has /particles/semi_axes (issue 37 on)
};

std::string FieldsXdmfText(const Grid& grid, const std::vector<XdmfEntry>& entries,
                           bool has_conformation);
void WriteFieldsXdmf(const std::string& path, const Grid& grid,
                     const std::vector<XdmfEntry>& entries, bool has_conformation);

}  // namespace dlmfd
