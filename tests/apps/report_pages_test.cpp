// report.html beside a decomposition and a comparison (compare-light --report), with the data each needs:
// cells and portals from cells.glb; the error per texel against the reference.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::quote;

nlohmann::json pageData(const std::string& page) {
  const std::string open = "<script id=\"cpgi-data\" type=\"application/json\">";
  const size_t start = page.find(open);
  if (start == std::string::npos) return nullptr;
  const size_t from = start + open.size();
  return nlohmann::json::parse(page.substr(from, page.find("</script>", from) - from));
}

TEST(ReportPages, DecompositionShowsItsCellsAndPortals) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(scene)).status, 0);
  const test::CommandRun r = cpgi(dir, "decompose " + quote(scene) + " -o " + quote(dir / "d"));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json data = pageData(test::slurp(dir / "d/report.html"));
  ASSERT_TRUE(data.is_object());
  const nlohmann::json cells = nlohmann::json::parse(test::slurp(dir / "d/cells.json"));
  EXPECT_EQ(data["kind"], "decomposition");
  EXPECT_FALSE(data.contains("lightmap"));
  EXPECT_EQ(data["report"], cells);
  EXPECT_GE(data["cells"].size(), 2u);
  EXPECT_GE(data["portals"].size(), 1u);
  for (const auto& c : data["cells"]) EXPECT_TRUE(c.contains("eye")) << c.dump();
}

TEST(ReportPages, ComparisonCarriesTheErrorPerTexel) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(scene)).status, 0);
  const std::string atlas = " --density 3";
  ASSERT_EQ(cpgi(dir, "bake " + quote(scene) + " -o " + quote(dir / "bake") + atlas + " -q").status, 0);
  ASSERT_EQ(
      cpgi(dir, "reference " + quote(scene) + " -o " + quote(dir / "ref") + atlas + " --spp 4 -q").status, 0);
  const test::CommandRun r = cpgi(dir, "compare-light " + quote(dir / "bake") + " " + quote(dir / "ref") +
                                           " --report " + quote(dir / "cmp"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("rel_rmse"), std::string::npos);  // the usual figures still go to stdout
  const nlohmann::json data = pageData(test::slurp(dir / "cmp/report.html"));
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["kind"], "comparison");
  EXPECT_GT(data["report"]["rel_rmse"].get<double>(), 0.0);
  const int texels = data["lightmap"]["width"].get<int>() * data["lightmap"]["height"].get<int>();
  EXPECT_EQ(data["lightmap"]["error"].get<std::string>().size(), size_t(4 * ((4 * texels + 2) / 3)));
  EXPECT_EQ(data["cells"].size(), 3u);  // seed1's hand-made cells, from the bake's baked.glb
  // compare-light's per-cell figures, for the page's cells table.
  ASSERT_EQ(data["report"]["cells"].size(), 3u) << data["report"].dump(1);
  EXPECT_GT(data["report"]["cells"][0]["rel_rmse"].get<double>(), 0.0);
  EXPECT_TRUE(data["report"]["worst_cell"].is_string());

  // A has no preview.glb: one line naming it, no page.
  const test::CommandRun bad = cpgi(dir, "compare-light " + quote(dir / "ref") + " " + quote(dir / "ref") +
                                             " --report " + quote(dir / "bad"));
  std::filesystem::remove(dir / "ref/preview.glb");
  const test::CommandRun missing = cpgi(dir, "compare-light " + quote(dir / "ref") + " " +
                                                 quote(dir / "bake") + " --report " + quote(dir / "bad2"));
  EXPECT_EQ(bad.status, 0) << bad.err;  // a reference folder is a valid A
  EXPECT_EQ(missing.status, 1);
  ASSERT_EQ(missing.errLines().size(), 1u) << missing.err;
  EXPECT_NE(missing.err.find("preview.glb"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad2/report.html"));
}

}  // namespace
}  // namespace cpgi
