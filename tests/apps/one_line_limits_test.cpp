// End to end (issue 15, defect 8): extreme values give one clear line. A voxel far too small says how
// many voxels it asks for and what would fit (it said "0 voxels"); a node name holding newlines stays on
// the warning's one line.
#include <filesystem>

#include <gtest/gtest.h>

#include "tests/support/glb_builder.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

TEST(OneLineLimits, TinyVoxelSaysWhatWouldFit) {
  test::TempDir dir;
  test::cpgiOrThrow(dir, "generate seed1 -o " + test::quote(dir / "seed1.glb"));
  const test::CommandRun r = test::cpgi(dir, "decompose " + test::quote(dir / "seed1.glb") + " -o " +
                                                 test::quote(dir / "out") + " --voxel 1e-6");
  EXPECT_EQ(r.status, 1);
  // (seed1's own cells are mentioned first: decompose ignores them)
  ASSERT_FALSE(r.errLines().empty());
  const std::string line = r.errLines().back();
  EXPECT_EQ(line.rfind("cpgi: --voxel: 1e-06 m gives ", 0), 0u) << line;
  EXPECT_NE(line.find("e+"), std::string::npos) << "a count in the 10^20s, not 0: " << line;
  EXPECT_NE(line.find("voxels, more than the limit of"), std::string::npos) << line;
  EXPECT_NE(line.find("need a voxel of at least about 0.0"), std::string::npos) << line;
}

// Memory estimated before the large allocations (issue 15, item 3): an atlas or item buffers beyond
// --max-memory are refused up front, naming the option to lower and the limit, and nothing is written.
TEST(OneLineLimits, RunsBeyondMaxMemoryAreRefusedUpFront) {
  test::TempDir dir;
  const std::string scene = test::quote(dir / "seed1.glb");
  test::cpgiOrThrow(dir, "generate seed1 -o " + scene);
  auto refused = [&](const std::string& flags, const std::string& start, const std::string& limit) {
    const test::CommandRun r =
        test::cpgi(dir, "bake " + scene + " -q -o " + test::quote(dir / "out") + flags);
    EXPECT_EQ(r.status, 1) << flags;
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    const std::string line = r.errLines()[0];
    EXPECT_EQ(line.rfind("cpgi: " + start, 0), 0u) << line;
    EXPECT_NE(line.find("more than --max-memory " + limit), std::string::npos) << line;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "lightmap.exr"));
  };
  refused(" --texels-per-quad 128 --max-memory 100M", "--texels-per-quad: the lightmap atlas of ",
          "100 MiB; lower the resolution or raise --max-memory");
  // 16384² pixels × 16 regions: about 48 GiB, beyond the default share of a test machine.
  refused(" --texels-per-quad 2 --item-buffer 16384 --regions 4", "--item-buffer: the solve (", "");
  const test::CommandRun bad = test::cpgi(dir, "bake " + scene + " -o x --max-memory lots");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.err.find("--max-memory: must be a size such as 8G or 512M, got lots"), std::string::npos)
      << bad.err;
}

// The decomposition's grids too (issue 15, item 3): seed1 at 2 cm is about 2e7 voxels, some 800 MB by
// decompositionBytes, refused before any grid is allocated by decompose, by a bake that decomposes (one
// --max-memory for the whole bake) and by compare-cells.
TEST(OneLineLimits, DecompositionBeyondMaxMemoryIsRefusedUpFront) {
  test::TempDir dir;
  const std::string scene = test::quote(dir / "seed1.glb");
  test::cpgiOrThrow(dir, "generate seed1 --no-cells -o " + scene);
  const std::string out = test::quote(dir / "out"), flags = " --voxel 0.02 --max-memory 200M";
  for (const std::string& command :
       {"decompose " + scene + " -o " + out + flags,
        "bake " + scene + " -q -o " + out + " --method cells --cells auto" + flags,
        "compare-cells " + scene + " auto auto --bake" + flags}) {
    SCOPED_TRACE(command);
    const test::CommandRun r = test::cpgi(dir, command);
    EXPECT_EQ(r.status, 1);
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    const std::string line = r.errLines()[0];
    EXPECT_EQ(line.rfind("cpgi: --voxel: the decomposition's grid of ", 0), 0u) << line;
    EXPECT_NE(line.find(" voxels of 0.02 m needs about "), std::string::npos) << line;
    EXPECT_NE(line.find("more than --max-memory 200 MiB; give a larger --voxel or raise --max-memory"),
              std::string::npos)
        << line;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "cells.json"));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "lightmap.exr"));
  }
}

TEST(OneLineLimits, NodeNameWithNewlinesStaysOnTheWarningsLine) {
  test::TempDir dir;
  test::GlbBuilder g;
  const int m = g.addMaterial({{"name", "m"}, {"emissiveFactor", {1, 1, 1}}});
  // One good triangle and one of zero area, which is dropped with a warning naming its node.
  g.addNode(
      {{"name", "evil\nname\rwith\tcontrols"},
       {"mesh", g.addMesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0}, {0, 1, 2, 3, 4, 5}, m)}});
  g.writeGlb(dir / "evil.glb");
  const test::CommandRun r = test::cpgi(dir, "info " + test::quote(dir / "evil.glb"));
  EXPECT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(r.errLines().size(), 1u) << r.err;
  EXPECT_NE(r.errLines()[0].find("evil\\nname\\rwith\\tcontrols"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cpgi
