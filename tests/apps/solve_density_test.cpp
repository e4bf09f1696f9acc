// End to end (issue 13 item 2, issue 12's house): `bake --solve-density auto`, the default, solves a
// large atlas in two levels (the interreflection on a coarser atlas) and a small one as before; a value
// forces it, and anything else is refused naming the option.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using nlohmann::json;
using test::cpgi;
using test::slurp;

json bake(const test::TempDir& dir, const std::string& scene, const std::string& name,
          const std::string& options) {
  const test::CommandRun r =
      cpgi(dir, "bake '" + scene + "' -o '" + dir / name + "' --item-buffer 128 --unshot 0.2 -q " + options);
  EXPECT_EQ(r.status, 0) << r.err;
  return json::parse(slurp(dir / name + "/report.json"));
}

TEST(SolveDensity, AutoIsOneLevelForASmallAtlasAndTwoForALargeOne) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const json small = bake(dir, scene, "small", "--texels-per-quad 8");
  EXPECT_EQ(small["solve_density_option"], "auto");
  EXPECT_TRUE(small["solve_density"].is_null());
  EXPECT_EQ(small["solve_texels"], small["texels"]);
  // 64² texels a quad: 180 224 texels, past the 100 000 of auto.
  const json large = bake(dir, scene, "large", "--texels-per-quad 64");
  EXPECT_GT(large["texels"].get<size_t>(), 100'000u);
  EXPECT_EQ(large["solve_density"], 5.0);
  EXPECT_LT(large["solve_texels"].get<size_t>(), large["texels"].get<size_t>() / 4);
  const json& e = large["energy"];
  const double emitted = e["emitted_w"].get<double>();
  EXPECT_NEAR(e["absorbed_w"].get<double>() + e["unshot_w"].get<double>() + e["escaped_w"].get<double>(),
              emitted, 1e-3 * emitted);
  // Forced: one level on the large atlas, two on the small.
  const json one = bake(dir, scene, "one", "--texels-per-quad 64 --solve-density 0");
  EXPECT_TRUE(one["solve_density"].is_null());
  EXPECT_EQ(one["solve_texels"], one["texels"]);
  EXPECT_EQ(one["solve_density_option"], 0.0);
  const json two = bake(dir, scene, "two", "--density 10 --solve-density 5");
  EXPECT_EQ(two["solve_density"], 5.0);
  // The interreflection by rays where the GL device is llvmpipe (--indirect-solver auto), by item buffers
  // when asked, and the same light either way within the stop's share.
  EXPECT_EQ(two["renderer"].get<std::string>().find("llvmpipe") != std::string::npos ? "rays" : "gpu",
            two["indirect_solver"]);
  const json gpu = bake(dir, scene, "gpu", "--density 10 --solve-density 5 --indirect-solver gpu");
  EXPECT_EQ(gpu["indirect_solver"], "gpu");
  EXPECT_NEAR(gpu["energy"]["absorbed_w"].get<double>(), two["energy"]["absorbed_w"].get<double>(),
              0.2 * two["energy"]["emitted_w"].get<double>());
  EXPECT_EQ(cpgi(dir, "bake '" + scene + "' -o '" + dir / "bad" + "' --indirect-solver cuda").status, 1);
}

// Cells in two levels when asked: the lamps on the output's atlas, the cells on the coarse one; auto keeps
// a cells bake in one level, as its cell jobs are, and cell jobs or on-demand bakes refuse a value.
TEST(SolveDensity, CellsSolveInTwoLevelsWhenAsked) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const std::string cells = " --method cells --cells '" + scene + "' --density 10";
  const json one = bake(dir, scene, "one", cells);
  EXPECT_TRUE(one["solve_density"].is_null());
  const json two = bake(dir, scene, "two", cells + " --solve-density 5");
  EXPECT_EQ(two["solve_density"], 5.0);
  EXPECT_LT(two["solve_texels"].get<size_t>() * 2, two["texels"].get<size_t>());
  EXPECT_EQ(two["cells"].size(), one["cells"].size());
  const json& e = two["energy"];
  const double emitted = e["emitted_w"].get<double>();
  EXPECT_NEAR(e["absorbed_w"].get<double>() + e["unshot_w"].get<double>() + e["escaped_w"].get<double>(),
              emitted, 1e-3 * emitted);
  for (const std::string refused : {" --plan '" + dir / "plan" + "'", std::string(" --only-cells A")}) {
    const test::CommandRun r = cpgi(
        dir, "bake '" + scene + "' -o '" + dir / "bad" + "' -q" + cells + " --solve-density 5" + refused);
    EXPECT_EQ(r.status, 1) << refused;
    EXPECT_NE(r.err.find("--solve-density"), std::string::npos) << r.err;
  }
}

TEST(SolveDensity, AnythingButAutoOrTexelsPerMetreIsRefused) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  for (const char* bad : {"-1", "nan", "abc", "5x", "inf"}) {
    const test::CommandRun r =
        cpgi(dir, "bake '" + scene + "' -o '" + dir / "out" + "' --solve-density " + bad);
    EXPECT_EQ(r.status, 1) << bad;
    EXPECT_NE(r.err.find("--solve-density"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out/report.json"));
  }
}

}  // namespace
}  // namespace cpgi
