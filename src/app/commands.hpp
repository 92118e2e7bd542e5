#pragma once
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace gs {

// Each returns the process exit code; bad input throws with a clear message.
class Transport;
int command_run(const std::vector<std::string>& args, Transport& transport);
int command_check(const std::vector<std::string>& args);
int command_info(const std::vector<std::string>& args);    // app/command_info.cpp
int command_mixing(const std::vector<std::string>& args);  // app/command_mixing.cpp

}  // namespace gs
