// compare-light --bench FILE: the bench results are checked before anything else, so a wrong file fails
// at once with one line naming it, and --bench needs --report (the chart is a part of report.html). That
// the page draws the chart is tests/core/html_report/browser_test.cpp's.
#include <fstream>

#include <gtest/gtest.h>

#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::quote;

TEST(BenchChart, BadResultsFailWithOneLineNamingTheFile) {
  test::TempDir dir;
  const struct {
    const char* text;
    const char* expected;
  } cases[] = {
      {"{\"scene\": \"seed1\"}", "is not a JSON array of bench rows"},
      {"[", "is not a JSON array of bench rows"},
      {"[]", "is not a JSON array of bench rows"},
      {"[{\"scene\": \"seed1\", \"method\": \"cells-diffuse\", \"seconds\": 2}]", "row 1 lacks"},
      {"[{\"scene\": \"s\", \"method\": \"m\", \"seconds\": 2, \"rel_rmse\": 0.1}, {\"scene\": \"s\"}]",
       "row 2 lacks"},
      {"[{\"scene\": \"s\", \"method\": \"m\", \"seconds\": -1, \"rel_rmse\": 0.1}]", "row 1 lacks"},
  };
  const std::string file = dir / "results.json";
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    std::ofstream(file) << c.text;
    // The folders need not exist: the bench file is read first.
    const test::CommandRun r =
        cpgi(dir.path(), "compare-light " + quote(dir / "a") + " " + quote(dir / "b") + " --report " +
                             quote(dir / "page") + " --bench " + quote(file));
    EXPECT_EQ(r.status, 1);
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
  }
  const test::CommandRun missing =
      cpgi(dir.path(), "compare-light a b --report p --bench " + quote(dir / "none.json"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("cannot read it"), std::string::npos) << missing.err;
  const test::CommandRun alone = cpgi(dir.path(), "compare-light a b --bench " + quote(file));
  EXPECT_EQ(alone.status, 1);
  EXPECT_NE(alone.err.find("--report"), std::string::npos) << alone.err;
}

}  // namespace
}  // namespace cpgi
