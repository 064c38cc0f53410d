// Subcommands of the `patchspin` tool register themselves here, one per file
// (cmd_*.cpp), so adding a subcommand touches no other file.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <vector>

namespace patchspin::tool {

using CommandSetup = std::function<void(CLI::App& app)>;

std::vector<CommandSetup>& commandRegistry();

struct RegisterCommand {
  explicit RegisterCommand(CommandSetup setup) { commandRegistry().push_back(std::move(setup)); }
};

// Thrown by subcommands for bad arguments: printed as one line, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace patchspin::tool
