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
    write_xdmf_series(dir.file("particles.xmf"), entries);
  }
  return entries;
}

TEST(XdmfSeries, MentionsEverySnapshotAndDataset) {
  ScratchDir dir;
  const SnapshotFields fields = parse_snapshot_fields({"id", "radius", "velocity", "orientation"});
  const std::vector<XdmfEntry> entries = write_series(dir, fields);
  const std::string xmf = read_text(dir.file("particles.xmf"));
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
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"particles.xmf", "particles_0000000000.h5",
                                                     "particles_0000000100.h5", "particles_0000000200.h5"}))
      << "no temporary files left";
}

TEST(XdmfSeries, EveryReferenceMatchesTheDatasetInTheFile) {
  ScratchDir dir;
  write_series(dir, all_particle_fields());
  const std::string xmf = read_text(dir.file("particles.xmf"));
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

}  // namespace
}  // namespace gs
