#pragma once
// Every HDF5 call in src/io goes through GS_H5_CHECK: a negative return throws
// H5Error naming the call, the HDF5 file, the source line and HDF5's own
// message. Handle closes what a call opened, also while an error unwinds.
#include <hdf5.h>

#include <stdexcept>
#include <string>

namespace gs::h5 {

// A failed HDF5 call.
struct H5Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws H5Error for `call` (its source text) failing on `file`; the message
// carries the outermost and innermost entries of HDF5's error stack.
[[noreturn]] void fail(const char* call, const std::string& file, const char* source, int line);

template <class T>
T checked(T result, const char* call, const std::string& file, const char* source, int line) {
  if (result < 0) fail(call, file, source, line);
  return result;
}

// HDF5 prints its error stack to stderr by default; our errors reach the user
// through H5Error instead. Idempotent; called before any file is opened.
void silence_library_errors();

// Owns one HDF5 identifier and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = o.id_;
      close_ = o.close_;
      o.id_ = H5I_INVALID_HID;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  // Gives up ownership, for a close whose result must be checked.
  hid_t release() {
    const hid_t id = id_;
    id_ = H5I_INVALID_HID;
    return id;
  }
  // Closes unchecked: used on cleanup paths, where an error is already on its way.
  void reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = H5I_INVALID_HID;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

}  // namespace gs::h5

#define GS_H5_CHECK(call, file) ::gs::h5::checked((call), #call, (file), __FILE__, __LINE__)
