#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "io/h5_snapshot.hpp"
#include "io/xdmf_series.hpp"
#include "io_test_helpers.hpp"

namespace gs {
namespace {

using test::ScratchDir;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::size_t element_size(const std::string& file, const std::string& dataset) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  const hid_t t = H5Dget_type(d);
  const std::size_t size = H5Tget_size(t);
  H5Tclose(t);
  H5Dclose(d);
  H5Fclose(f);
  return size;
}

// Writes three snapshots of a growing run and the index over them, as the run
// loop does: the index is rewritten after every snapshot.
std::vector<XdmfEntry> write_series(const ScratchDir& dir, const SnapshotFields& fields) {
  std::vector<XdmfEntry> entries;
  for (int k = 0; k < 3; ++k) {
    const ParticleSnapshot s = test::sample_particles(4 + std::size_t(k), 0.01 * k, 100LL * k);
    const std::string name = snapshot_h5_name(s.step);
    write_snapshot(dir.file(name), s, fields, test::sample_walls(), SnapshotMetadata());
    entries.push_back(xdmf_entry(name, s, fields));
    write_xdmf_series(dir.file("particles.xdmf"), entries);
  }
  return entries;
}

TEST(XdmfSeries, MentionsEverySnapshotAndDataset) {
  ScratchDir dir;
  const SnapshotFields fields = parse_snapshot_fields({"id", "radius", "velocity", "orientation"});
  const std::vector<XdmfEntry> entries = write_series(dir, fields);
  const std::string xmf = read_text(dir.file("particles.xdmf"));
  EXPECT_EQ(xmf, xdmf_series_text(entries));

  EXPECT_NE(xmf.find("<Xdmf Version=\"3.0\""), std::string::npos);
  EXPECT_NE(xmf.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_EQ(count(xmf, "TopologyType=\"Polyvertex\""), 3u);
  EXPECT_EQ(count(xmf, "GeometryType=\"XYZ\""), 3u);
  EXPECT_EQ(count(xmf, "<Time Value="), 3u);
  EXPECT_NE(xmf.find("<Time Value=\"0.02\"/>"), std::string::npos);
  for (const XdmfEntry& e : entries)
    for (const char* field : {"position", "id", "radius", "velocity", "orientation"})
      EXPECT_EQ(count(xmf, e.h5_file + ":/particles/" + field), 1u) << e.h5_file << " " << field;
  EXPECT_NE(xmf.find("Name=\"velocity\" AttributeType=\"Vector\""), std::string::npos);
  EXPECT_NE(xmf.find("Name=\"radius\" AttributeType=\"Scalar\""), std::string::npos);
  EXPECT_EQ(count(xmf, "Name=\"position\""), 0u) << "position is the geometry, not an attribute";
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"particles.xdmf", "particles_0000000000.h5",
                                                     "particles_0000000100.h5", "particles_0000000200.h5"}))
      << "no temporary files left";
}

TEST(XdmfSeries, EveryReferenceMatchesTheDatasetInTheFile) {
  ScratchDir dir;
  write_series(dir, all_particle_fields().add(SnapshotField::orientation));
  const std::string xmf = read_text(dir.file("particles.xdmf"));
  const std::regex item(R"re(<DataItem Dimensions="([0-9 ]+)" NumberType="(\w+)" Precision="(\d)" Format="HDF">([^:<]+):/([^<]+)</DataItem>)re");
  int checked = 0;
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), item); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const std::string file = dir.file(m[4]), dataset = m[5];
    ASSERT_TRUE(test::h5_link_exists(file, dataset)) << file << ":/" << dataset;
    std::vector<hsize_t> dims;
    test::read_h5<double>(file, dataset, H5T_NATIVE_DOUBLE, &dims);
    std::string shape;
    for (hsize_t d : dims) shape += (shape.empty() ? "" : " ") + std::to_string(d);
    EXPECT_EQ(shape, m[1].str()) << dataset;
    EXPECT_EQ(std::to_string(element_size(file, dataset)), m[3].str()) << dataset;
    ++checked;
  }
  EXPECT_EQ(checked, 3 * 12) << "position and 11 attributes per snapshot";
}

