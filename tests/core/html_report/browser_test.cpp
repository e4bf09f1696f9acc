// report.html in a real browser: headless Chromium (Debian's) driven by puppeteer-core opens the report
// of a cells bake of seed1, and that of a comparison with a reference, and checks what they draw
// (core/html_report/web/browser_test.mjs: the canvas follows the lightmap; cells, texel density, portals and
// the error heat map toggle; exposure brightens; in-cell views are readable; walking moves; tables are
// there; the comparison's bench chart). The screenshots stay in BUILD_DIR/report-screenshots.
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>

#include "tests/core/html_report/node_tools.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::quote;

// Empty when node, the npm packages and chromium are there; otherwise what is missing.
std::string missingBrowser() {
  std::string missing = test::missingNodeTools();
  if (missing.empty() && !std::filesystem::exists(CPGI_CHROMIUM))
    missing = "chromium is not installed (./setup.sh installs it)";
  return missing;
}

// Runs core/html_report/web/browser_test.mjs on `page`; screenshots into BUILD_DIR/report-screenshots/NAME.
void expectPageWorks(const test::TempDir& dir, const std::string& page, const std::string& name) {
  const std::string shots = std::string(CPGI_SCREENSHOTS) + "/" + name;
  const test::CommandRun r = test::runNodeScript(
      dir.path(), "browser_test.mjs", quote(CPGI_CHROMIUM) + " " + quote(page) + " " + quote(shots));
  std::cout << "figures: " << r.out << "\nscreenshots: " << shots << "\n";
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST(ReportInBrowser, Seed1CellsBakeShowsLitSceneCellsAndPortals) {
  const std::string missing = missingBrowser();
  if (!missing.empty()) GTEST_SKIP() << "SKIPPED, NOT TESTED: the browser test cannot run: " << missing;

  test::TempDir dir;
  const std::string scene = dir / "seed1.glb", out = dir / "bake";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(scene)).status, 0);
  const test::CommandRun bake = cpgi(
      dir, "bake " + quote(scene) + " -o " + quote(out) + " --method cells --cells " + quote(scene) + " -q");
  ASSERT_EQ(bake.status, 0) << bake.err;
  ASSERT_TRUE(std::filesystem::exists(out + "/report.html"));
  expectPageWorks(dir, out + "/report.html", "seed1");
}

TEST(ReportInBrowser, Seed1ComparisonShowsTheErrorHeatMap) {
  const std::string missing = missingBrowser();
  if (!missing.empty()) GTEST_SKIP() << "SKIPPED, NOT TESTED: the browser test cannot run: " << missing;

  test::TempDir dir;
  const std::string scene = dir / "seed1.glb", atlas = " --density 3";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(scene)).status, 0);
  ASSERT_EQ(cpgi(dir, "bake " + quote(scene) + " -o " + quote(dir / "bake") + atlas + " -q").status, 0);
  ASSERT_EQ(
      cpgi(dir, "reference " + quote(scene) + " -o " + quote(dir / "ref") + atlas + " --spp 4 -q").status, 0);
  // Two scenes' bench rows (bench/speed_accuracy.py's results.json): the page charts them.
  {
    std::ofstream bench(dir / "results.json");
    bench
        << R"([{"scene": "seed1", "resolution": "8", "method": "global-hemicube", "seconds": 2.5, "rel_rmse": 0.08},
      {"scene": "seed1", "resolution": "16", "method": "global-hemicube", "seconds": 9, "rel_rmse": 0.04,
       "rel_rmse_nonemissive": 0.05},
      {"scene": "seed1", "resolution": "8", "method": "cells-diffuse", "seconds": 1.5, "rel_rmse": 0.09},
      {"scene": "seed3", "resolution": "8", "method": "cells-diffuse", "seconds": 30, "rel_rmse": 0.02}])";
  }
  const test::CommandRun compare =
      cpgi(dir, "compare-light " + quote(dir / "bake") + " " + quote(dir / "ref") + " --report " +
                    quote(dir / "cmp") + " --bench " + quote(dir / "results.json"));
  ASSERT_EQ(compare.status, 0) << compare.err;
  expectPageWorks(dir, dir / "cmp/report.html", "seed1-comparison");
}

}  // namespace
}  // namespace cpgi
