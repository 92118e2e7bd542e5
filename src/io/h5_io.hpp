#pragma once
// Typed helpers over the HDF5 C API for src/io: files, groups, datasets and
// attributes addressed by path ("particles/position", "/" for the root).
// Files store fixed little-endian types whatever the machine; every call is
// checked (h5_check.hpp).
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "core/particle_fields.hpp"
#include "core/vec3.hpp"
#include "io/h5_check.hpp"

namespace gs::h5 {

// A file that opens but does not hold what the reader expects: a missing
// dataset or attribute, a wrong shape or element type.
struct FormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// HDF5 types of an element type: in memory (native) and in the file.
template <class T> struct TypeOf;
template <> struct TypeOf<double> {
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
  static hid_t file() { return H5T_IEEE_F64LE; }
};
template <> struct TypeOf<float> {
  static hid_t memory() { return H5T_NATIVE_FLOAT; }
  static hid_t file() { return H5T_IEEE_F32LE; }
};
template <> struct TypeOf<std::uint8_t> {
  static hid_t memory() { return H5T_NATIVE_UINT8; }
  static hid_t file() { return H5T_STD_U8LE; }
};
template <> struct TypeOf<std::uint16_t> {
  static hid_t memory() { return H5T_NATIVE_UINT16; }
  static hid_t file() { return H5T_STD_U16LE; }
};
template <> struct TypeOf<std::uint32_t> {
  static hid_t memory() { return H5T_NATIVE_UINT32; }
  static hid_t file() { return H5T_STD_U32LE; }
};
template <> struct TypeOf<std::int32_t> {
  static hid_t memory() { return H5T_NATIVE_INT32; }
  static hid_t file() { return H5T_STD_I32LE; }
};
template <> struct TypeOf<std::int64_t> {
  static hid_t memory() { return H5T_NATIVE_INT64; }
  static hid_t file() { return H5T_STD_I64LE; }
};
template <> struct TypeOf<std::uint64_t> {
  static hid_t memory() { return H5T_NATIVE_UINT64; }
  static hid_t file() { return H5T_STD_U64LE; }
};

// An open HDF5 file and its path, which every error message names.
class File {
 public:
  static File create(const std::string& path);  // replaces an existing file
  static File open_read_only(const std::string& path);

  hid_t id() const { return handle_.get(); }
  const std::string& path() const { return path_; }
  // Checked close: HDF5 writes its buffers here. Every object opened in the
  // file must be closed first. Without it the destructor closes unchecked.
  void close();

