#include "io/xdmf_series.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/text_file.hpp"

namespace gs {
namespace {

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string exact(double x) {
  char s[32];
  std::snprintf(s, sizeof(s), "%.17g", x);
  return s;
}

// "Vector" also for orientation's four components: both ParaView readers
// (Xdmf3 and the older Xdmf2) then give a 4-component array; "Matrix" is
// misread by the Xdmf2 one.
const char* attribute_type(int components) { return components == 1 ? "Scalar" : "Vector"; }

void data_item(std::ostream& out, const XdmfEntry& e, const SnapshotFieldInfo& info) {
  out << "          <DataItem Dimensions=\"" << e.particle_count;
  if (info.components > 1) out << ' ' << info.components;
  out << "\" NumberType=\"" << info.number_type << "\" Precision=\"" << info.precision << "\" Format=\"HDF\">"
      << xml_escaped(e.h5_file) << ":/particles/" << info.name << "</DataItem>\n";
}

void grid(std::ostream& out, const XdmfEntry& e) {
  char name[40];
  std::snprintf(name, sizeof(name), "step_%010lld", e.step);
  out << "      <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n"
      << "        <Time Value=\"" << exact(e.time) << "\"/>\n"
      << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << e.particle_count
      << "\" NodesPerElement=\"1\"/>\n"
      << "        <Geometry GeometryType=\"XYZ\">\n";
  data_item(out, e, field_info(SnapshotField::position));
  out << "        </Geometry>\n";
  for (SnapshotField f : e.fields.list()) {
    if (f == SnapshotField::position) continue;
    const SnapshotFieldInfo& info = field_info(f);
    out << "        <Attribute Name=\"" << info.name << "\" AttributeType=\"" << attribute_type(info.components)
        << "\" Center=\"Node\">\n";
    data_item(out, e, info);
    out << "        </Attribute>\n";
  }
  out << "      </Grid>\n";
}

// One time of the walls collection: a spatial collection of one triangle
// grid per wall, at the pose the snapshot stored.
void wall_grids(std::ostream& out, const XdmfEntry& e) {
  char name[40];
  std::snprintf(name, sizeof(name), "walls_%010lld", e.step);
  out << "      <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      << "        <Time Value=\"" << exact(e.time) << "\"/>\n";
  for (std::size_t k = 0; k < e.walls.size(); ++k) {
    const WallSurfaceInfo& w = e.walls[k];
    const std::string at = xml_escaped(e.h5_file) + ":/wall_surfaces/" + std::to_string(k);
    out << "        <Grid Name=\"" << xml_escaped(w.name) << "\" GridType=\"Uniform\">\n"
        << "          <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << w.triangles << "\">\n"
        << "            <DataItem Dimensions=\"" << w.triangles
        << " 3\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << at << "/triangles</DataItem>\n"
        << "          </Topology>\n"
        << "          <Geometry GeometryType=\"XYZ\">\n"
        << "            <DataItem Dimensions=\"" << w.vertices
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << at << "/vertices</DataItem>\n"
        << "          </Geometry>\n"
        << "        </Grid>\n";
  }
  out << "      </Grid>\n";
}

}  // namespace

XdmfEntry xdmf_entry(const std::string& h5_file, const ParticleSnapshot& s, const SnapshotFields& fields,
                     std::vector<WallSurfaceInfo> walls) {
  XdmfEntry e;
  e.time = s.time;
  e.step = s.step;
  e.h5_file = h5_file;
  e.particle_count = s.size();
  e.fields = fields;
  e.walls = std::move(walls);
  return e;
}

std::string xdmf_series_text(const std::vector<XdmfEntry>& entries) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
      << "  <Domain>\n"
      << "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const XdmfEntry& e : entries) grid(out, e);
  out << "    </Grid>\n";
  // Walls in a collection of their own, beside the particles, so that
  // readers of the particle grids see them unchanged.
  if (std::any_of(entries.begin(), entries.end(), [](const XdmfEntry& e) { return !e.walls.empty(); })) {
    out << "    <Grid Name=\"walls\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const XdmfEntry& e : entries)
      if (!e.walls.empty()) wall_grids(out, e);
    out << "    </Grid>\n";
  }
  out << "  </Domain>\n"
      << "</Xdmf>\n";
  return out.str();
}

void write_xdmf_series(const std::string& path, const std::vector<XdmfEntry>& entries) {
  const std::string text = xdmf_series_text(entries);
  write_atomically(path, [&](const std::string& temporary) { write_text_file(temporary, text); });
}

}  // namespace gs
