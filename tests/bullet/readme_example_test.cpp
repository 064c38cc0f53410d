// The README's example program builds (it is compiled into this test), runs,
// and is the one the README shows.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#define main readmeExampleMain
#include "../../bullet_integration/examples/readme_example.cpp"
#undef main

namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// (the tests directory, from the source tree CMake configured: __FILE__ is
// relative where a compiler cache rewrites the paths)
const std::string kDir = std::string(PATCHSPIN_SOURCE_DIR) + "/tests/bullet";

TEST(ReadmeExample, RunsAndTheCoinComesToRest) {
  EXPECT_EQ(readmeExampleMain(), 0);
}

TEST(ReadmeExample, ReadmeShowsExactlyThisProgram) {
  const std::string program =
      readFile(kDir + "/../../bullet_integration/examples/readme_example.cpp");
  const std::string readme = readFile(kDir + "/../../bullet_integration/README.md");
  ASSERT_FALSE(program.empty());
  ASSERT_FALSE(readme.empty());
  EXPECT_NE(readme.find("```cpp\n" + program + "```"), std::string::npos)
      << "README.md must quote examples/readme_example.cpp verbatim";
  const std::string topReadme = readFile(kDir + "/../../README.md");
  EXPECT_NE(topReadme.find("```cpp\n" + program + "```"), std::string::npos)
      << "the top-level README.md must quote examples/readme_example.cpp verbatim";
}

}  // namespace
