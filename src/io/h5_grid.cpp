#include "io/h5_grid.hpp"

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/h5_io.hpp"
#include "io/text_file.hpp"

namespace gs {
namespace {

std::string exact(double x) {
  char s[32];
  std::snprintf(s, sizeof(s), "%.17g", x);
  return s;
}

std::vector<hsize_t> field_dims(const GridShape& g, int components) {
  std::vector<hsize_t> dims{hsize_t(g.cells[2]), hsize_t(g.cells[1]), hsize_t(g.cells[0])};
  if (components > 1) dims.push_back(hsize_t(components));
  return dims;
}

const char* attribute_type(int components) {
  return components == 1 ? "Scalar" : components == 3 ? "Vector" : "Tensor";
}

void write_grid_file(const std::string& path, const GridShape& shape, const std::vector<GridField>& fields,
                     double time, long long step) {
  h5::File f = h5::File::create(path);
  h5::write_attribute(f, "/", "time", time);
  h5::write_attribute(f, "/", "step", std::int64_t(step));
  const double origin[3] = {shape.origin.x, shape.origin.y, shape.origin.z};
  const double spacing[3] = {shape.spacing.x, shape.spacing.y, shape.spacing.z};
  const std::int32_t cells[3] = {shape.cells[0], shape.cells[1], shape.cells[2]};
  h5::write_array(f, "origin", origin, {3});
  h5::write_array(f, "spacing", spacing, {3});
  h5::write_array(f, "cells", cells, {3});
  std::string names;  // the fields in their order, which the index follows
  for (const GridField& field : fields) names += (names.empty() ? "" : ",") + field.name;
  h5::write_string_attribute(f, "/", "fields", names);
  for (const GridField& field : fields) {
    if (field.values.size() != std::size_t(shape.cell_count()) * std::size_t(field.components))
      throw std::logic_error("grid field " + field.name + " has the wrong number of values");
    h5::write_array(f, field.name, field.values.data(), field_dims(shape, field.components));
  }
  f.close();
}

}  // namespace

void write_grid_h5(const std::string& path, const GridShape& shape, const std::vector<GridField>& fields, double time,
                   long long step) {
  write_atomically(path, [&](const std::string& temporary) { write_grid_file(temporary, shape, fields, time, step); });
}

GridSeriesEntry read_grid_entry(const std::string& directory, const std::string& h5_file) {
  h5::File f = h5::File::open_read_only(directory + "/" + h5_file);
  GridSeriesEntry e;
  e.h5_file = h5_file;
  e.time = h5::read_attribute<double>(f, "/", "time");
  e.step = h5::read_attribute<std::int64_t>(f, "/", "step");
  const std::vector<double> origin = h5::read_array<double>(f, "origin", {3});
  const std::vector<double> spacing = h5::read_array<double>(f, "spacing", {3});
  const std::vector<std::int32_t> cells = h5::read_array<std::int32_t>(f, "cells", {3});
  e.shape.origin = Vec3d(origin[0], origin[1], origin[2]);
  e.shape.spacing = Vec3d(spacing[0], spacing[1], spacing[2]);
  e.shape.cells = {cells[0], cells[1], cells[2]};
  std::stringstream names(h5::read_string_attribute(f, "/", "fields"));
  for (std::string name; std::getline(names, name, ',');) {
    const std::vector<hsize_t> dims = h5::dims_of(f, name);
    e.fields.emplace_back(name, dims.size() == 4 ? int(dims[3]) : 1);
  }
  return e;
}

std::string grid_xdmf_text(const std::string& name, const std::vector<GridSeriesEntry>& entries) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf Version=\"3.0\">\n  <Domain>\n"
      << "    <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const GridSeriesEntry& e : entries) {
    const GridShape& g = e.shape;
    // XDMF orders a structured grid's axes z, y, x (slowest first), as the datasets.
    const std::string cells = std::to_string(g.cells[2]) + " " + std::to_string(g.cells[1]) + " " +
                              std::to_string(g.cells[0]);
    out << "      <Grid Name=\"step_" << e.step << "\" GridType=\"Uniform\">\n"
        << "        <Time Value=\"" << exact(e.time) << "\"/>\n"
        << "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << g.cells[2] + 1 << ' ' << g.cells[1] + 1
        << ' ' << g.cells[0] + 1 << "\"/>\n"
        << "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
        << "          <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
        << exact(g.origin.z) << ' ' << exact(g.origin.y) << ' ' << exact(g.origin.x) << "</DataItem>\n"
        << "          <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">"
        << exact(g.spacing.z) << ' ' << exact(g.spacing.y) << ' ' << exact(g.spacing.x) << "</DataItem>\n"
        << "        </Geometry>\n";
    for (const auto& [field, components] : e.fields) {
      out << "        <Attribute Name=\"" << field << "\" AttributeType=\"" << attribute_type(components)
          << "\" Center=\"Cell\">\n"
          << "          <DataItem Dimensions=\"" << cells << (components > 1 ? " " + std::to_string(components) : "")
          << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << e.h5_file << ":/" << field
          << "</DataItem>\n        </Attribute>\n";
    }
    out << "      </Grid>\n";
  }
  out << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return out.str();
}

void write_grid_xdmf(const std::string& path, const std::string& name, const std::vector<GridSeriesEntry>& entries) {
  const std::string text = grid_xdmf_text(name, entries);
  write_atomically(path, [&](const std::string& temporary) { write_text_file(temporary, text); });
}

}  // namespace gs
