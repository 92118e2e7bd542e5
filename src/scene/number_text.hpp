#pragma once
// A number as the scene's messages print it: six significant digits.
#include <sstream>
#include <string>

namespace gs {

inline std::string number_text(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

}  // namespace gs
