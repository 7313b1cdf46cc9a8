// A synthetic chain robot for tests and benches of many-link behaviour: `links` boxes of
// 8 x 4 x 4 cm, 10 cm apart, joined by revolute joints whose axes alternate between z and y,
// each limited to [-limit, limit] rad. Curled states touch themselves, straight-ish ones do not.
#pragma once

#include <sstream>
#include <string>

namespace octomotion::test {

inline std::string snakeUrdf(int links, double limit) {
  std::ostringstream u;
  u << "<robot name=\"snake\">\n";
  for (int i = 0; i < links; ++i) {
    u << "<link name=\"l" << i << "\"><collision><origin xyz=\"0.05 0 0\"/><geometry>"
      << "<box size=\"0.08 0.04 0.04\"/></geometry></collision></link>\n";
  }
  for (int i = 1; i < links; ++i) {
    u << "<joint name=\"j" << i << "\" type=\"revolute\"><parent link=\"l" << i - 1
      << "\"/><child link=\"l" << i << "\"/><origin xyz=\"0.1 0 0\"/><axis xyz=\""
      << (i % 2 ? "0 0 1" : "0 1 0") << "\"/><limit lower=\"" << -limit << "\" upper=\"" << limit
      << "\" effort=\"1\" velocity=\"1\"/></joint>\n";
  }
  u << "</robot>\n";
  return u.str();
}

}  // namespace octomotion::test
