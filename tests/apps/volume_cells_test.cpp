// End to end (issue 12 item 3): a building whose rooms are given only as cellvolume: meshes bakes cell by
// cell from its own file, and compare-cells scores it over the whole interior; an empty comparison
// prints no perfect figure.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using nlohmann::json;
using test::cpgi;
using test::slurp;

TEST(VolumeCellsCommand, RoomsGivenAsVolumesBakeCellByCell) {
  test::TempDir dir;
  const std::string scene = dir / "house.glb";
  test::CommandRun r = cpgi(dir, "generate house-open --volumes-only -o '" + scene + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("4 cells, 0 portals"), std::string::npos) << r.out;
  r = cpgi(dir, "info '" + scene + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  // In process: --method cells --cells SCENE --voxel 0.1 --density 2 --unshot 0.05 --item-buffer 128.
  BakeSettings s = test::cellsBake(scene, scene);
  s.cells.decompose.voxelSize = 0.1;
  s.atlas.densityAuto = false;
  s.atlas.params.density = 2;
  s.solver.params.unshotFraction = 0.05;
  s.solver.params.itemBuffer = 128;
  Context ctx;
  const json report = test::bakeHere(s, ctx).report;
  for (const std::string& w : ctx.warnings()) EXPECT_EQ(w.find("in no cell"), std::string::npos) << w;
  EXPECT_EQ(report["cells"], 5);    // hall, living room, kitchen, bedroom + outside
  EXPECT_EQ(report["portals"], 9);  // 3 interior doors, 2 exterior doors, 4 windows
  for (const json& c : report["cell_energy"]) {
    EXPECT_GE(c["escaped_w"].get<double>(), -1e-3 * c["emitted_w"].get<double>() - 1e-6) << c["name"];
    if (c["name"] != "outside") {
      EXPECT_GT(c["absorbed_w"].get<double>(), 0.0) << c["name"];  // every room lit, none black
    }
  }
}

TEST(VolumeCellsCommand, DecomposeFromVolumesWritesTheRoomsCells) {
  test::TempDir dir;
  const std::string scene = dir / "spiral.glb";
  ASSERT_EQ(cpgi(dir, "generate house-spiral --volumes-only -o '" + scene + "'").status, 0);
  test::CommandRun r =
      cpgi(dir, "decompose '" + scene + "' -o '" + dir / "cells" + "' --from-volumes --voxel 0.1");
  ASSERT_EQ(r.status, 0) << r.err;
  const json report = json::parse(slurp(dir / "cells/cells.json"));
  EXPECT_EQ(report["outside_cell"], "outside");
  EXPECT_EQ(report["checks"]["leaking_faces"], 0);
  EXPECT_EQ(report["checks"]["connected"], true);
  std::vector<std::string> names;
  for (const json& c : report["cells"]) names.push_back(c["name"]);
  EXPECT_NE(std::find(names.begin(), names.end(), "landing"), names.end());
  // The cells.glb it wrote is an ordinary cells file: bake and compare-cells read it.
  r = cpgi(dir, "compare-cells '" + scene + "' '" + dir / "cells" + "' '" + scene + "' --voxel 0.1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GE(json::parse(r.out)["adjusted_rand_index"].get<double>(), 0.9);

  const std::string plain = dir / "plain.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + plain + "'").status, 0);
  r = cpgi(dir, "decompose '" + plain + "' -o '" + dir / "no" + "' --from-volumes");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_NE(r.err.find("--from-volumes needs rooms given as cellvolume: meshes alone"), std::string::npos)
      << r.err;
}

TEST(VolumeCellsCommand, CompareCellsScoresTheWholeInterior) {
  test::TempDir dir;
  const std::string scene = dir / "house.glb";
  ASSERT_EQ(cpgi(dir, "generate house-open --volumes-only -o '" + scene + "'").status, 0);
  const test::CommandRun r =
      cpgi(dir, "compare-cells '" + scene + "' auto '" + scene + "' --voxel 0.1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_GE(j["adjusted_rand_index"].get<double>(), 0.85);
  EXPECT_GE(j["coverage_b"].get<double>(), 0.9);
  EXPECT_GE(j["coverage_a"].get<double>(), 0.9);
  EXPECT_GT(j["interior_voxels"].get<size_t>(), 40000u);  // ~65 m³ of rooms at 0.1 m
  // B gives its rooms as volumes alone: its portals are those fitted where the volumes meet
  // (decompose --from-volumes), matched to A's within a voxel.
  EXPECT_EQ(j["portals_b_from"], "volumes");
  EXPECT_EQ(j["portals_a_from"], "cells");
  ASSERT_TRUE(j["portal_centre_error_m"].is_number()) << j["warnings"];
  EXPECT_LE(j["portal_centre_error_m"].get<double>(), 0.1);
  EXPECT_EQ(j["warnings"].dump().find("no portals"), std::string::npos) << j["warnings"];
}

TEST(VolumeCellsCommand, EmptyComparisonPrintsNoPerfectFigure) {
  // Both decompositions are one room volume far from the geometry: no voxel of the scene is in a room.
  test::TempDir dir;
  std::ofstream(dir / "room.obj") << "v 0 0 0\nv 4 0 0\nv 4 0 4\nv 0 0 4\nf 1 3 2\nf 1 4 3\n"
                                  << "g cellvolume:far\n"
                                  << "v 100 0 0\nv 101 0 0\nv 101 1 0\nv 100 1 0\n"
                                  << "v 100 0 1\nv 101 0 1\nv 101 1 1\nv 100 1 1\n"
                                  << "f 5 8 7\nf 5 7 6\nf 9 10 11\nf 9 11 12\nf 5 6 10\nf 5 10 9\n"
                                  << "f 8 12 11\nf 8 11 7\nf 5 9 12\nf 5 12 8\nf 6 7 11\nf 6 11 10\n";
  const std::string scene = dir / "room.obj";
  test::CommandRun r =
      cpgi(dir, "compare-cells '" + scene + "' '" + scene + "' '" + scene + "' --voxel 0.1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["adjusted_rand_index"].is_null());
  EXPECT_TRUE(j["portal_centre_error_m"].is_null());
  EXPECT_EQ(j["labelled_in_both"], 0);
  EXPECT_NE(j["warnings"].dump().find("nothing to score"), std::string::npos) << j["warnings"];
  r = cpgi(dir, "compare-cells '" + scene + "' '" + scene + "' '" + scene + "' --voxel 0.1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("1.0000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("n/a"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("nothing to score"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cpgi
