#include "io/h5_io.hpp"

namespace gs::h5 {
namespace {

// "file.h5:/particles/position", for messages.
std::string where(const File& f, const std::string& path) {
  return f.path() + ":" + (path.empty() || path[0] != '/' ? "/" : "") + path;
}

std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string s = "(";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + ")";
}

hsize_t element_count(const std::vector<hsize_t>& dims) {
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  return n;
}

Handle file_access_list(const std::string& path) {
  Handle fapl(GS_H5_CHECK(H5Pcreate(H5P_FILE_ACCESS), path), H5Pclose);
  // SEMI: closing the file fails while an object in it is still open, instead
  // of leaving the file open (and unflushed) behind our back.
  GS_H5_CHECK(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_SEMI), path);
#if H5_VERSION_GE(1, 10, 7)
  // Keep HDF5's file lock, but do not fail where the file system has no
  // locks (common on cluster file systems such as Lustre or NFS).
  GS_H5_CHECK(H5Pset_file_locking(fapl.get(), true, true), path);
#endif
  return fapl;
}

Handle open_dataset(const File& f, const std::string& path) {
  if (!exists(f, path)) throw FormatError("missing dataset " + where(f, path));
  return Handle(GS_H5_CHECK(H5Dopen2(f.id(), path.c_str(), H5P_DEFAULT), where(f, path)), H5Dclose);
}

Handle open_attribute(const File& f, const std::string& object, const std::string& name) {
  if (!has_attribute(f, object, name))
    throw FormatError("missing attribute '" + name + "' of " + where(f, object));
  return Handle(GS_H5_CHECK(H5Aopen_by_name(f.id(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                            where(f, object)),
                H5Aclose);
}

std::recursive_mutex& library_mutex() {
  static std::recursive_mutex m;
  return m;
}

}  // namespace

File File::create(const std::string& path) {
  Lock lock(library_mutex());
  silence_library_errors();
  Handle fapl = file_access_list(path);
  return File(std::move(lock), path, Handle(GS_H5_CHECK(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), path),
                           H5Fclose));
}

File File::open_read_only(const std::string& path) {
  Lock lock(library_mutex());
  silence_library_errors();
  Handle fapl = file_access_list(path);
  return File(std::move(lock), path, Handle(GS_H5_CHECK(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), path), H5Fclose));
}

void File::close() {
  GS_H5_CHECK(H5Fclose(handle_.release()), path_);
  lock_.unlock();
}

void create_group(const File& f, const std::string& path) {
  Handle g(GS_H5_CHECK(H5Gcreate2(f.id(), path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), where(f, path)),
           H5Gclose);
}

bool exists(const File& f, const std::string& path) {
  std::size_t end = path.find_first_not_of('/');
  while (end != std::string::npos) {
    end = path.find('/', end);
    const std::string prefix = path.substr(0, end);
    if (GS_H5_CHECK(H5Lexists(f.id(), prefix.c_str(), H5P_DEFAULT), where(f, prefix)) <= 0) return false;
    if (end != std::string::npos) ++end;
  }
  return true;
}

void write_raw(const File& f, const std::string& path, hid_t memory_type, hid_t file_type, const void* data,
               const std::vector<hsize_t>& dims) {
  const std::string at = where(f, path);
  Handle space(GS_H5_CHECK(H5Screate_simple(int(dims.size()), dims.data(), nullptr), at), H5Sclose);
  Handle set(GS_H5_CHECK(H5Dcreate2(f.id(), path.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                    H5P_DEFAULT),
                         at),
             H5Dclose);
  // An empty dataset has nothing to write (and HDF5 1.10 refuses a null buffer).
  if (element_count(dims) > 0)
    GS_H5_CHECK(H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), at);
  GS_H5_CHECK(H5Dclose(set.release()), at);
}

void write_vec3(const File& f, const std::string& path, const std::vector<Vec3d>& v) {
  static_assert(sizeof(Vec3d) == 3 * sizeof(double), "Vec3d must be three packed doubles");
  write_array(f, path, reinterpret_cast<const double*>(v.data()), {hsize_t(v.size()), 3});
}

void write_quaternions(const File& f, const std::string& path, const std::vector<Quaternion>& q) {
  static_assert(sizeof(Quaternion) == 4 * sizeof(float), "Quaternion must be four packed floats");
  write_array(f, path, reinterpret_cast<const float*>(q.data()), {hsize_t(q.size()), 4});
}

