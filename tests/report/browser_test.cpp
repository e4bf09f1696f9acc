// report.html in a real browser: headless Chromium (Debian's) driven by puppeteer-core opens the report
// of a cells bake of seed1 and checks what it draws (report/web/browser_test.mjs: the canvas follows the
// lightmap, cells and texel density and portals toggle, exposure brightens, tables are there). The
// screenshots stay in BUILD_DIR/report-screenshots.
#include <gtest/gtest.h>

#include "tests/report/node_tools.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::quote;

TEST(ReportInBrowser, Seed1CellsBakeShowsLitSceneCellsAndPortals) {
  std::string missing = test::missingNodeTools();
  if (missing.empty() && !std::filesystem::exists(CPGI_CHROMIUM))
    missing = "chromium is not installed (./setup.sh installs it)";
  if (!missing.empty()) GTEST_SKIP() << "SKIPPED, NOT TESTED: the browser test cannot run: " << missing;

  test::TempDir dir;
  const std::string scene = dir / "seed1.glb", out = dir / "bake";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(scene)).status, 0);
  const test::CommandRun bake = cpgi(
      dir, "bake " + quote(scene) + " -o " + quote(out) + " --method cells --cells " + quote(scene) + " -q");
  ASSERT_EQ(bake.status, 0) << bake.err;
  ASSERT_TRUE(std::filesystem::exists(out + "/report.html"));

  const std::string shots = std::string(CPGI_SCREENSHOTS) + "/seed1";
  const test::CommandRun r =
      test::runNodeScript(dir.path(), "browser_test.mjs",
                          quote(CPGI_CHROMIUM) + " " + quote(out + "/report.html") + " " + quote(shots));
  std::cout << "figures: " << r.out << "screenshots: " << shots << "\n";
  EXPECT_EQ(r.status, 0) << r.err;
}

}  // namespace
}  // namespace cpgi
