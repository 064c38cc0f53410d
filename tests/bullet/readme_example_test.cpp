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

const std::string kDir = std::string(__FILE__).substr(0, std::string(__FILE__).rfind('/'));

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
