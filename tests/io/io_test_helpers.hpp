#pragma once
// Shared by the tests in tests/io: a scratch directory per test, particles
// with a distinct value in every field, and plain HDF5 C API readers that do
// not go through src/io (so a round trip checks the file, not our reader).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/simulation.hpp"
#include "walls/wall.hpp"

namespace gs::test {

// A fresh directory, removed with everything in it at the end of the test.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("gs_io_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

inline ParticleSnapshot sample_particles(std::size_t n, double time = 0.125, long long step = 250) {
  ParticleSnapshot s;
  s.time = time;
  s.step = step;
  for (std::size_t i = 0; i < n; ++i) {
    const double k = double(i);
    s.id.push_back(ParticleId(1000 + 7 * i));
    s.material.push_back(std::uint8_t(i % 3));
    s.marker.push_back(std::uint8_t(200 + i % 50));
    s.radius.push_back(0.001f + 1e-5f * float(i));
    s.mass.push_back(1.1e-5f * float(i + 1));
    s.inertia.push_back(3.3e-12f * float(i + 1));
    s.position.push_back({0.1 + k / 3.0, -0.2 - k / 7.0, 1e-3 * k + 1.0 / 9.0});
    s.velocity.push_back({k * 0.5, -1.0 / (k + 3.0), 2.0});
    s.angular_velocity.push_back({1.0 / (k + 1.0), 0.0, -3.25 * k});
    s.orientation.push_back({1.0f / float(i + 1), 0.5f, -0.25f, 0.125f});
    s.force.push_back({1e-3 * k, -9.81e-3, 1.0 / (k + 11.0)});
    s.torque.push_back({-1e-7 * k, 2e-7, 1.0 / (k + 13.0) * 1e-6});
  }
  return s;
}

inline std::vector<Wall> sample_walls() {
  Wall floor;
  floor.kind = WallKind::plane;
  floor.point = {0, 0, 0};
  floor.normal = {0, 0, 1};
  Wall drum;
  drum.kind = WallKind::cylinder;
  drum.material = 1;
  drum.point = {0, -0.05, 0.1};
  drum.normal = {0, 1, 0};
  drum.radius = 0.1;
  drum.length = 0.05;
  drum.angular_velocity = {0, 3.0, 0};
  drum.axis_point = {0, 0, 0.1};
  const double c = 0.8, s = 0.6;  // rotated about y
  const double r[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
  for (int k = 0; k < 9; ++k) drum.rotation[k] = r[k];
  drum.shift = {0.01, 0, 0};
  return {floor, drum};
}

// Dataset `path` of `file` through the plain C API; dims receives its shape.
template <class T>
std::vector<T> read_h5(const std::string& file, const std::string& path, hid_t memory_type,
                       std::vector<hsize_t>* dims = nullptr) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << path;
  const hid_t space = H5Dget_space(d);
  std::vector<hsize_t> shape(H5Sget_simple_extent_ndims(space));
  H5Sget_simple_extent_dims(space, shape.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t x : shape) count *= x;
  std::vector<T> out(count);
  if (count > 0) {
    EXPECT_GE(H5Dread(d, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), 0) << path;
  }
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  if (dims) *dims = shape;
  return out;
}

template <class T>
T read_h5_attribute(const std::string& file, const std::string& object, const std::string& name,
                    hid_t memory_type) {
  T value{};
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen_by_name(f, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(a, 0) << object << "@" << name;
  EXPECT_GE(H5Aread(a, memory_type, &value), 0);
  H5Aclose(a);
  H5Fclose(f);
  return value;
}

inline std::string read_h5_string(const std::string& file, const std::string& object, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen_by_name(f, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(a, 0) << object << "@" << name;
  const hid_t type = H5Aget_type(a);
  std::string value(H5Tget_size(type), '\0');
  EXPECT_GE(H5Aread(a, type, value.data()), 0);
  H5Tclose(type);
  H5Aclose(a);
  H5Fclose(f);
  return value.c_str();
}

inline bool h5_link_exists(const std::string& file, const std::string& path) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  bool found = f >= 0;
  std::size_t at = 0;
  while (found && at != std::string::npos) {
    at = path.find('/', at + 1);
    found = H5Lexists(f, path.substr(0, at).c_str(), H5P_DEFAULT) > 0;
  }
  if (f >= 0) H5Fclose(f);
  return found;
}

}  // namespace gs::test
