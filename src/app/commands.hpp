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

// An option's value that must be a whole number in [lo, hi], all of its
// text (so neither "10x" nor "1e3" reads as 10 or 1); else throws
// "`rule`, got 'text'".
long long whole_number(const std::string& text, long long lo, long long hi, const std::string& rule);

}  // namespace gs
