// STL reading and writing: ASCII and binary round trips, format detection,
// vertex sharing and welding, and every error a user can meet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "walls/impeller.hpp"
#include "walls/stl.hpp"

namespace gs {
namespace {

class StlFiles : public ::testing::Test {
 protected:
  std::string path(const std::string& name) {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    const std::string p = ::testing::TempDir() + "gs_stl_" + std::to_string(::getpid()) + "_" + test + "_" + name;
    created_.push_back(p);
    return p;
  }
  static std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static void spit(const std::string& p, const std::string& data) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(data.data(), std::streamsize(data.size()));
  }
  // The error message of read_stl, or "" when it succeeds.
  static std::string error_of(const std::string& p, const StlReadOptions& o = {}) {
    try {
      read_stl(p, o);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  void TearDown() override {
    for (const std::string& p : created_) std::remove(p.c_str());
  }

 private:
  std::vector<std::string> created_;
};

TriangleMesh tetrahedron() {
  TriangleMeshBuilder b("tetra");
  const std::int32_t o = b.vertex({0.1, 0.2, 0.3}), x = b.vertex({1.0 / 3, 0.2, 0.3});
  const std::int32_t y = b.vertex({0.1, 1.7, 0.3}), z = b.vertex({0.1, 0.2, -2.0 / 7});
  b.triangle(o, y, x);
  b.triangle(o, x, z);
  b.triangle(o, z, y);
  b.triangle(x, y, z);
  return b.take();
}

// Same triangles in the same order, with corners at `round`(a's corners).
template <class Round>
void expect_same_triangles(const TriangleMesh& a, const TriangleMesh& b, Round round) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t t = 0; t < a.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3d& p = a.vertices[a.triangles[t][k]];
      const Vec3d& q = b.vertices[b.triangles[t][k]];
      EXPECT_EQ(q.x, round(p.x)) << "triangle " << t << " corner " << k;
      EXPECT_EQ(q.y, round(p.y)) << "triangle " << t << " corner " << k;
      EXPECT_EQ(q.z, round(p.z)) << "triangle " << t << " corner " << k;
    }
}

const std::string kFacet =
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
    "    endloop\n  endfacet\n";

TEST_F(StlFiles, AsciiRoundTripIsExact) {
  const TriangleMesh m = tetrahedron();
  const std::string p = path("tetra_ascii.stl");
  write_stl(p, m, StlFormat::ascii);
  const TriangleMesh r = read_stl(p);
  EXPECT_EQ(r.name, "tetra");
  expect_same_triangles(m, r, [](double v) { return v; });
}

TEST_F(StlFiles, BinaryRoundTripKeepsFloatPrecision) {
  const TriangleMesh m = tetrahedron();
  const std::string p = path("tetra_binary.stl");
  write_stl(p, m, StlFormat::binary);
  EXPECT_EQ(slurp(p).size(), 84u + 50u * 4u);
  const TriangleMesh r = read_stl(p);
  expect_same_triangles(m, r, [](double v) { return double(float(v)); });
}

TEST_F(StlFiles, BinaryWhoseHeaderSaysSolidIsReadAsBinary) {
  const std::string p = path("solid_header.stl");
  write_stl(p, tetrahedron(), StlFormat::binary);
  std::string data = slurp(p);
  const std::string header = "solid exported by a CAD tool that writes binary files like this";
  data.replace(0, header.size(), header);
  spit(p, data);
  EXPECT_EQ(read_stl(p).triangles.size(), 4u);
}

TEST_F(StlFiles, ImpellerRoundTripStaysClosed) {
  const TriangleMesh m = make_impeller();
  const std::string p = path("impeller.stl");
  write_stl(p, m);
  const TriangleMesh r = read_stl(p);
  EXPECT_EQ(r.triangles.size(), m.triangles.size());
  EXPECT_EQ(r.vertices.size(), m.vertices.size());
  EXPECT_TRUE(mesh_topology(r).closed());
  EXPECT_TRUE(mesh_topology(r).consistently_oriented());
  EXPECT_NEAR(mesh_volume(r) / mesh_volume(m), 1.0, 1e-6);
}

TEST_F(StlFiles, SeveralSolidsUppercaseAndScale) {
  const std::string p = path("two_solids.stl");
  spit(p, "SOLID a\n" + kFacet + "ENDSOLID a\nsolid b\n" +
              "facet normal 0 0 0 outer loop vertex 0 0 0 vertex 0 1 0 vertex 0 0 1 endloop endfacet\nendsolid\n");
  StlReadOptions o;
  o.scale = 1e-3;
  const TriangleMesh m = read_stl(p, o);
  EXPECT_EQ(m.name, "a");
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.vertices.size(), 4u);  // (0,0,0) and (0,1,0) are shared
  EXPECT_DOUBLE_EQ(m.vertices[1].x, 1e-3);
}

