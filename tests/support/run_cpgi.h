// Runs the `cpgi` binary under test (CPGI_BINARY) in a shell and captures what a user would see.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/temp_dir.h"

namespace cpgi::test {

struct CommandRun {
  int status = -1;  ///< exit status; 128 + signal when the process was killed (a crash)
  std::string out, err;
  /// The messages on stderr, without the progress lines a stage that lasts a second prints in a pipe
  /// (core/progress.h): a refusal after a long stage is still one line of message.
  std::vector<std::string> errLines() const {
    std::vector<std::string> lines;
    for (const std::string& line : allErrLines())
      if (line.rfind("progress: ", 0) != 0) lines.push_back(line);
    return lines;
  }
  std::vector<std::string> allErrLines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// Single-quotes `s` for the shell.
inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// A shell command line with stdout and stderr captured through the files `prefix`stdout.txt and
/// `prefix`stderr.txt in `folder`.
inline CommandRun runCaptured(const std::filesystem::path& folder, const std::string& commandLine,
                              const std::string& prefix = "") {
  const std::string out = (folder / (prefix + "stdout.txt")).string();
  const std::string err = (folder / (prefix + "stderr.txt")).string();
  const std::string command = commandLine + " > " + quote(out) + " 2> " + quote(err);
  const int raw = std::system(command.c_str());
  CommandRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

/// `cpgi ARGS` with stdout and stderr captured through files in `folder`. ARGS is shell text: quote paths.
inline CommandRun cpgi(const std::filesystem::path& folder, const std::string& args) {
  return runCaptured(folder, quote(CPGI_BINARY) + " " + args);
}

inline CommandRun cpgi(const TempDir& dir, const std::string& args) {
  return cpgi(dir.path(), args);
}

/// `cpgi ARGS` for a suite's set-up (generate, reference, bake), where a failure leaves nothing to test:
/// throws with the command and its stderr.
inline void cpgiOrThrow(const TempDir& dir, const std::string& args) {
  const CommandRun r = cpgi(dir, args);
  if (r.status != 0) throw std::runtime_error("cpgi " + args + ": " + r.err);
}

}  // namespace cpgi::test
