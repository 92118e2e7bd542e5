#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "io/text_file.hpp"

namespace gs {
namespace {

void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) {
    const int error = errno;
    throw std::runtime_error(os_error("cannot open for fsync " + path, error));
  }
  const bool ok = ::fsync(fd) == 0;
  const int error = errno;
  ::close(fd);
  if (!ok) throw std::runtime_error(os_error("fsync failed on " + path, error));
}

// Makes the rename itself durable. Best effort: some file systems refuse to
// sync a directory, and the data is already safe in the renamed file.
void sync_directory_of(const std::string& path) {
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string temporary_path_for(const std::string& path) {
  return path + ".tmp" + std::to_string(long(::getpid()));
}

void write_atomically(const std::string& path, const std::function<void(const std::string& temporary)>& write) {
  const std::string temporary = temporary_path_for(path);
  try {
    write(temporary);
    sync_file(temporary);
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
      const int error = errno;
      throw std::runtime_error(os_error("cannot rename " + temporary + " to " + path, error));
    }
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
  sync_directory_of(path);
}

}  // namespace gs
