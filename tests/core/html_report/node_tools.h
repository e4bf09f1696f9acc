// The node tools of core/html_report/web/ as the report tests run them: node and the npm packages setup.sh
// installs (CPGI_NODE, CPGI_NODE_MODULES), and Debian's chromium (CPGI_CHROMIUM).
#pragma once

#include <filesystem>
#include <string>

#include "tests/support/run_cpgi.h"

namespace cpgi::test {

/// Empty when node and the npm packages are there; otherwise what is missing, for a loud GTEST_SKIP.
inline std::string missingNodeTools() {
  namespace fs = std::filesystem;
  if (!fs::exists(CPGI_NODE)) return "node is not installed (./setup.sh installs it)";
  if (!fs::exists(fs::path(CPGI_NODE_MODULES) / "gltf-validator"))
    return std::string("no npm packages in ") + CPGI_NODE_MODULES + " (./setup.sh installs them)";
  return {};
}

/// `node core/html_report/web/SCRIPT ARGS` (ARGS is shell text), output captured through files in `folder`.
inline CommandRun runNodeScript(const std::filesystem::path& folder, const std::string& script,
                                const std::string& args) {
  const std::string out = (folder / "node-stdout.txt").string(), err = (folder / "node-stderr.txt").string();
  const std::string command =
      quote(CPGI_NODE) + " " + quote(std::string(CPGI_SOURCE_DIR) + "/core/html_report/web/" + script) + " " +
      quote(CPGI_NODE_MODULES) + " " + args + " > " + quote(out) + " 2> " + quote(err);
  const int raw = std::system(command.c_str());
  CommandRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace cpgi::test
