#pragma once
// Plain (non-HDF5) output files whose errors carry the system's reason: the
// errno of the failing call is captured right after it, so a message reads
// "cannot write out/run.log: Permission denied" or "error writing
// out/particles.xdmf.tmp42: No space left on device".
#include <cstdio>
#include <string>

namespace gs {

// "<what>: <strerror(error)>".
std::string os_error(const std::string& what, int error);

// fopen(path, mode); throws "cannot write <path>: <reason>" when it fails.
std::FILE* open_for_writing(const std::string& path, const char* mode);
// fflush; throws "error writing <path>: <reason>" when it, or an earlier
// write to f, failed.
void flush_checked(std::FILE* f, const std::string& path);

// Writes `text` to `path` (truncating it), flushed and closed, every step checked.
void write_text_file(const std::string& path, const std::string& text);

// A file being written line by line: printf records the first failure, close
// reports it (or the flush's or close's own) with its reason.
class TextFile {
 public:
  TextFile(const std::string& path, const char* mode = "w");
  ~TextFile();  // closes unchecked: an error is already on its way
  TextFile(const TextFile&) = delete;
  TextFile& operator=(const TextFile&) = delete;

  void printf(const char* format, ...) __attribute__((format(printf, 2, 3)));
  void close();

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  int error_ = 0;  // errno of the first failed write, 0 while none failed
};

}  // namespace gs
