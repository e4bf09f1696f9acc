// End to end: `cpgi bake --method cells` on seed1 writes the global atlas's layout (so compare-light works
// against the reference), its report keeps the energy per cell and portal, and its error against the
// reference stays near the global solve's.
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using CliRun = test::CommandRun;
using test::cpgi;
using test::slurp;

// Cells from another file of the same scene (a copy here, as a decompose output's cells.glb would be) are
// matched to the scene's triangles by centroid and facing side: by centroid alone the two faces of
// openings' zero-thickness B|C partition both went to one room, and through the hole left in the other
// B let 7.8 W of its 28.5 escape and C 1.0 W of 2.6, in closed rooms, without a word.
TEST(CellsBake, CellsFromAnotherFileKeepEachFaceOfAThinWallInItsRoom) {
  test::TempDir dir;
  const std::string scene = dir / "openings.glb", cells = dir / "cells.glb";
  ASSERT_EQ(cpgi(dir, "generate openings -o '" + scene + "'").status, 0);
  std::filesystem::copy_file(scene, cells);
  BakeSettings s = test::cellsBake(scene, cells);
  s.atlas.densityAuto = false;
  s.atlas.params.density = 5;
  Context ctx;
  const nlohmann::json report = test::bakeHere(s, ctx).report;
  for (const std::string& w : ctx.warnings())
    EXPECT_EQ(w.find("not in the cells file"), std::string::npos) << w;
  ASSERT_EQ(report["cell_energy"].size(), 3u);
  for (const auto& c : report["cell_energy"])
    EXPECT_LT(c["escaped_w"].get<double>(), 0.01 * c["absorbed_w"].get<double>()) << c.dump();
}

TEST(CellsBake, Seed1AgainstGlobalAndReference) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const std::string atlas = " --texels-per-quad 8 -q";
  // The bakes in process (their folders for compare-light): --texels-per-quad 8 --unshot 0.01
  // --item-buffer 256, cell by cell and global.
  BakeSettings s = test::cellsBake(scene, scene);
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 8;
  s.solver.params.unshotFraction = 0.01;
  s.solver.params.itemBuffer = 256;
  s.output.folder = dir / "cells";
  test::bakeHere(s);
  s.cells.method = BakeMethod::Global;
  s.output.folder = dir / "global";
  test::bakeHere(s);
  CliRun r = cpgi(dir, "reference '" + scene + "' -o '" + dir / "ref" + "'" + atlas + " --spp 256");
  ASSERT_EQ(r.status, 0) << r.err;

  const nlohmann::json report = nlohmann::json::parse(slurp(dir / "cells/report.json"));
  for (const char* key : {"method", "seconds", "solve_seconds", "texels", "shots", "unshot_fraction", "cells",
                          "portals", "rounds", "cell_energy", "portal_energy", "energy"})
    EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_EQ(report["method"], "cells");
  EXPECT_EQ(report["cells"], 3);
  EXPECT_EQ(report["portals"], 2);
  EXPECT_LE(report["unshot_fraction"].get<double>(), 0.01);
  EXPECT_GE(report["rounds"].get<int>(), 2);  // light must go A → B → back at least once
  const nlohmann::json global = nlohmann::json::parse(slurp(dir / "global/report.json"));
  EXPECT_EQ(report["atlas"], global["atlas"]);
  EXPECT_EQ(report["texels"], global["texels"]);
  double emitted = 0.0;
  for (const auto& c : report["cell_energy"]) {
    const double in = c["emitted_w"].get<double>() + c["received_w"].get<double>();
    const double out = c["absorbed_w"].get<double>() + c["sent_w"].get<double>() +
                       c["unshot_w"].get<double>() + c["escaped_w"].get<double>();
    EXPECT_NEAR(out, in, 1e-3 * in) << c["name"];
    emitted += c["emitted_w"].get<double>();
  }
  EXPECT_NEAR(emitted, 600.0, 0.01);  // two 1 m² lamps of 100 W/m² × 3 channels
  // Room B has no lamp: all its light came through the two doors.
  for (const auto& c : report["cell_energy"]) {
    if (c["name"] == "B") {
      EXPECT_GT(c["received_w"].get<double>(), 0.02 * emitted);
    }
  }

  r = cpgi(dir, "compare-light '" + dir / "cells" + "' '" + dir / "ref" + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const double cellsError = nlohmann::json::parse(r.out)["rel_rmse_nonemissive"].template get<double>();
  r = cpgi(dir, "compare-light '" + dir / "global" + "' '" + dir / "ref" + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const double globalError = nlohmann::json::parse(r.out)["rel_rmse_nonemissive"].template get<double>();
  std::printf("seed1 8x8: relative RMSE (non-emissive) cells %.4f, global %.4f\n", cellsError, globalError);
  EXPECT_LT(cellsError, 0.10);
  EXPECT_LT(cellsError, globalError + 0.03);
}

// --cells auto runs the automatic decomposition: seed1's three rooms and two doors.
TEST(CellsBake, AutomaticCells) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  BakeSettings s = test::cellsBake(scene, "auto");
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 4;
  s.solver.params.unshotFraction = 0.02;
  s.solver.params.itemBuffer = 256;
  const nlohmann::json report = test::bakeHere(s).report;
  EXPECT_EQ(report["method"], "cells");
  EXPECT_EQ(report["cells"], 3);
  EXPECT_EQ(report["portals"], 2);
  EXPECT_LE(report["unshot_fraction"].get<double>(), 0.02);
  const auto& e = report["energy"];
  EXPECT_NEAR(e["absorbed_w"].get<double>() + e["unshot_w"].get<double>() + e["escaped_w"].get<double>(),
              e["emitted_w"].get<double>(), 1e-3 * e["emitted_w"].get<double>());
  for (const auto& p : report["portal_energy"])
    EXPECT_GT(p["a_to_b_w"].get<double>() + p["b_to_a_w"].get<double>(), 1.0);
}

