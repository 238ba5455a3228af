#include "dlmfd/io/fields_xdmf.h"

#include <sstream>

#include "dlmfd/io/atomic_file.h"

namespace dlmfd {
namespace {

std::string Dims(const Grid& g) {
  return std::to_string(g.NodesY()) + " " + std::to_string(g.NodesX());
}

void HeavyItem(std::ostringstream& o, const Grid& g, const std::string& file,
               const std::string& set, const std::string& indent) {
  o << indent << "<DataItem Dimensions=\"" << Dims(g)
    << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file << ":/" << set
    << "</DataItem>\n";
}

void Scalar(std::ostringstream& o, const Grid& g, const std::string& file, const std::string& set) {
  o << "          <Attribute Name=\"" << set << "\" AttributeType=\"Scalar\" Center=\"Node\">\n";
  HeavyItem(o, g, file, set, "            ");
  o << "          </Attribute>\n";
}

void Mesh(std::ostringstream& o, const Grid& g) {
  o.precision(17);
  o << "        <Topology TopologyType=\"2DCoRectMesh\" Dimensions=\"" << Dims(g) << "\"/>\n";
  o << "        <Geometry GeometryType=\"ORIGIN_DXDY\">\n";
  o << "          <DataItem Dimensions=\"2\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
    << g.y0 << " " << g.x0 << "</DataItem>\n";
  o << "          <DataItem Dimensions=\"2\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
    << g.h << " " << g.h << "</DataItem>\n";
  o << "        </Geometry>\n";
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
  o << "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const XdmfEntry& e : entries) {
    o << "      <Grid Name=\"step\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    o << "        <Time Value=\"" << e.time << "\"/>\n";
    o << "      <Grid Name=\"velocity_mesh\" GridType=\"Uniform\">\n";
    Mesh(o, grid);
    o << "          <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n";
    o << "            <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1)\" Dimensions=\""
      << Dims(grid) << " 2\">\n";
    HeavyItem(o, grid, e.file, "u", "              ");
    HeavyItem(o, grid, e.file, "v", "              ");
    o << "            </DataItem>\n";
    o << "          </Attribute>\n";
    Scalar(o, grid, e.file, "u");
    Scalar(o, grid, e.file, "v");
    if (has_conformation) {
      for (const char* set : {"trA", "A11", "A12", "A22"}) Scalar(o, grid, e.file, set);
    }
    o << "      </Grid>\n";
    o << "      <Grid Name=\"pressure_mesh\" GridType=\"Uniform\">\n";
    Mesh(o, coarse);
    Scalar(o, coarse, e.file, "p");
    o << "      </Grid>\n";
    o << "      </Grid>\n";
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
