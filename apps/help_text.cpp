#include "apps/help_text.h"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "core/error.h"

namespace cpgi::cli {

std::vector<std::string> wrapWords(const std::string& text, size_t width) {
  std::vector<std::string> lines;
  std::istringstream paragraphs(text);
  for (std::string paragraph; std::getline(paragraphs, paragraph);) {
    if (paragraph.size() <= width) {  // as written: an example's spacing lines up its comments
      lines.push_back(paragraph);
      continue;
    }
    // A line's own indent (an example's) is kept on its first line.
    const size_t indent = paragraph.find_first_not_of(' ');
    std::string line = indent == std::string::npos ? "" : paragraph.substr(0, indent);
    std::istringstream words(paragraph);
    bool empty = true;
    for (std::string word; words >> word;) {
      if (!empty && line.size() + 1 + word.size() > width) {
        lines.push_back(line);
        line.clear();
        empty = true;
      }
      line += (empty ? "" : " ") + word;
      empty = false;
    }
    lines.push_back(line);
  }
  return lines;
}

namespace {

std::string joinLines(const std::vector<std::string>& lines, const std::string& indent) {
  std::string out;
  for (size_t i = 0; i < lines.size(); ++i) out += (i ? indent : "") + lines[i] + "\n";
  return out;
}

// CLI11's formatter with the groups in kHelpGroups' order and every line wrapped at kHelpColumns: a name
// on the left (itself wrapped when its choices and defaults run long), its description in a column
// beside it or, when the name reaches that column, on the lines below.
class GroupedHelp : public CLI::Formatter {
 public:
  GroupedHelp() { column_width(30); }

  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override {
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    return make_description(app) + joinLines(wrapWords(make_usage(app, name), kHelpColumns), "    ") +
           make_positionals(app) + orderedGroups(app, mode) + make_subcommands(app, mode) + "\n" +
           make_footer(app);
  }

  std::string make_option(const CLI::Option* opt, bool positional) const override {
    return column("  " + make_option_name(opt, positional) + make_option_opts(opt), make_option_desc(opt));
  }

  std::string make_subcommand(const CLI::App* sub) const override {
    return column("  " + sub->get_display_name(), sub->get_description());
  }

  std::string make_description(const CLI::App* app) const override {
    const std::string text = CLI::Formatter::make_description(app);
    return text.empty() ? text : joinLines(wrapWords(text, kHelpColumns), "");
  }

  std::string make_footer(const CLI::App* app) const override {
    const std::string text = app->get_footer();
    return text.empty() ? text : joinLines(wrapWords(text, kHelpColumns), "");
  }

 private:
  // CLI11's make_groups (not virtual) with the groups sorted by kHelpGroups.
  std::string orderedGroups(const CLI::App* app, CLI::AppFormatMode mode) const {
    std::vector<std::string> groups = app->get_groups();
    std::stable_sort(groups.begin(), groups.end(),
                     [](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
    std::string out;
    for (const std::string& group : groups) {
      const std::vector<const CLI::Option*> options =
          app->get_options([app, mode, &group](const CLI::Option* o) {
            return o->get_group() == group && o->nonpositional() &&
                   (mode != CLI::AppFormatMode::Sub ||
                    (app->get_help_ptr() != o && app->get_help_all_ptr() != o));
          });
      if (!group.empty() && !options.empty()) out += make_group(group, false, options);
    }
    return out;
  }

  static size_t rank(const std::string& group) {
    for (size_t i = 0; i < std::size(kHelpGroups); ++i)
      if (kHelpGroups[i] == group) return i + 1;
    return 0;
  }

  std::string column(const std::string& name, const std::string& description) const {
    const size_t width = get_column_width();
    const std::vector<std::string> left = wrapWords(name, kHelpColumns - 6);
    std::string out = joinLines(left, "      ");
    if (description.empty()) return out;
    const std::vector<std::string> right = wrapWords(description, kHelpColumns - width);
    const std::string pad(width, ' ');
    if (left.size() == 1 && left[0].size() + 2 <= width) {
      out = left[0] + std::string(width - left[0].size(), ' ');
      return out + joinLines(right, pad);
    }
    return out + pad + joinLines(right, pad);
  }
};

// Optimal string alignment distance: inserts, deletes, changes and swaps of neighbours cost one each.
size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string lowered(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// An option's name as typed ("--density", "-o"), not a value that happens to start with '-' ("-4",
// "-0.3,1,0,500").
bool isOptionName(const std::string& arg) {
  if (arg.size() < 2 || arg[0] != '-') return false;
  const size_t letter = arg[1] == '-' ? 2 : 1;
  return letter < arg.size() && std::isalpha(static_cast<unsigned char>(arg[letter]));
}

std::vector<std::string> optionNames(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* o : cmd.get_options()) {
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    for (const std::string& n : o->get_snames()) names.push_back("-" + n);
  }
  return names;
}

std::string suggestion(const std::string& given, const std::vector<std::string>& names) {
  const std::string near = nearestName(given, names);
  return near.empty() ? "" : "; did you mean " + near + "?";
}

}  // namespace

std::shared_ptr<CLI::Formatter> groupedHelpFormatter() {
  return std::make_shared<GroupedHelp>();
}

std::string nearestName(const std::string& given, const std::vector<std::string>& names) {
  const std::string typed = lowered(given);
  const size_t letters = typed.size() - std::min(typed.find_first_not_of('-'), typed.size());
  const size_t allowed = std::max<size_t>(1, letters / 4);
  std::string best, onlyPrefix;
  size_t bestDistance = allowed + 1, prefixes = 0;
  for (const std::string& name : names) {
    const std::string candidate = lowered(name);
    const size_t d = editDistance(typed, candidate);
    if (d < bestDistance) {
      bestDistance = d;
      best = name;
    }
    if (letters >= 3 && candidate.rfind(typed, 0) == 0) {
      ++prefixes;
      onlyPrefix = name;
    }
  }
  if (!best.empty()) return best;
  return prefixes == 1 ? onlyPrefix : "";
}

std::string unknownNameMessage(const CLI::App& app, const std::vector<std::string>& args) {
  const CLI::App* cmd = nullptr;
  const std::vector<const CLI::App*> commands = app.get_subcommands([](const CLI::App*) { return true; });
  for (const std::string& arg : args) {
    if (arg == "--") break;
    if (isOptionName(arg)) {
      const CLI::App& in = cmd ? *cmd : app;
      const std::string name = arg.substr(0, arg.find('='));
      if (in.get_option_no_throw(name)) continue;
      const std::string where = cmd ? cmd->get_name() + ": " : "";
      return where + name + " is not an option" + suggestion(name, optionNames(in));
    }
    if (cmd) continue;  // a value or a positional argument of the command
    for (const CLI::App* c : commands)
      if (c->check_name(arg)) cmd = c;
    if (cmd) continue;
    std::vector<std::string> names;
    for (const CLI::App* c : commands) names.push_back(c->get_name());
    const std::string near = suggestion(arg, names);
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    return printable(arg) + " is not a command" + (near.empty() ? " (the commands: " + list + ")" : near);
  }
  return {};
}

}  // namespace cpgi::cli
