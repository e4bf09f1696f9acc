// Each subcommand registers itself on the CLI11 app; when it is chosen, `selected` is set to the function
// that runs it. Commands only parse, call the libraries and report (DEVELOPERS.md: apps/ is thin).
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace cpgi::cli {

using CommandFn = std::function<int()>;

// void add<Name>Command(CLI::App& app, CommandFn& selected); one per subcommand, in apps/<name>_command.cpp
void addInfoCommand(CLI::App& app, CommandFn& selected);
void addGenerateCommand(CLI::App& app, CommandFn& selected);
void addBakeCommand(CLI::App& app, CommandFn& selected);
void addReferenceCommand(CLI::App& app, CommandFn& selected);
void addCompareLightCommand(CLI::App& app, CommandFn& selected);
void addDecomposeCommand(CLI::App& app, CommandFn& selected);
void addCompareCellsCommand(CLI::App& app, CommandFn& selected);

}  // namespace cpgi::cli
