#include "io/h5_check.hpp"

#include <cstring>
#include <vector>

namespace gs::h5 {
namespace {

herr_t collect_message(unsigned, const H5E_error2_t* entry, void* messages) {
  if (entry->desc && entry->desc[0] != '\0')
    static_cast<std::vector<std::string>*>(messages)->push_back(entry->desc);
  return 0;
}

// "H5Dcreate2(...)" -> "H5Dcreate2": the function is what a reader needs.
std::string function_name(const char* call) {
  const char* paren = std::strchr(call, '(');
  return paren ? std::string(call, paren) : std::string(call);
}

// ".../src/io/h5_io.cpp" -> "io/h5_io.cpp".
const char* short_source(const char* source) {
  const char* at = std::strstr(source, "src/");
  return at ? at + 4 : source;
}

}  // namespace

void silence_library_errors() {
  // Per thread: a thread-safe HDF5 keeps its error settings per thread.
  static thread_local const bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

void fail(const char* call, const std::string& file, const char* source, int line) {
  std::vector<std::string> messages;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_message, &messages);
  H5Eclear2(H5E_DEFAULT);
  std::string what = "HDF5 " + function_name(call) + " failed on " + file + " (" + short_source(source) + ":" +
                     std::to_string(line) + ")";
  if (!messages.empty()) {
    what += ": " + messages.front();
    if (messages.size() > 1) what += " (" + messages.back() + ")";
  }
  throw H5Error(what);
}

}  // namespace gs::h5
