// End to end: `cpgi bake --method cells --portals directional` on the spot through a door
// (scenes/stability_scenes.h), where a diffuse portal is the known failure: against the path-traced
// reference, directional portals must undo most of the diffuse portal's excess error over the global solve.
#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::slurp;

double nonEmissiveError(const test::TempDir& dir, const std::string& bake) {
  const test::CommandRun r = cpgi(dir, "compare-light '" + dir / bake + "' '" + dir / "ref" + "' --json");
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(r.out)["rel_rmse_nonemissive"].get<double>();
}

TEST(DirectionalBake, SpotThroughADoorAgainstTheReference) {
  test::TempDir dir;
  const std::string scene = dir / "spot.glb";
  ASSERT_EQ(cpgi(dir, "generate spot-door -o '" + scene + "'").status, 0);
  // On the thesis's fixed eyes, where the portal modes' difference was measured: this test compares the
  // portal modes, not the eyes (bench/RESULTS.md, issue 11, for the global solve with drawn eyes).
  // In process, into the folders compare-light reads: --texels-per-quad 8 --unshot 1e-3 --item-buffer 256
  // --fixed-eyes, globally and cell by cell with diffuse and directional portals.
  BakeSettings s = test::cellsBake(scene, scene);
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 8;
  s.solver.params.unshotFraction = 1e-3;
  s.solver.params.itemBuffer = 256;
  s.solver.params.jitteredEyes = false;
  s.output.views.width = 64;  // the pictures are not what is compared
  for (const auto& [out, portals] : {std::pair("diffuse", PortalLight::Diffuse),
                                     std::pair("directional", PortalLight::Directional)}) {
    s.cells.params.portals = portals;
    s.output.folder = dir / out;
    test::bakeHere(s);
  }
  s.cells.method = BakeMethod::Global;
  s.output.folder = dir / "global";
  test::bakeHere(s);
  ASSERT_EQ(cpgi(dir, "reference '" + scene + "' -o '" + dir / "ref" + "' --texels-per-quad 8 --spp 256 -q").status, 0);
  const nlohmann::json report = nlohmann::json::parse(slurp(dir / "directional/report.json"));
  EXPECT_EQ(report["portal_mode"], "directional");
  const auto& e = report["energy"];
  EXPECT_NEAR(e["absorbed_w"].get<double>() + e["unshot_w"].get<double>() + e["escaped_w"].get<double>(),
              e["emitted_w"].get<double>(), 1e-3 * e["emitted_w"].get<double>());

  const double global = nonEmissiveError(dir, "global"), diffuse = nonEmissiveError(dir, "diffuse"),
               directional = nonEmissiveError(dir, "directional");
  std::printf("spot-door 8x8: relative RMSE (non-emissive) global %.4f, cells diffuse %.4f, directional %.4f\n",
              global, diffuse, directional);
  // The spot's beam crossed the door as portal light, and a diffuse portal spread it: the cells' excess
  // error over the global solve was > 0.1 with diffuse portals, halved by directional ones. Since the
  // lights' first shot goes over the whole scene (radiosity/cells/cell_first_shot.h) both are at the
  // global solve's error: measured +0.004 either way.
  EXPECT_LT(diffuse - global, 0.02);
  EXPECT_LT(directional - global, 0.02);
}

TEST(DirectionalBake, UnknownPortalModeFailsWithOneLine) {
  test::TempDir dir;
  const std::string scene = dir / "spot.glb";
  ASSERT_EQ(cpgi(dir, "generate spot-door -o '" + scene + "'").status, 0);
  const test::CommandRun r = cpgi(dir, "bake '" + scene + "' -o '" + dir / "out" + "' --method cells --cells '" +
                                           scene + "' --portals spot -q");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--portals"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace cpgi