void write_image_counts(const File& f, const std::string& path, const std::vector<ImageCount>& n) {
  static_assert(sizeof(ImageCount) == 3 * sizeof(std::int32_t), "ImageCount must be three packed int32");
  write_array(f, path, reinterpret_cast<const std::int32_t*>(n.data()), {hsize_t(n.size()), 3});
}

std::vector<hsize_t> dims_of(const File& f, const std::string& path) {
  Handle set = open_dataset(f, path);
  Handle space(GS_H5_CHECK(H5Dget_space(set.get()), where(f, path)), H5Sclose);
  const int rank = GS_H5_CHECK(H5Sget_simple_extent_ndims(space.get()), where(f, path));
  std::vector<hsize_t> dims(rank);
  GS_H5_CHECK(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), where(f, path));
  return dims;
}

void require_shape(const File& f, const std::string& path, const std::vector<hsize_t>& dims) {
  const std::vector<hsize_t> stored = dims_of(f, path);
  if (stored != dims)
    throw FormatError("dataset " + where(f, path) + " has shape " + shape_text(stored) + ", expected " +
                      shape_text(dims));
}

void read_raw(const File& f, const std::string& path, hid_t memory_type, hid_t file_type, void* data,
              const std::vector<hsize_t>& dims) {
  const std::string at = where(f, path);
  require_shape(f, path, dims);
  Handle set = open_dataset(f, path);
  Handle type(GS_H5_CHECK(H5Dget_type(set.get()), at), H5Tclose);
  if (GS_H5_CHECK(H5Tequal(type.get(), file_type), at) <= 0)
    throw FormatError("dataset " + at + " has an unexpected element type");
  if (element_count(dims) > 0)
    GS_H5_CHECK(H5Dread(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), at);
}

void read_rows_raw(const File& f, const std::string& path, hid_t memory_type, hid_t file_type, void* data,
                   const std::vector<hsize_t>& dims, hsize_t first, hsize_t rows) {
  const std::string at = where(f, path);
  require_shape(f, path, dims);
  if (dims.empty() || first + rows > dims[0])
    throw FormatError("dataset " + at + ": rows " + std::to_string(first) + " + " + std::to_string(rows) +
                      " lie outside its shape " + shape_text(dims));
  Handle set = open_dataset(f, path);
  Handle type(GS_H5_CHECK(H5Dget_type(set.get()), at), H5Tclose);
  if (GS_H5_CHECK(H5Tequal(type.get(), file_type), at) <= 0)
    throw FormatError("dataset " + at + " has an unexpected element type");
  std::vector<hsize_t> start(dims.size(), 0), count = dims;
  start[0] = first;
  count[0] = rows;
  if (element_count(count) == 0) return;
  Handle file_space(GS_H5_CHECK(H5Dget_space(set.get()), at), H5Sclose);
  GS_H5_CHECK(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr), at);
  Handle memory_space(GS_H5_CHECK(H5Screate_simple(int(count.size()), count.data(), nullptr), at), H5Sclose);
  GS_H5_CHECK(H5Dread(set.get(), memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data), at);
}

std::vector<Vec3d> read_vec3(const File& f, const std::string& path, hsize_t n) {
  require_shape(f, path, {n, 3});
  std::vector<Vec3d> v(n);
  read_raw(f, path, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, v.data(), {n, 3});
  return v;
}

std::vector<Quaternion> read_quaternions(const File& f, const std::string& path, hsize_t n) {
  require_shape(f, path, {n, 4});
  std::vector<Quaternion> q(n);
  read_raw(f, path, H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, q.data(), {n, 4});
  return q;
}

std::vector<ImageCount> read_image_counts(const File& f, const std::string& path, hsize_t n) {
  require_shape(f, path, {n, 3});
  std::vector<ImageCount> v(n);
  read_raw(f, path, H5T_NATIVE_INT32, H5T_STD_I32LE, v.data(), {n, 3});
  return v;
}

void write_attribute_raw(const File& f, const std::string& object, const std::string& name, hid_t memory_type,
                         hid_t file_type, const void* value) {
  const std::string at = where(f, object) + "@" + name;
  Handle space(GS_H5_CHECK(H5Screate(H5S_SCALAR), at), H5Sclose);
  Handle attr(GS_H5_CHECK(H5Acreate_by_name(f.id(), object.c_str(), name.c_str(), file_type, space.get(),
                                            H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                          at),
              H5Aclose);
  GS_H5_CHECK(H5Awrite(attr.get(), memory_type, value), at);
  GS_H5_CHECK(H5Aclose(attr.release()), at);
}

void write_string_attribute(const File& f, const std::string& object, const std::string& name,
                            const std::string& value) {
  const std::string at = where(f, object) + "@" + name;
  Handle type(GS_H5_CHECK(H5Tcopy(H5T_C_S1), at), H5Tclose);
  GS_H5_CHECK(H5Tset_size(type.get(), value.size() + 1), at);
  GS_H5_CHECK(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), at);
  write_attribute_raw(f, object, name, type.get(), type.get(), value.c_str());
}

