#include <cstdio>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "apps/options.h"
#include "core/crash_report.h"
#include "core/error.h"

int main(int argc, char** argv) {
  cpgi::installCrashReport("cpgi");
  CLI::App app{
      "cpgi: bakes diffuse global illumination for indoor scenes into lightmaps (cell-portal radiosity). "
      "`cpgi COMMAND --help` lists a command's options by topic; docs/commands/ has a page for each."};
  // Before the commands are added: they take the app's formatter as they are made.
  app.formatter(cpgi::cli::groupedHelpFormatter());
  app.footer(
      "Examples:\n"
      "  cpgi generate seed1 -o out/seed1.glb\n"
      "  cpgi bake out/seed1.glb -o out/seed1        # then open out/seed1/report.html\n"
      "  cpgi decompose scene.glb -o out/cells\n"
      "  cpgi view out/seed1 --view-size 1280x720");
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
    // A mistyped command or option is named with the nearest valid one, not as CLI11's "arguments were
    // not expected" or "a subcommand is required".
    const std::string unknown =
        cpgi::cli::unknownNameMessage(app, std::vector<std::string>(argv + 1, argv + argc));
    std::cerr << "cpgi: " << (unknown.empty() ? std::string(e.what()) : unknown) << " (see --help)\n";
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
