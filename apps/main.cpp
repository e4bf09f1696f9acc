#include <cstdio>
#include <exception>
#include <iostream>
#include <stdexcept>

#include "apps/commands.h"
#include "apps/options.h"
#include "core/crash_report.h"
#include "core/error.h"

int main(int argc, char** argv) {
  cpgi::installCrashReport("cpgi");
  CLI::App app{"cpgi: cell-portal global illumination (radiosity baking for indoor scenes)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cpgi 0.1.0");
  cpgi::cli::CommandFn selected;
  cpgi::cli::addInfoCommand(app, selected);
  cpgi::cli::addGenerateCommand(app, selected);
  cpgi::cli::addBakeCommand(app, selected);
  cpgi::cli::addReferenceCommand(app, selected);
  cpgi::cli::addCompareLightCommand(app, selected);
  cpgi::cli::addDecomposeCommand(app, selected);
  cpgi::cli::addCompareCellsCommand(app, selected);
  cpgi::cli::addViewCommand(app, selected);
  cpgi::cli::addCellJobCommand(app, selected);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" that succeed; a real one is a single line naming the option.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << "cpgi: " << e.what() << " (see --help)\n";
    return 1;
  }
  try {
    return selected ? selected() : 1;
  } catch (const cpgi::InputError& e) {
    // Libraries name parameters ("voxel size"); the user typed flags (--voxel).
    std::cerr << "cpgi: " << cpgi::cli::userMessage(e) << "\n";
  } catch (const cpgi::SystemError& e) {
    std::cerr << "cpgi: " << e.what() << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "cpgi: out of memory (lower the resolution, or see --max-memory)\n";
  } catch (const std::length_error& e) {
    // std::vector's "vector::_M_default_append": a size taken from the input beyond what can be allocated.
    std::cerr << "cpgi: out of memory: the input asks for an array larger than can be allocated (" << e.what()
              << ")\n";
  } catch (const std::exception& e) {
    std::cerr << "cpgi: internal error: " << e.what() << "\n";
  }
  return 1;
}