bool has_attribute(const File& f, const std::string& object, const std::string& name) {
  if (!exists(f, object)) return false;
  return GS_H5_CHECK(H5Aexists_by_name(f.id(), object.c_str(), name.c_str(), H5P_DEFAULT), where(f, object)) > 0;
}

void read_attribute_raw(const File& f, const std::string& object, const std::string& name, hid_t memory_type,
                        hid_t file_type, void* value) {
  const std::string at = where(f, object) + "@" + name;
  Handle attr = open_attribute(f, object, name);
  Handle space(GS_H5_CHECK(H5Aget_space(attr.get()), at), H5Sclose);
  Handle type(GS_H5_CHECK(H5Aget_type(attr.get()), at), H5Tclose);
  if (GS_H5_CHECK(H5Sget_simple_extent_npoints(space.get()), at) != 1 ||
      GS_H5_CHECK(H5Tequal(type.get(), file_type), at) <= 0)
    throw FormatError("attribute " + at + " has an unexpected type or shape");
  GS_H5_CHECK(H5Aread(attr.get(), memory_type, value), at);
}

std::string read_string_attribute(const File& f, const std::string& object, const std::string& name) {
  const std::string at = where(f, object) + "@" + name;
  Handle attr = open_attribute(f, object, name);
  Handle type(GS_H5_CHECK(H5Aget_type(attr.get()), at), H5Tclose);
  if (GS_H5_CHECK(H5Tget_class(type.get()), at) != H5T_STRING)
    throw FormatError("attribute " + at + " is not a string");
  if (GS_H5_CHECK(H5Tis_variable_str(type.get()), at) > 0) {  // as other tools (h5py) write them
    Handle memory(GS_H5_CHECK(H5Tcopy(H5T_C_S1), at), H5Tclose);
    GS_H5_CHECK(H5Tset_size(memory.get(), H5T_VARIABLE), at);
    char* text = nullptr;
    GS_H5_CHECK(H5Aread(attr.get(), memory.get(), &text), at);
    std::string value = text ? text : "";
    H5free_memory(text);
    return value;
  }
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0) fail("H5Tget_size", at, __FILE__, __LINE__);
  std::string buffer(size + 1, '\0');
  Handle memory(GS_H5_CHECK(H5Tcopy(H5T_C_S1), at), H5Tclose);
  GS_H5_CHECK(H5Tset_size(memory.get(), size + 1), at);
  GS_H5_CHECK(H5Tset_strpad(memory.get(), H5T_STR_NULLTERM), at);
  GS_H5_CHECK(H5Aread(attr.get(), memory.get(), buffer.data()), at);
  return std::string(buffer.c_str());
}

std::int64_t read_row_count(const File& f, const std::string& object, const std::string& name,
                            const std::string& dataset) {
  const auto count = read_attribute<std::int64_t>(f, object, name);
  const std::vector<hsize_t> dims = dims_of(f, dataset);
  if (count < 0 || dims.empty() || dims[0] != hsize_t(count))
    throw FormatError("attribute '" + name + "' of " + where(f, object) + " is " + std::to_string(count) +
                      ", but dataset " + where(f, dataset) + " has shape " + shape_text(dims) + ": " +
                      (dims.empty() ? "no rows" : std::to_string(dims[0]) + " rows") +
                      " (the file is damaged or was not written by grainstorm)");
  return count;
}

std::vector<std::string> list_group(const File& f, const std::string& path) {
  const std::string at = where(f, path);
  Handle group(GS_H5_CHECK(H5Gopen2(f.id(), path.c_str(), H5P_DEFAULT), at), H5Gclose);
  H5G_info_t info;
  GS_H5_CHECK(H5Gget_info(group.get(), &info), at);
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length = GS_H5_CHECK(
        H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT), at);
    std::string name(std::size_t(length) + 1, '\0');
    GS_H5_CHECK(H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                                   H5P_DEFAULT),
                at);
    name.resize(std::size_t(length));
    names.push_back(name);
  }
  return names;
}

}  // namespace gs::h5
