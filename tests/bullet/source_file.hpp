// The text of a file of the source tree, for the tests that check what the
// documents show (ReadmeExample, RobotFootExample): PATCHSPIN_SOURCE_DIR is
// set by tests/CMakeLists.txt (not __FILE__, which a compiler cache makes
// relative). Empty if the file cannot be read.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

inline std::string sourceFile(const std::string& relative) {
  std::ifstream in(std::string(PATCHSPIN_SOURCE_DIR) + "/" + relative);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
