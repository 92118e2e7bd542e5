#pragma once
#include <string>
#include <vector>

namespace gs {

// Each returns the process exit code; bad input throws with a clear message.
int command_run(const std::vector<std::string>& args);
int command_check(const std::vector<std::string>& args);

}  // namespace gs
