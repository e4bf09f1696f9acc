// User-facing errors: one line that names the stage, the input and the problem (style.md point 7).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace cpgi {

/// `text` fit for a one-line message: control characters escaped (a node name may hold a newline), at
/// most `maxChars` characters kept (a data URI can be megabytes long), the full length said when cut.
inline std::string printable(const std::string& text, size_t maxChars = 80) {
  std::string out;
  size_t kept = 0;
  for (unsigned char c : text) {
    if (kept++ == maxChars) {
      out += "... (" + std::to_string(text.size()) + " characters)";
      break;
    }
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

/// A problem with what the user handed us (a file, an option). The CLI prints what() and exits 1.
class InputError : public std::runtime_error {
 public:
  /// @param where  the file or parameter at fault, e.g. "scenes/house.glb" or "voxel size": libraries name
  ///                parameters in words, the command line maps them to its flags (apps/options.h)
  /// @param problem  what is wrong, lower case, no trailing period; another parameter it mentions is
  ///                 quoted `like this`, so the command line can name its flag instead
  /// Both are kept to one line of sane length whatever a file smuggled into them.
  InputError(const std::string& where, const std::string& problem)
      : InputError(Printable{printable(where, 1000), printable(problem, 2000)}) {}
  const std::string& where() const { return where_; }
  const std::string& problem() const { return problem_; }

 private:
  struct Printable {
    std::string where, problem;
  };
  explicit InputError(Printable p)
      : std::runtime_error(p.where + ": " + p.problem),
        where_(std::move(p.where)),
        problem_(std::move(p.problem)) {}
  std::string where_;
  std::string problem_;
};

/// A failure of the machine rather than of the input (no OpenGL context, disk full).
class SystemError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cpgi
