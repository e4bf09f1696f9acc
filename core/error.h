// User-facing errors: one line that names the stage, the input and the problem (style.md point 7).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

namespace cpgi {

/// The length of the well-formed UTF-8 sequence starting at text[at] (2 to 4 bytes: no overlong form,
/// no surrogate, at most U+10FFFF), or 0 when none starts there. C1 controls (U+0080 to U+009F) count as
/// none: some terminals act on them.
inline size_t utf8SequenceLength(const std::string& text, size_t at) {
  const auto byte = [&](size_t i) {
    return at + i < text.size() ? static_cast<unsigned char>(text[at + i]) : 0u;
  };
  const unsigned lead = byte(0);
  const size_t length = lead >= 0xC2 && lead <= 0xDF   ? 2
                        : lead >= 0xE0 && lead <= 0xEF ? 3
                        : lead >= 0xF0 && lead <= 0xF4 ? 4
                                                       : 0;
  if (length == 0) return 0;
  uint32_t code = lead & (0xFF >> (length + 1));
  for (size_t i = 1; i < length; ++i) {
    if ((byte(i) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i) & 0x3F);
  }
  const uint32_t least[] = {0, 0, 0xA0, 0x800, 0x10000};
  if (code < least[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return length;
}

/// `text` fit for a one-line message: control characters and bytes that are not UTF-8 escaped (a node
/// name may hold a newline, or bytes a terminal would act on), at most `maxChars` characters kept (a data
/// URI can be megabytes long), the full length said when cut.
inline std::string printable(const std::string& text, size_t maxChars = 80) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  size_t kept = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (kept++ == maxChars) {
      out += "... (" + std::to_string(text.size()) + " characters)";
      break;
    }
    const size_t sequence = c >= 0x80 ? utf8SequenceLength(text, i) : 0;
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (sequence > 0) {
      out.append(text, i, sequence);
      i += sequence - 1;
    } else if (c < 0x20 || c >= 0x7f) {
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
