// End to end (issue 13 item 2, issue 12's house): `bake --solve-density auto`, the default, solves a
// large atlas in two levels (the interreflection on a coarser atlas) and a small one as before; a value
// forces it, and anything else is refused naming the option.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using nlohmann::json;
using test::cpgi;
using test::slurp;

// The bakes below in process (nothing written: their reports are what is read): `bake SCENE --item-buffer
// 128 --unshot 0.2` and the options each sets.
BakeSettings quick(const std::string& scene) {
  BakeSettings s;
  s.input.scene = scene;
  s.solver.params.itemBuffer = 128;
  s.solver.params.unshotFraction = 0.2;
  return s;
}
BakeSettings texelsPerQuad(BakeSettings s, int n) {  // --texels-per-quad N
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = n;
  return s;
}
BakeSettings density(BakeSettings s, float d) {  // --density D
  s.atlas.densityAuto = false;
  s.atlas.params.density = d;
  return s;
}
BakeSettings solveDensity(BakeSettings s, float d) {  // --solve-density D
  s.solver.solveDensity = d;
  return s;
}
// --max-shots 10: on the large atlas the levels chosen and the energy's bookkeeping are what is checked,
// which hold at any stop; its 180 224 texels shot to the 20 % stop took most of the test's time.
BakeSettings fewShots(BakeSettings s) {
  s.solver.params.maxShots = 10;
  return s;
}
json bake(const BakeSettings& s) {
  return test::bakeHere(s).report;
}

TEST(SolveDensity, AutoIsOneLevelForASmallAtlasAndTwoForALargeOne) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const json small = bake(texelsPerQuad(quick(scene), 8));
  EXPECT_EQ(small["solve_density_option"], "auto");
  EXPECT_TRUE(small["solve_density"].is_null());
  EXPECT_EQ(small["solve_texels"], small["texels"]);
  // 64² texels a quad: 180 224 texels, past the 100 000 of auto.
  const json large = bake(fewShots(texelsPerQuad(quick(scene), 64)));
  EXPECT_GT(large["texels"].get<size_t>(), 100'000u);
  EXPECT_EQ(large["solve_density"], 5.0);
  EXPECT_LT(large["solve_texels"].get<size_t>(), large["texels"].get<size_t>() / 4);
  const json& e = large["energy"];
  const double emitted = e["emitted_w"].get<double>();
  EXPECT_NEAR(e["absorbed_w"].get<double>() + e["unshot_w"].get<double>() + e["escaped_w"].get<double>(),
              emitted, 1e-3 * emitted);
  // Forced: one level on the large atlas, two on the small.
  const json one = bake(fewShots(solveDensity(texelsPerQuad(quick(scene), 64), 0)));
  EXPECT_TRUE(one["solve_density"].is_null());
  EXPECT_EQ(one["solve_texels"], one["texels"]);
  EXPECT_EQ(one["solve_density_option"], 0.0);
  const json two = bake(solveDensity(density(quick(scene), 10), 5));
  EXPECT_EQ(two["solve_density"], 5.0);
  // The interreflection by rays where the GL device is llvmpipe (--indirect-solver auto), by item buffers
  // when asked, and the same light either way within the stop's share.
  EXPECT_EQ(two["renderer"].get<std::string>().find("llvmpipe") != std::string::npos ? "rays" : "gpu",
            two["indirect_solver"]);
  BakeSettings byGpu = solveDensity(density(quick(scene), 10), 5);
  byGpu.solver.indirect = IndirectSolver::Gpu;  // --indirect-solver gpu
  const json gpu = bake(byGpu);
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
  BakeSettings byCells = density(quick(scene), 10);
  byCells.cells.method = BakeMethod::Cells;
  byCells.cells.source = scene;
  const json one = bake(byCells);
  EXPECT_TRUE(one["solve_density"].is_null());
  const json two = bake(solveDensity(byCells, 5));
  EXPECT_EQ(two["solve_density"], 5.0);
  EXPECT_LT(two["solve_texels"].get<size_t>() * 2, two["texels"].get<size_t>());
  EXPECT_EQ(two["cells"].size(), one["cells"].size());
  const json& e = two["energy"];
  const double emitted = e["emitted_w"].get<double>();
  EXPECT_NEAR(e["absorbed_w"].get<double>() + e["unshot_w"].get<double>() + e["escaped_w"].get<double>(),
              emitted, 1e-3 * emitted);
  for (const std::string& refused : {" --plan '" + dir / "plan" + "'", std::string(" --only-cells A")}) {
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
