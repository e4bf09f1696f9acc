// End to end (issue 13 item 2): `bake --density auto` lays the output atlas out from a first shot of the
// lamps, records its choice in report.json, and its lightmap is judged against a fixed-density one with
// `compare-light --scene`, which reads it at the other's texels as an engine would.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using nlohmann::json;
using test::cpgi;
using test::slurp;

constexpr const char* kQuick = " --item-buffer 128 --unshot 0.05 -q";

// kQuick as settings, for the bakes run in process, into `folder`.
BakeSettings quick(const std::string& scene, const std::string& folder) {
  BakeSettings s;
  s.input.scene = scene;
  s.output.folder = folder;
  s.solver.params.itemBuffer = 128;
  s.solver.params.unshotFraction = 0.05;
  return s;
}

TEST(AutoDensity, ChoosesTexelsPerSurfaceAndIsReadAtAnotherAtlassTexels) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  BakeSettings s = quick(scene, dir / "auto");  // --density auto, the default
  ASSERT_TRUE(s.atlas.densityAuto);
  const json a = test::bakeHere(s).report;
  EXPECT_EQ(a["density_option"], "auto");
  EXPECT_EQ(a["atlas"]["density"], "auto");
  const json& choice = a["auto_density"];
  EXPECT_GT(choice["pilot_texels"].get<size_t>(), 0u);
  const double least = choice["min_density"].get<double>();
  size_t charted = 0;
  double finest = 0.0, coarsest = 1e9;
  for (const json& d : choice["chart_texels_by_density"]) {
    charted += d["texels"].get<size_t>();
    finest = std::max(finest, d["density"].get<double>());
    coarsest = std::min(coarsest, d["density"].get<double>());
  }
  // Charts keep at least 2 texels an edge, so a small one may read finer than the most asked.
  EXPECT_GE(coarsest, least - 0.05);
  EXPECT_GT(finest, coarsest) << "seed1's light is not flat everywhere";
  EXPECT_GE(charted, a["texels"].get<size_t>());
  // The ceilings of rooms A and C, which no lamp lights, are shaded by the lamp hung 1 cm under each
  // from every bounce: the contact asks its most of both whole 4 × 4 m ceilings, (4 × 20)² texels each.
  const double contact = choice["max_contact_density"].get<double>();
  EXPECT_EQ(contact, 20.0);
  size_t atContact = 0;
  for (const json& d : choice["chart_texels_by_density"])
    if (std::abs(d["density"].get<double>() - contact) < 0.05) atContact += d["texels"].get<size_t>();
  EXPECT_GE(atContact, 2u * 80u * 80u);
  // Two levels, and no light made up on the way.
  EXPECT_EQ(a["solve_density"], 5.0);
  const json& e = a["energy"];
  EXPECT_GT(e["escaped_w"].get<double>(), -1e-3 * e["emitted_w"].get<double>());

  s = quick(scene, dir / "fixed");  // --density 8
  s.atlas.densityAuto = false;
  s.atlas.params.density = 8;
  test::bakeHere(s);
  // Different atlases: A is read at B's texels through the scene given, or else the one their reports name.
  test::CommandRun r = cpgi(
      dir, "compare-light '" + dir / "auto" + "' '" + dir / "fixed" + "' --json --scene '" + scene + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const json cmp = json::parse(r.out);
  r = cpgi(dir, "compare-light '" + dir / "auto" + "' '" + dir / "fixed" + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["rel_rmse"], cmp["rel_rmse"]);
  ASSERT_EQ(cmp["cells"].size(), 3u);
  for (const json& c : cmp["cells"]) {
    EXPECT_NEAR(c["ratio_of_means"].get<double>(), 1.0, 0.05) << c["name"];
    EXPECT_LT(c["rel_rmse"].get<double>(), 0.15) << c["name"];
  }
  // An auto atlas cannot be rebuilt from its report, so it is no B for another atlas.
  r = cpgi(dir, "compare-light '" + dir / "fixed" + "' '" + dir / "auto" + "' --scene '" + scene + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("auto"), std::string::npos) << r.err;
  // Another scene does not give B's atlas.
  const std::string other = dir / "seed2.glb";
  ASSERT_EQ(cpgi(dir, "generate seed2 -o '" + other + "'").status, 0);
  r = cpgi(dir, "compare-light '" + dir / "auto" + "' '" + dir / "fixed" + "' --scene '" + other + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("seed2.glb"), std::string::npos) << r.err;
  // With the scene gone from where the reports say, refused, saying how to go on.
  std::filesystem::rename(scene, dir / "moved.glb");
  r = cpgi(dir, "compare-light '" + dir / "auto" + "' '" + dir / "fixed" + "' --json");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--scene"), std::string::npos) << r.err;
}

