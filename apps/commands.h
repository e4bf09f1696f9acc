// Each subcommand registers itself on the CLI11 app; when it is chosen, `selected` is set to the function
// that runs it. Commands only parse, call the libraries and report (DEVELOPERS.md: apps/ is thin).
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace cpgi::cli {

using CommandFn = std::function<int()>;

/// CLI11's PositiveNumber prints the largest double in its message; this one says what it means.
inline const CLI::Validator kPositive(
    [](std::string& value) -> std::string {
      double v = 0.0;
      if (!CLI::detail::lexical_cast(value, v) || !(v > 0.0) || !std::isfinite(v))
        return "must be a positive number, got " + value;
      return {};
    },
    "POSITIVE");

// void add<Name>Command(CLI::App& app, CommandFn& selected); one per subcommand, in apps/<name>_command.cpp
void addInfoCommand(CLI::App& app, CommandFn& selected);
void addGenerateCommand(CLI::App& app, CommandFn& selected);
void addBakeCommand(CLI::App& app, CommandFn& selected);
void addReferenceCommand(CLI::App& app, CommandFn& selected);
void addCompareLightCommand(CLI::App& app, CommandFn& selected);
void addDecomposeCommand(CLI::App& app, CommandFn& selected);
void addCompareCellsCommand(CLI::App& app, CommandFn& selected);
void addViewCommand(CLI::App& app, CommandFn& selected);
void addCellJobCommand(CLI::App& app, CommandFn& selected);

}  // namespace cpgi::cli
