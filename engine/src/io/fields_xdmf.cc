#include "dlmfd/io/fields_xdmf.h"

#include <sstream>

#include "dlmfd/io/atomic_file.h"

namespace dlmfd {
namespace {

// The node shape of one layer, slowest first: "1 ny+1 nx+1".
std::string DimensionsText(const Grid& g) {
  return "1 " + std::to_string(g.NodesY()) + " " + std::to_string(g.NodesX());
}

void HeavyItem(std::ostringstream& o, const std::string& dims, const std::string& file,
               const std::string& set, const std::string& indent) {
  o << indent << "<DataItem Dimensions=\"" << dims
    << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file << ":/" << set
    << "</DataItem>\n";
}

// A node attribute: "Scalar" of shape DimensionsText(g), or "Vector" of shape DimensionsText(g)
// plus 3 components.
void Attribute(std::ostringstream& o, const Grid& g, const std::string& type,
               const std::string& file, const std::string& set) {
  const std::string dims = type == "Vector" ? DimensionsText(g) + " 3" : DimensionsText(g);
  o << "          <Attribute Name=\"" << set << "\" AttributeType=\"" << type
    << "\" Center=\"Node\">\n";
  HeavyItem(o, dims, file, set, "            ");
  o << "          </Attribute>\n";
}

void Scalar(std::ostringstream& o, const Grid& g, const std::string& file, const std::string& set) {
  Attribute(o, g, "Scalar", file, set);
}

// ORIGIN_DXDYDZ, z first: origin "0 y0 x0", spacing "1 h h".
void Mesh(std::ostringstream& o, const Grid& g) {
  o.precision(17);
  o << "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << DimensionsText(g)
    << "\"/>\n";
  o << "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n";
  o << "          <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">0 "
    << g.y0 << " " << g.x0 << "</DataItem>\n";
  o << "          <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">1 "
    << g.h << " " << g.h << "</DataItem>\n";
  o << "        </Geometry>\n";
}

// One point per particle at (x, y, 0), with its radius, velocity, angular velocity, angle, id and
// semi-axes (a, b, 0).
void ParticleGrid(std::ostringstream& o, const XdmfEntry& e) {
  const std::string n = std::to_string(e.particles);
  o << "      <Grid Name=\"particles\" GridType=\"Uniform\">\n";
  o << "        <Time Value=\"" << e.time << "\"/>\n";
  o << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
    << "\" NodesPerElement=\"1\"/>\n";
  o << "        <Geometry GeometryType=\"XYZ\">\n";
  HeavyItem(o, n + " 3", e.file, "particles/position_xyz", "          ");
  o << "        </Geometry>\n";
  const auto attribute = [&](const char* name, const char* type, const std::string& dims,
                             const std::string& set, const char* number) {
    o << "        <Attribute Name=\"" << name << "\" AttributeType=\"" << type
      << "\" Center=\"Node\">\n";
    o << "          <DataItem Dimensions=\"" << dims << "\" NumberType=\"" << number
      << "\" Precision=\"8\" Format=\"HDF\">" << e.file << ":/" << set << "</DataItem>\n";
    o << "        </Attribute>\n";
  };
  attribute("radius", "Scalar", n, "particles/radius", "Float");
  attribute("velocity", "Vector", n + " 3", "particles/velocity_xyz", "Float");
  attribute("angular_velocity", "Scalar", n, "particles/angular_velocity", "Float");
  if (e.particle_angles) attribute("angle", "Scalar", n, "particles/angle", "Float");
  if (e.particle_semi_axes)
    attribute("semi_axes", "Vector", n + " 3", "particles/semi_axes", "Float");
  attribute("id", "Scalar", n, "particles/id", "Int");
  o << "      </Grid>\n";
}

}  // namespace

std::string FieldsXdmfText(const Grid& grid, const std::vector<XdmfEntry>& entries,
                           bool has_conformation) {
  const Grid coarse = grid.Coarse();
  std::ostringstream o;
  o.precision(17);
  o << "<?xml version=\"1.0\" ?>\n";
  o << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n";
  o << "  <Domain>\n";
  o << "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
  const auto temporal = [&](const char* name) {
    o << "    <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  };
  temporal("velocity_mesh");
  for (const XdmfEntry& e : entries) {
    o << "      <Grid Name=\"velocity_mesh\" GridType=\"Uniform\">\n";
    o << "        <Time Value=\"" << e.time << "\"/>\n";
    Mesh(o, grid);
    Attribute(o, grid, "Vector", e.file, "velocity");
    Scalar(o, grid, e.file, "u");
    Scalar(o, grid, e.file, "v");
    if (has_conformation) {
      for (const char* set : {"trA", "A11", "A12", "A22"}) Scalar(o, grid, e.file, set);
    }
    o << "      </Grid>\n";
  }
  o << "    </Grid>\n";
  temporal("pressure_mesh");
  for (const XdmfEntry& e : entries) {
    o << "      <Grid Name=\"pressure_mesh\" GridType=\"Uniform\">\n";
    o << "        <Time Value=\"" << e.time << "\"/>\n";
    Mesh(o, coarse);
    Scalar(o, coarse, e.file, "p");
    o << "      </Grid>\n";
  }
  o << "    </Grid>\n";
  bool particles = false;
  for (const XdmfEntry& e : entries) particles = particles || e.particles > 0;
  if (particles) {
    temporal("particles");
    for (const XdmfEntry& e : entries) {
      if (e.particles > 0) ParticleGrid(o, e);
    }
    o << "    </Grid>\n";
  }
  o << "    </Grid>\n";
  o << "  </Domain>\n";
  o << "</Xdmf>\n";
  return o.str();
}

void WriteFieldsXdmf(const std::string& path, const Grid& grid,
                     const std::vector<XdmfEntry>& entries, bool has_conformation) {
  WriteTextAtomically(path, FieldsXdmfText(grid, entries, has_conformation));
}

}  // namespace dlmfd
