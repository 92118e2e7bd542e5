#include "io/text_file.hpp"

#include <cerrno>
#include <cstdarg>
#include <cstring>
#include <stdexcept>

namespace gs {

std::string os_error(const std::string& what, int error) { return what + ": " + std::strerror(error); }

std::FILE* open_for_writing(const std::string& path, const char* mode) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (!f) {
    const int error = errno;
    throw std::runtime_error(os_error("cannot write " + path, error));
  }
  return f;
}

void flush_checked(std::FILE* f, const std::string& path) {
  errno = 0;
  const bool flushed = std::fflush(f) == 0;
  const int error = errno;
  // A write that failed before this flush left the error flag (and, with
  // nothing written since, its errno).
  if (!flushed || std::ferror(f)) throw std::runtime_error(os_error("error writing " + path, error ? error : EIO));
}

void write_text_file(const std::string& path, const std::string& text) {
  TextFile f(path);
  f.printf("%s", text.c_str());
  f.close();
}

TextFile::TextFile(const std::string& path, const char* mode) : path_(path), file_(open_for_writing(path, mode)) {}

TextFile::~TextFile() {
  if (file_) std::fclose(file_);
}

void TextFile::printf(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  const int written = std::vfprintf(file_, format, args);
  const int error = errno;
  va_end(args);
  if (written < 0 && error_ == 0) error_ = error ? error : EIO;
}

void TextFile::close() {
  std::FILE* f = file_;
  file_ = nullptr;
  const bool flushed = std::fflush(f) == 0;
  if (!flushed && error_ == 0) error_ = errno ? errno : EIO;
  if (std::ferror(f) && error_ == 0) error_ = EIO;
  const bool closed = std::fclose(f) == 0;
  if (!closed && error_ == 0) error_ = errno ? errno : EIO;
  if (error_ != 0) throw std::runtime_error(os_error("error writing " + path_, error_));
}

}  // namespace gs
