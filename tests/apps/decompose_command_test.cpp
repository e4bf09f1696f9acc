// End to end: `cpgi decompose` on a generated seed scene writes cells.glb / cells.json /
// decomposition.png that `cpgi info` and `cpgi compare-cells` read back; bad input exits 1 with one line.
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using nlohmann::json;

using CommandResult = test::CommandRun;
using test::cpgi;
using test::slurp;

size_t lineCount(const std::string& s) {
  size_t n = 0;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

TEST(DecomposeCommand, SeedSceneRoundTripsThroughInfoAndCompareCells) {
  test::TempDir dir;
  const std::string scene = dir / "seed2.glb", out = dir / "cells";
  ASSERT_EQ(cpgi(dir, "generate seed2 -o '" + scene + "'").status, 0);
  const CommandResult run = cpgi(dir, "decompose '" + scene + "' -o '" + out + "' --voxel 0.05");
  ASSERT_EQ(run.status, 0) << run.err;
  for (const char* f : {"cells.glb", "cells.json", "decomposition.png"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / f)) << f;

  const json report = json::parse(slurp(out + "/cells.json"));
  EXPECT_EQ(report["counts"]["cells"], 3);
  EXPECT_EQ(report["counts"]["portals"], 2);
  EXPECT_EQ(report["checks"]["leaking_faces"], 0);
  EXPECT_DOUBLE_EQ(report["parameters"]["voxel_m"].get<double>(), 0.05);
  for (const json& p : report["portals"]) EXPECT_NEAR(p["area_m2"].get<double>(), 2.1, 0.2);
  double volume = 0.0;
  for (const json& c : report["cells"]) volume += c["volume_m3"].get<double>();
  // Empty voxels are those whose centres lie over half a voxel from every surface: three rooms of
  // 3.95 × 3.95 × 2.95 m (46.03 m³), each less a cube of 1.05³ and a panel of 2.05 × 1.55 × 0.1 m,
  // plus the two doorways (1 × 2.1 × 0.2 m): 134.5 m³.
  EXPECT_NEAR(volume, 134.5, 1.0);
  EXPECT_GT(report["timings_s"]["total"].get<double>(), 0.0);

  const CommandResult info = cpgi(dir, "info '" + out + "/cells.glb' --json");
  ASSERT_EQ(info.status, 0) << info.err;
  const json described = json::parse(info.out);
  EXPECT_EQ(described["cells"].size(), 3u);
  EXPECT_EQ(described["portals"].size(), 2u);

  const CommandResult cmp =
      cpgi(dir, "compare-cells '" + scene + "' '" + out + "' '" + scene + "' --json --voxel 0.05");
  ASSERT_EQ(cmp.status, 0) << cmp.err;
  const json m = json::parse(cmp.out);
  EXPECT_GE(m["adjusted_rand_index"].get<double>(), 0.95);
  EXPECT_GE(m["matched_iou"].get<double>(), 0.95);
  EXPECT_LT(m["portal_centre_error_m"].get<double>(), 0.05);
  EXPECT_EQ(m["portal_matches"].size(), 2u);

  const CommandResult autoCmp =
      cpgi(dir, "compare-cells '" + scene + "' auto '" + scene + "' --json --voxel 0.05");
  ASSERT_EQ(autoCmp.status, 0) << autoCmp.err;
  EXPECT_GE(json::parse(autoCmp.out)["adjusted_rand_index"].get<double>(), 0.95);
}

TEST(DecomposeCommand, OpenHouseHasAnOutsideCellAndEveryRoom) {
  // A generated house whose front door, terrace door and windows stand open (issue 12): the rooms are
  // cells, the outside is one more, flagged exterior, joined to them by a portal per opening.
  test::TempDir dir;
  const std::string scene = dir / "house.glb", out = dir / "cells";
  ASSERT_EQ(cpgi(dir, "generate house-open -o '" + scene + "'").status, 0);
  const CommandResult run = cpgi(dir, "decompose '" + scene + "' -o '" + out + "' --voxel 0.1");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("not covered by a portal: 0"), std::string::npos) << run.out;
  const json report = json::parse(slurp(out + "/cells.json"));
  EXPECT_EQ(report["enclosed"], true);
  EXPECT_EQ(report["outside_cell"], "outside");
  EXPECT_EQ(report["counts"]["cells"], 5);    // hall, living room, kitchen, bedroom + outside
  EXPECT_EQ(report["counts"]["portals"], 9);  // 3 interior doors, 2 exterior doors, 4 windows
  EXPECT_EQ(report["checks"]["leaking_faces"], 0);
  EXPECT_EQ(report["checks"]["connected"], true);
  int exterior = 0;
  for (const json& c : report["cells"]) exterior += c["exterior"].get<bool>();
  EXPECT_EQ(exterior, 1);
  // Scored against the house's own rooms (its cellvolume: boxes).
  const CommandResult cmp =
      cpgi(dir, "compare-cells '" + scene + "' '" + out + "' '" + scene + "' --json --voxel 0.1");
  ASSERT_EQ(cmp.status, 0) << cmp.err;
  EXPECT_GE(json::parse(cmp.out)["adjusted_rand_index"].get<double>(), 0.9);
}

TEST(DecomposeCommand, OpenSceneIsOneCellWithAMessage) {
  test::TempDir dir;
  std::ofstream(dir / "ground.obj") << "v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 3 2\nf 1 4 3\n"
                                    << "v -1 0 -1\nv 1 0 -1\nv 1 2 -1\nv -1 2 -1\nf 5 6 7\nf 5 7 8\n";
  const CommandResult r =
      cpgi(dir, "decompose '" + (dir / "ground.obj") + "' -o '" + (dir / "out") + "' --voxel 0.1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("no enclosed empty space"), std::string::npos) << r.err;
  const json report = json::parse(slurp(dir / "out/cells.json"));
  EXPECT_EQ(report["counts"]["cells"], 1);
  EXPECT_EQ(report["enclosed"], false);
}

TEST(DecomposeCommand, BadInputExitsOneWithOneLine) {
  test::TempDir dir;
  std::ofstream(dir / "empty.obj") << "# nothing\n";
  for (const std::string& file : {dir / "empty.obj", dir / "missing.glb"}) {
    const CommandResult r = cpgi(dir, "decompose '" + file + "' -o '" + (dir / "out") + "'");
    EXPECT_EQ(r.status, 1) << file;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out/cells.json"));
  }
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const CommandResult badVoxel =
      cpgi(dir, "decompose '" + (dir / "tri.obj") + "' -o '" + (dir / "out") + "' --voxel -1");
  EXPECT_EQ(badVoxel.status, 1);
  EXPECT_EQ(lineCount(badVoxel.err), 1u) << badVoxel.err;
  EXPECT_NE(badVoxel.err.find("--voxel"), std::string::npos) << badVoxel.err;
  const CommandResult noCells =
      cpgi(dir, "compare-cells '" + (dir / "tri.obj") + "' auto '" + (dir / "tri.obj") + "'");
  EXPECT_EQ(noCells.status, 1);
  EXPECT_NE(noCells.err.find("no cell"), std::string::npos) << noCells.err;
}

}  // namespace
}  // namespace cpgi