// Cells lay their atlases out by the densities of the whole scene's pilot (their charts are the global
// atlas's, else the bake warns), and cell jobs take them from the plan rather than shooting pilots of their
// own: plan, first shot, rounds and gather give the single-process bake's lightmap byte for byte.
TEST(AutoDensity, CellsAndCellJobsFollowTheWholeScenesPilot) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const std::string cells = " --method cells --cells '" + scene + "' --density auto" + std::string(kQuick);
  BakeSettings s = quick(scene, dir / "one");  // the single process, in this one
  s.cells.method = BakeMethod::Cells;
  s.cells.source = scene;
  s.solver.solveDensity = 0.0f;  // one level, as cell jobs solve
  Context ctx;
  const json one = test::bakeHere(s, ctx).report;
  for (const std::string& w : ctx.warnings())
    EXPECT_EQ(w.find("charted differently"), std::string::npos) << w;
  test::CommandRun r;
  EXPECT_EQ(one["density_option"], "auto");
  EXPECT_GT(one["auto_density"]["pilot_texels"].get<size_t>(), 0u);

  const std::string plan = "'" + dir / "plan" + "'";
  r = cpgi(dir, "bake '" + scene + "' -o '" + dir / "jobs" + "'" + cells + " --plan " + plan);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(slurp(dir / "plan/plan.json"))["triangle_density"].size(),
            one["triangles"].get<size_t>());
  ASSERT_EQ(cpgi(dir, "cell-job " + plan + " --first-shot -q").status, 0);
  ASSERT_EQ(cpgi(dir, "cell-job " + plan + " --first-shot-sum -q").status, 0);
  for (int round = 1;; ++round) {
    r = cpgi(dir, "cell-job " + plan + " --status --json");
    ASSERT_EQ(r.status, 0) << r.err;
    if (json::parse(r.out)["next_step"] != "round") break;
    ASSERT_LT(round, 64);
    r = cpgi(dir, "cell-job " + plan + " --round " + std::to_string(round) + " -q");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  r = cpgi(dir, "cell-job " + plan + " --gather -q");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(slurp(dir / "jobs/lightmap.exr"), slurp(dir / "one/lightmap.exr"));
}

TEST(AutoDensity, RefusedWhereItDoesNotApply) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  for (const std::string& options :
       {std::string("--density auto --texels-per-quad 8"), std::string("--density abc"),
        std::string("--density -2"), std::string("--density nan")}) {
    const test::CommandRun r = cpgi(dir, "bake '" + scene + "' -o '" + dir / "out" + "' -q " + options);
    EXPECT_EQ(r.status, 1) << options;
    EXPECT_NE(r.err.find("--"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out/report.json")) << options;
  }
}

// `--max-texels N` (issue 46): the automatic density scaled down to fit, said in one line, recorded in
// report.json; `--scale` as a loading option, with the units check's one line for a scene not in metres.
TEST(AutoDensity, MaxTexelsScalesTheDensityDownToFitAndScaleLoadsInMetres) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  test::CommandRun r = cpgi(dir, "bake '" + scene + "' -o '" + dir / "whole" + "'" + kQuick);
  ASSERT_EQ(r.status, 0) << r.err;
  const size_t whole = json::parse(slurp(dir / "whole/report.json"))["texels"].get<size_t>();
  const size_t budget = whole / 3;
  r = cpgi(dir, "bake '" + scene + "' -o '" + dir / "fit" + "' --max-texels " + std::to_string(budget) +
                    " --item-buffer 128 --unshot 0.05");
  ASSERT_EQ(r.status, 0) << r.err;
  const json a = json::parse(slurp(dir / "fit/report.json"));
  EXPECT_LE(a["texels"].get<size_t>(), budget);
  EXPECT_EQ(a["max_texels"].get<size_t>(), budget);
  EXPECT_TRUE(a["stop_bounded"].is_boolean());
  size_t lines = 0;
  for (size_t at = r.err.find("--max-texels"); at != std::string::npos;
       at = r.err.find("--max-texels", at + 1))
    ++lines;
  EXPECT_EQ(lines, 1u) << r.err;
  EXPECT_NE(r.err.find("scaled by 0."), std::string::npos) << r.err;

  // The same scene blown up to centimetres by --scale 100: `info` says it is not in metres.
  r = cpgi(dir, "info '" + dir / "seed1.glb" + "' --scale 100");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("not in metres"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--scale 0.01"), std::string::npos) << r.err;
  r = cpgi(dir, "info '" + scene + "'");
  EXPECT_EQ(r.err.find("not in metres"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cpgi
