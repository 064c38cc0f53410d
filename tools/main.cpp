// patchspin: evaluate friction models, find limit directions, run simulations.
#include "command_registry.hpp"

#include <patchspin/types.hpp>

#include <cstdio>
#include <exception>

namespace patchspin::tool {
std::vector<CommandSetup>& commandRegistry() {
  static std::vector<CommandSetup> registry;
  return registry;
}
}  // namespace patchspin::tool

int main(int argc, char** argv) {
  CLI::App app{"patchspin: slip-spin friction of flat contact patches (Antali & Varkonyi)"};
  app.require_subcommand(1);
  for (auto& setup : patchspin::tool::commandRegistry()) setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const patchspin::Error& e) {
    std::fprintf(stderr, "patchspin: error: %s\n", e.what());
    return 2;
  } catch (const patchspin::tool::UsageError& e) {
    std::fprintf(stderr, "patchspin: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "patchspin: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
