// User-facing errors: one line that names the stage, the input and the problem (style.md point 7).
#pragma once

#include <stdexcept>
#include <string>

namespace cpgi {

/// A problem with what the user handed us (a file, an option). The CLI prints what() and exits 1.
class InputError : public std::runtime_error {
 public:
  /// @param where  the file or parameter at fault, e.g. "scenes/house.glb" or "voxel size": libraries name
  ///                parameters in words, the command line maps them to its flags (apps/options.h)
  /// @param problem  what is wrong, lower case, no trailing period; another parameter it mentions is
  ///                 quoted `like this`, so the command line can name its flag instead
  InputError(const std::string& where, const std::string& problem)
      : std::runtime_error(where + ": " + problem), where_(where), problem_(problem) {}
  const std::string& where() const { return where_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string where_;
  std::string problem_;
};

/// A failure of the machine rather than of the input (no OpenGL context, disk full).
class SystemError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cpgi