// With the domain given, each snapshot time also holds one triangle grid per
// analytic wall, in a temporal collection "walls" beside the particles; the
// vertices it points to lie on the walls' surfaces at that time (the drum
// turns about its axis point between snapshots).
TEST(XdmfSeries, WallsAreTriangleGridsOnTheirSurfaces) {
  ScratchDir dir;
  const SnapshotFields fields = default_snapshot_fields();
  std::vector<XdmfEntry> entries;
  std::vector<std::vector<Wall>> poses;
  for (int k = 0; k < 2; ++k) {
    std::vector<Wall> walls = test::sample_walls();
    walls[1].shift = {0.01 * (k + 1), 0.02 * k, 0};  // the drum moves
    const ParticleSnapshot s = test::sample_particles(4, 0.01 * k, 100LL * k);
    SnapshotMetadata m;
    m.wall_names = {"floor", "drum"};
    m.domain = DomainBox{{-0.2, -0.1, -0.1}, {0.2, 0.1, 0.3}};
    const std::string name = snapshot_h5_name(s.step);
    write_snapshot(dir.file(name), s, fields, walls, m);
    entries.push_back(xdmf_entry(name, s, fields, read_snapshot_wall_surfaces(dir.file(name))));
    poses.push_back(walls);
  }
  write_xdmf_series(dir.file("particles.xdmf"), entries);
  const std::string xmf = read_text(dir.file("particles.xdmf"));
  EXPECT_EQ(count(xmf, "<Grid Name=\"walls\" GridType=\"Collection\" CollectionType=\"Temporal\">"), 1u);
  EXPECT_EQ(count(xmf, "CollectionType=\"Spatial\""), 2u);
  EXPECT_EQ(count(xmf, "<Grid Name=\"floor\" GridType=\"Uniform\">"), 2u);
  EXPECT_EQ(count(xmf, "<Grid Name=\"drum\" GridType=\"Uniform\">"), 2u);
  EXPECT_EQ(count(xmf, "TopologyType=\"Triangle\""), 4u);
  EXPECT_EQ(count(xmf, "TopologyType=\"Polyvertex\""), 2u) << "the particle grids are unchanged";

  const std::regex item(R"re(<DataItem Dimensions="(\d+) 3" NumberType="Float" Precision="8" Format="HDF">([^:<]+):/wall_surfaces/(\d)/vertices</DataItem>)re");
  int checked = 0;
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), item); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const int snapshot = m[2].str() == snapshot_h5_name(0) ? 0 : 1;
    const Wall& w = poses[snapshot][std::stoi(m[3])];
    std::vector<hsize_t> dims;
    const auto xyz = test::read_h5<double>(dir.file(m[2]), "wall_surfaces/" + m[3].str() + "/vertices",
                                           H5T_NATIVE_DOUBLE, &dims);
    ASSERT_EQ(dims.size(), 2u);
    EXPECT_EQ(std::to_string(dims[0]), m[1].str());
    for (hsize_t i = 0; i < dims[0]; ++i) {
      const Vec3d x(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
      if (w.kind == WallKind::plane) {
        EXPECT_EQ(x.z, 0.0);  // the floor, z = 0
      } else {  // the drum's axis at this pose: R e_y through R (point - axis_point) + axis_point + shift
        const double* R = w.rotation;
        const Vec3d d = w.point - w.axis_point;
        const Vec3d base = Vec3d(R[0] * d.x + R[1] * d.y + R[2] * d.z, R[3] * d.x + R[4] * d.y + R[5] * d.z,
                                 R[6] * d.x + R[7] * d.y + R[8] * d.z) + w.axis_point + w.shift;
        const Vec3d axis(R[1], R[4], R[7]);
        const double along = dot(x - base, axis);
        EXPECT_NEAR(norm(x - base - along * axis), w.radius, 1e-14);
        EXPECT_GE(along, -1e-15);
        EXPECT_LE(along, w.length + 1e-15);
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, 4) << "two walls at two times";
}

}  // namespace
}  // namespace gs
