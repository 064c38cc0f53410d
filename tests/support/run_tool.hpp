// Runs the `patchspin` command-line tool from a test and captures its output.
#pragma once

#include <string>

namespace patchspin::testing {

struct ToolRun {
  int exitCode = -1;
  std::string out;  // standard output
  std::string err;  // standard error
};

// Runs `<tool> <arguments>` through /bin/sh (arguments are passed verbatim).
ToolRun runTool(const std::string& tool, const std::string& arguments);

}  // namespace patchspin::testing
