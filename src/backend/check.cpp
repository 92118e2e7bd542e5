#include "backend/check.hpp"

namespace gs {

int& current_rank() {
  static int rank = 0;
  return rank;
}

void throw_external_error(const char* library, const char* call, const char* file, int line,
                          const std::string& message) {
  throw ExternalError("rank " + std::to_string(current_rank()) + ": " + library + " call " + call + " failed at " +
                      file + ":" + std::to_string(line) + ": " + message);
}

}  // namespace gs
