// The README's example program builds (it is compiled into this test), runs,
// and is the one the README shows.
#include <gtest/gtest.h>

#include "source_file.hpp"

#include <string>

#define main readmeExampleMain
#include "../../bullet_integration/examples/readme_example.cpp"
#undef main

namespace {

TEST(ReadmeExample, RunsAndTheCoinComesToRest) {
  EXPECT_EQ(readmeExampleMain(), 0);
}

TEST(ReadmeExample, ReadmeShowsExactlyThisProgram) {
  const std::string program = sourceFile("bullet_integration/examples/readme_example.cpp");
  const std::string readme = sourceFile("bullet_integration/README.md");
  ASSERT_FALSE(program.empty());
  ASSERT_FALSE(readme.empty());
  EXPECT_NE(readme.find("```cpp\n" + program + "```"), std::string::npos)
      << "README.md must quote examples/readme_example.cpp verbatim";
  const std::string topReadme = sourceFile("README.md");
  EXPECT_NE(topReadme.find("```cpp\n" + program + "```"), std::string::npos)
      << "the top-level README.md must quote examples/readme_example.cpp verbatim";
}

}  // namespace