 private:
  using Lock = std::unique_lock<std::recursive_mutex>;
  File(Lock lock, std::string path, Handle handle)
      : lock_(std::move(lock)), path_(std::move(path)), handle_(std::move(handle)) {}
  // Held while the file is open: one thread at a time in the HDF5 library
  // (output is written on a thread of its own, io/background_writer.hpp,
  // and a library built without thread safety must not be entered twice).
  // First member: released after the handle is closed.
  Lock lock_;
  std::string path_;
  Handle handle_;
};

void create_group(const File& f, const std::string& path);
// Whether every component of `path` exists ("walls/kind": group and dataset).
bool exists(const File& f, const std::string& path);

// Dataset `path` of shape `dims` from data (product of dims elements, row-major).
void write_raw(const File& f, const std::string& path, hid_t memory_type, hid_t file_type, const void* data,
               const std::vector<hsize_t>& dims);
template <class T>
void write_array(const File& f, const std::string& path, const T* data, const std::vector<hsize_t>& dims) {
  write_raw(f, path, TypeOf<T>::memory(), TypeOf<T>::file(), data, dims);
}
template <class T>
void write_vector(const File& f, const std::string& path, const std::vector<T>& v) {
  write_array(f, path, v.data(), {hsize_t(v.size())});
}
void write_vec3(const File& f, const std::string& path, const std::vector<Vec3d>& v);             // (N, 3)
void write_quaternions(const File& f, const std::string& path, const std::vector<Quaternion>& q);  // (N, 4) w x y z
void write_image_counts(const File& f, const std::string& path, const std::vector<ImageCount>& n);  // (N, 3) int32
// One per-particle or per-contact field, in the shape its type has (N), (N, 3) or (N, 4).
template <class T>
void write_field(const File& f, const std::string& path, const std::vector<T>& v) {
  write_vector(f, path, v);
}
inline void write_field(const File& f, const std::string& path, const std::vector<Vec3d>& v) { write_vec3(f, path, v); }
inline void write_field(const File& f, const std::string& path, const std::vector<Quaternion>& v) {
  write_quaternions(f, path, v);
}
inline void write_field(const File& f, const std::string& path, const std::vector<ImageCount>& v) {
  write_image_counts(f, path, v);
}

// Shape of dataset `path`; FormatError when it is missing.
std::vector<hsize_t> dims_of(const File& f, const std::string& path);
// Reads dataset `path` into data after checking that it has exactly shape
// `dims` and the file type of T (no silent conversion); FormatError if not.
void read_raw(const File& f, const std::string& path, hid_t memory_type, hid_t file_type, void* data,
              const std::vector<hsize_t>& dims);
// Rows [first, first + rows) along the first dimension of dataset `path`,
// which must have shape `dims` and the file type given; the rows lie in
// `data` one after the other. Large datasets are read this way a block at a
// time, so the reader never holds them whole.
void read_rows_raw(const File& f, const std::string& path, hid_t memory_type, hid_t file_type, void* data,
                   const std::vector<hsize_t>& dims, hsize_t first, hsize_t rows);
// FormatError unless dataset `path` has exactly shape `dims`: the readers
// check it before they allocate, so a count that a file gets wrong (or a
// damaged one) is reported instead of allocating for it.
void require_shape(const File& f, const std::string& path, const std::vector<hsize_t>& dims);
template <class T>
std::vector<T> read_array(const File& f, const std::string& path, const std::vector<hsize_t>& dims) {
  require_shape(f, path, dims);
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  std::vector<T> out(count);
  read_raw(f, path, TypeOf<T>::memory(), TypeOf<T>::file(), out.data(), dims);
  return out;
}
std::vector<Vec3d> read_vec3(const File& f, const std::string& path, hsize_t n);
std::vector<Quaternion> read_quaternions(const File& f, const std::string& path, hsize_t n);
std::vector<ImageCount> read_image_counts(const File& f, const std::string& path, hsize_t n);
// The inverse of write_field: n rows into `out`.
template <class T>
void read_field(const File& f, const std::string& path, hsize_t n, std::vector<T>& out) {
  out = read_array<T>(f, path, {n});
}
inline void read_field(const File& f, const std::string& path, hsize_t n, std::vector<Vec3d>& out) {
  out = read_vec3(f, path, n);
}
inline void read_field(const File& f, const std::string& path, hsize_t n, std::vector<Quaternion>& out) {
  out = read_quaternions(f, path, n);
}
inline void read_field(const File& f, const std::string& path, hsize_t n, std::vector<ImageCount>& out) {
  out = read_image_counts(f, path, n);
}

// Scalar attributes of the object at `object` ("/" is the root).
void write_attribute_raw(const File& f, const std::string& object, const std::string& name, hid_t memory_type,
                         hid_t file_type, const void* value);
template <class T>
void write_attribute(const File& f, const std::string& object, const std::string& name, T value) {
  write_attribute_raw(f, object, name, TypeOf<T>::memory(), TypeOf<T>::file(), &value);
}
void write_string_attribute(const File& f, const std::string& object, const std::string& name,
                            const std::string& value);

bool has_attribute(const File& f, const std::string& object, const std::string& name);
// FormatError when the attribute is missing or not a scalar of T's class and size.
void read_attribute_raw(const File& f, const std::string& object, const std::string& name, hid_t memory_type,
                        hid_t file_type, void* value);
template <class T>
T read_attribute(const File& f, const std::string& object, const std::string& name) {
  T value{};
  read_attribute_raw(f, object, name, TypeOf<T>::memory(), TypeOf<T>::file(), &value);
  return value;
}
std::string read_string_attribute(const File& f, const std::string& object, const std::string& name);

// The int64 count attribute `name` of `object` ("particle_count" of "/"),
// checked against the rows of `dataset`, which holds one row per counted
// item: FormatError naming both when it is negative or they disagree.
std::int64_t read_row_count(const File& f, const std::string& object, const std::string& name,
                            const std::string& dataset);

// Names of the links directly under group `path`, in name order.
std::vector<std::string> list_group(const File& f, const std::string& path);

}  // namespace gs::h5
