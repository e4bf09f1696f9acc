// What the command line prints about itself: --help grouped by topic and wrapped to a width, and the
// nearest valid name for a mistyped command or option.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace cpgi::cli {

/// The topics --help groups the options under, in the order it lists them (CLI11's own "Options", with
/// --help and a command's few options of its own, comes first).
inline constexpr std::string_view kHelpGroups[] = {"Input", "Atlas",  "Solver", "Cells",
                                                   "Sky",   "Output", "Limits"};
/// --help's lines end by this column.
inline constexpr size_t kHelpColumns = 100;

/// --help's formatter: the groups in kHelpGroups' order, every line (usage, option, description,
/// examples) wrapped to end by kHelpColumns. Set on the app before its subcommands are added: they copy it.
std::shared_ptr<CLI::Formatter> groupedHelpFormatter();

/// `text` cut at spaces into lines of at most `width` characters (a word longer than that keeps a line
/// of its own); the line breaks `text` holds are kept.
std::vector<std::string> wrapWords(const std::string& text, size_t width);

/// The name in `names` nearest to `given`, as a user mistypes: the fewest letters inserted, left out,
/// changed or swapped (at most a quarter of its length, and at least one), or the only name `given`
/// begins (three letters or more); "" when none is that near. Case is ignored.
std::string nearestName(const std::string& given, const std::vector<std::string>& names);

/// For a command line CLI11 refused: the one line naming the first command or option in `args` (the
/// arguments after the program's name) that `app` does not have, with the nearest valid name ("bake:
/// --densty is not an option; did you mean --density?"), or "" when every name in `args` is known (the
/// error is another one).
std::string unknownNameMessage(const CLI::App& app, const std::vector<std::string>& args);

}  // namespace cpgi::cli
