// The robotics example program builds (it is compiled into this test), runs
// (its foot holds under 0.8 of its yaw limit), and the README's robotics
// lines are its own.
#include <gtest/gtest.h>

#include "source_file.hpp"

#include <set>
#include <sstream>
#include <string>

#define main robotFootExampleMain
#include "../../bullet_integration/examples/robot_foot_example.cpp"
#undef main

namespace {

std::string trimmed(const std::string& line) {
  const auto b = line.find_first_not_of(' ');
  return b == std::string::npos ? "" : line.substr(b);
}

TEST(RobotFootExample, RunsAndTheFootHolds) {
  EXPECT_EQ(robotFootExampleMain(), 0);
}

// The code block after the README's "Robots" paragraph: every line of it is
// a line of the program (indentation aside), so what the README shows builds.
TEST(RobotFootExample, ReadmeRoboticsLinesAreTheProgramsOwn) {
  const std::string program = sourceFile("bullet_integration/examples/robot_foot_example.cpp");
  const std::string readme = sourceFile("README.md");
  ASSERT_FALSE(program.empty());
  const auto robots = readme.find("Robots (`btMultiBodyDynamicsWorld`");
  ASSERT_NE(robots, std::string::npos) << "README.md has no robotics paragraph";
  const auto begin = readme.find("```cpp\n", robots);
  ASSERT_NE(begin, std::string::npos);
  const auto end = readme.find("```\n", begin + 7);
  ASSERT_NE(end, std::string::npos);
  std::set<std::string> lines;
  std::istringstream p(program);
  for (std::string line; std::getline(p, line);) lines.insert(trimmed(line));
  std::istringstream block(readme.substr(begin + 7, end - begin - 7));
  int count = 0;
  for (std::string line; std::getline(block, line); ++count)
    EXPECT_EQ(lines.count(trimmed(line)), 1u) << "not in robot_foot_example.cpp: " << line;
  EXPECT_GE(count, 5);
}

}  // namespace
