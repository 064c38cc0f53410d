#include "run_tool.hpp"

#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace patchspin::testing {

ToolRun runTool(const std::string& tool, const std::string& arguments) {
  ToolRun run;
  char errPath[] = "/tmp/patchspin_tool_err_XXXXXX";
  const int fd = mkstemp(errPath);
  if (fd >= 0) close(fd);
  const std::string command = "'" + tool + "' " + arguments + " 2>'" + errPath + "'";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    run.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream errFile(errPath);
  std::stringstream errText;
  errText << errFile.rdbuf();
  run.err = errText.str();
  std::remove(errPath);
  return run;
}

}  // namespace patchspin::testing