TEST_F(StlFiles, WeldToleranceMergesNearbyCorners) {
  const std::string p = path("weld.stl");
  spit(p, "solid w\n" + kFacet +
              "facet normal 0 0 1 outer loop vertex 1.0000000001 0 0 vertex 1 1 0 vertex 0 1.0000000001 0 "
              "endloop endfacet\nendsolid w\n");
  EXPECT_EQ(read_stl(p).vertices.size(), 6u);
  StlReadOptions o;
  o.weld_tolerance = 1e-6;
  const TriangleMesh m = read_stl(p, o);
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(mesh_topology(m).edges, 5u);
  // A tolerance that collapses a triangle is reported as such.
  o.weld_tolerance = 2.0;
  EXPECT_NE(error_of(p, o).find("degenerate"), std::string::npos) << error_of(p, o);
}

TEST_F(StlFiles, MissingFile) {
  const std::string p = path("does_not_exist.stl");
  const std::string e = error_of(p);
  EXPECT_NE(e.find(p), std::string::npos) << e;
  EXPECT_NE(e.find("cannot open"), std::string::npos) << e;
}

TEST_F(StlFiles, TruncatedBinary) {
  for (const char* header : {"", "solid but binary"}) {
    const std::string p = path("truncated.stl");
    write_stl(p, tetrahedron(), StlFormat::binary);
    std::string data = slurp(p);
    data.replace(0, std::string(header).size(), header);
    spit(p, data.substr(0, data.size() - 30));
    const std::string e = error_of(p);
    EXPECT_NE(e.find(p), std::string::npos) << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << e;
    EXPECT_NE(e.find("4 triangles"), std::string::npos) << e;
  }
  const std::string tiny = path("tiny.stl");
  spit(tiny, std::string("\x01\x02\x03", 3));
  EXPECT_NE(error_of(tiny).find("not an STL file"), std::string::npos) << error_of(tiny);
}

TEST_F(StlFiles, MalformedAscii) {
  struct Case {
    std::string text, expect;
  };
  const std::string facet2 = "facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 endloop endfacet\n";
  const Case cases[] = {
      {"solid s\n" + kFacet, "missing 'endsolid'"},
      {"solid s\n" + facet2 + "endsolid\n", "exactly 3 vertices"},
      {"solid s\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 vertex 1 1 0 endloop "
       "endfacet\nendsolid\n",
       "exactly 3 vertices, got more"},
      {"solid s\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0x 0 vertex 0 1 0 endloop endfacet\nendsolid\n",
       "expected a number, got '0x'"},
      {"solid s\nfacet normal 0 0 1\nouter ring\n", "expected 'loop', got 'ring'"},
      {"solid s\n" + kFacet + "facet\n", "expected 'normal'"},
      {"solid s\nendsolid\nrubbish\n", "expected 'solid', got 'rubbish'"},
      {"solid s\nendsolid s\n", "no triangles"},
  };
  for (const Case& c : cases) {
    const std::string p = path("malformed.stl");
    spit(p, c.text);
    const std::string e = error_of(p);
    EXPECT_NE(e.find(p), std::string::npos) << e;
    EXPECT_NE(e.find(c.expect), std::string::npos) << "got: " << e << "\nexpected: " << c.expect;
  }
  // The line is named.
  const std::string p = path("line.stl");
  spit(p, "solid s\n" + kFacet + kFacet + "facet normal 0 0 1\n outer loop\n vertex 1 2 three\n");
  EXPECT_NE(error_of(p).find(p + ":18:"), std::string::npos) << error_of(p);
}

TEST_F(StlFiles, DegenerateTriangles) {
  const std::string p = path("degenerate.stl");
  spit(p, "solid d\n" + kFacet +
              "facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 1 1 vertex 2 2 2 endloop endfacet\nendsolid\n");
  std::string e = error_of(p);
  EXPECT_NE(e.find("facet 1 (line 9)"), std::string::npos) << e;
  EXPECT_NE(e.find("degenerate (zero area)"), std::string::npos) << e;
  spit(p, "solid d\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 0 0 endloop endfacet\nendsolid\n");
  e = error_of(p);
  EXPECT_NE(e.find("degenerate"), std::string::npos) << e;
}

TEST_F(StlFiles, NanCoordinates) {
  const std::string p = path("nan.stl");
  spit(p, "solid n\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex nan 0 0 vertex 0 1 0 endloop endfacet\nendsolid\n");
  std::string e = error_of(p);
  EXPECT_NE(e.find("NaN"), std::string::npos) << e;
  EXPECT_NE(e.find(p), std::string::npos) << e;
  // Binary: the second facet's first x becomes NaN.
  const std::string q = path("nan_binary.stl");
  write_stl(q, tetrahedron(), StlFormat::binary);
  std::string data = slurp(q);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  data.replace(84 + 50 + 12, 4, reinterpret_cast<const char*>(&nan), 4);
  spit(q, data);
  e = error_of(q);
  EXPECT_NE(e.find("facet 1 has a NaN"), std::string::npos) << e;
}

}  // namespace
}  // namespace gs
