#include "io/h5_meshes.hpp"

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/h5_io.hpp"
#include "io/text_file.hpp"

namespace gs {

std::string meshes_h5_name(long long step) {
  char name[64];
  std::snprintf(name, sizeof(name), "meshes_%010lld.h5", step);
  return name;
}

void write_meshes_h5(const std::string& path, const MeshSet& meshes, double time, long long step) {
  std::vector<std::int32_t> triangles;
  triangles.reserve(3 * meshes.corners.size());
  for (const MeshCorners& c : meshes.corners) triangles.insert(triangles.end(), {c.v[0], c.v[1], c.v[2]});
  write_atomically(path, [&](const std::string& temporary) {
    h5::File f = h5::File::create(temporary);
    h5::write_string_attribute(f, "/", "kind", "grainstorm meshes");
    h5::write_attribute(f, "/", "time", time);
    h5::write_attribute(f, "/", "step", std::int64_t(step));
    h5::write_vec3(f, "/vertices", meshes.vertex);
    h5::write_array(f, "/triangles", triangles.data(), {hsize_t(meshes.corners.size()), 3});
    h5::write_vector(f, "/mesh", meshes.mesh);
    f.close();
  });
}

void write_mesh_xdmf(const std::string& path, const std::vector<MeshSeriesEntry>& entries) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n"
      << "    <Grid Name=\"meshes\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const MeshSeriesEntry& e : entries) {
    char time[32];
    std::snprintf(time, sizeof(time), "%.17g", e.time);
    out << "      <Grid Name=\"meshes\" GridType=\"Uniform\">\n        <Time Value=\"" << time << "\"/>\n"
        << "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << e.triangles << "\">\n"
        << "          <DataItem Dimensions=\"" << e.triangles << " 3\" NumberType=\"Int\" Precision=\"4\" "
        << "Format=\"HDF\">" << e.h5_file << ":/triangles</DataItem>\n        </Topology>\n"
        << "        <Geometry GeometryType=\"XYZ\">\n          <DataItem Dimensions=\"" << e.vertices
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << e.h5_file
        << ":/vertices</DataItem>\n        </Geometry>\n"
        << "        <Attribute Name=\"mesh\" AttributeType=\"Scalar\" Center=\"Cell\">\n          <DataItem "
        << "Dimensions=\"" << e.triangles << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << e.h5_file
        << ":/mesh</DataItem>\n        </Attribute>\n      </Grid>\n";
  }
  out << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  const std::string text = out.str();
  write_atomically(path, [&](const std::string& temporary) { write_text_file(temporary, text); });
}

}  // namespace gs
