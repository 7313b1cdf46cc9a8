// Number formatting shared by the trade study's progress lines and its reports.
#pragma once

#include <iomanip>
#include <sstream>
#include <string>

namespace octomotion {

inline std::string fmt(double v, int precision = 3) {
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

}  // namespace octomotion