// --cells auto decomposes with the decomposition options (apps/options.h): a voxel size out of range is
// refused by the decomposition, naming the flag.
// --method cells without --cells: the scene's own cells when it has them (seed1's three rooms, as
// generated), else the automatic ones (the same rooms found in the raw model).
TEST(CellsBake, WithoutCellsNamedTheScenesOwnElseAutomatic) {
  test::TempDir dir;
  for (const std::string& raw : {std::string(""), std::string(" --no-cells")}) {
    const std::string scene = dir / ("seed1" + std::string(raw.empty() ? "" : "-raw") + ".glb");
    ASSERT_EQ(cpgi(dir, "generate seed1" + raw + " -o '" + scene + "'").status, 0);
    BakeSettings s = test::quickSeed1();
    s.input.scene = scene;
    s.cells.method = BakeMethod::Cells;
    Context ctx;
    const nlohmann::json report = test::bakeHere(s, ctx).report;
    EXPECT_EQ(report["cells"], 3) << raw;
    EXPECT_EQ(report["portals"], 2) << raw;
    // The automatic decomposition ran for the raw model only.
    bool decomposed = false;
    for (const Context::Timing& t : ctx.timings()) decomposed = decomposed || t.stage == "decompose";
    EXPECT_EQ(decomposed, !raw.empty()) << raw;
  }
}

TEST(CellsBake, DecompositionOptionsReachAutoCells) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const CliRun r = cpgi(dir, "bake '" + scene + "' -o '" + dir / "out" +
                                 "' --method cells --cells auto --texels-per-quad 2 --voxel 20 -q");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err.rfind("cpgi: --voxel: ", 0), 0u) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out/report.json"));
}

TEST(CellsBake, BadCellsOptionsFailWithOneLine) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  for (const std::string& cells : {std::string(" --cells none"), " --cells '" + dir / "missing.glb" + "'"}) {
    const CliRun r = cpgi(
        dir, "bake '" + scene + "' -o '" + dir / "out" + "' --method cells --texels-per-quad 4 -q" + cells);
    EXPECT_EQ(r.status, 1) << cells;
    EXPECT_NE(r.err.find("--cells"), std::string::npos);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  }
}

// The command line's cells bakes default to binned portals (radiosity/bake/bake_settings.h,
// kBakePortalLight), and so do the cell jobs of a plan made with the same options: run one after another by
// `cpgi cell-job`, they give the single-process bake texel for texel.
TEST(CellsBake, DefaultPortalsAreBinnedAlsoAsCellJobs) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const std::string cells = " --method cells --cells '" + scene + "' --texels-per-quad 4 --unshot 0.05 -q";
  const CliRun bake = cpgi(dir, "bake '" + scene + "' -o '" + (dir / "single") + "'" + cells);
  ASSERT_EQ(bake.status, 0) << bake.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "single/report.json"))["portal_mode"], "binned");

  const std::string plan = "'" + (dir / "plan") + "'";
  for (const std::string& step :
       {"bake '" + scene + "' -o '" + (dir / "jobs") + "'" + cells + " --plan " + plan,
        "cell-job " + plan + " --first-shot -q", "cell-job " + plan + " --first-shot-sum -q"}) {
    const CliRun r = cpgi(dir, step);
    ASSERT_EQ(r.status, 0) << step << "\n" << r.err;
  }
  for (int round = 1;; ++round) {
    ASSERT_LE(round, 64);
    const CliRun status = cpgi(dir, "cell-job " + plan + " --status --json");
    ASSERT_EQ(status.status, 0) << status.err;
    if (nlohmann::json::parse(status.out)["next_round"] == 0) break;
    const CliRun r = cpgi(dir, "cell-job " + plan + " --round " + std::to_string(round) + " -q");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const CliRun gather = cpgi(dir, "cell-job " + plan + " --gather -q");
  ASSERT_EQ(gather.status, 0) << gather.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "jobs/report.json"))["portal_mode"], "binned");
  const CliRun same = cpgi(dir, "compare-light '" + (dir / "jobs") + "' '" + (dir / "single") + "' --json");
  ASSERT_EQ(same.status, 0) << same.err;
  EXPECT_EQ(nlohmann::json::parse(same.out)["rel_rmse"].get<double>(), 0.0);
}

}  // namespace
}  // namespace cpgi
