// Progress in a pipe or a log: plain "progress: STAGE NN% ..." lines on stderr, a stage's first once it has
// lasted a second and then one per CPGI_PROGRESS_SECONDS (5 s by default; 0: every report), from bake (global
// and cells, whose lines name the round and its cells, and each cell's solve its cell), reference, decompose
// and view; none with -q.
#include <string>

#include <gtest/gtest.h>

#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using test::quote;

test::CommandRun cpgiEvery(const test::TempDir& dir, const std::string& period, const std::string& args) {
  return test::runCaptured(dir.path(),
                           "CPGI_PROGRESS_SECONDS=" + period + " " + quote(CPGI_BINARY) + " " + args);
}

bool hasLine(const test::CommandRun& r, const std::string& start) {
  for (const std::string& line : r.allErrLines())
    if (line.rfind(start, 0) == 0 && line.find('%') != std::string::npos) return true;
  return false;
}

TEST(ProgressLines, EveryLongCommandReportsItsStagesInAPipe) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb", atlas = " --texels-per-quad 2";
  ASSERT_EQ(test::cpgi(dir.path(), "generate seed1 -o " + quote(scene)).status, 0);

  test::CommandRun r =
      cpgiEvery(dir, "0", "bake " + quote(scene) + " -o " + quote(dir / "global") + atlas + " --unshot 0.2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(hasLine(r, "progress: solve ")) << r.err;
  EXPECT_TRUE(hasLine(r, "progress: views ")) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);  // no terminal tricks in a log

  r = cpgiEvery(dir, "0",
                "bake " + quote(scene) + " -o " + quote(dir / "cells") + atlas +
                    " --unshot 0.2 --method cells --cells " + quote(scene));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(hasLine(r, "progress: cells ")) << r.err;
  // Each round names the cells it solves (seed1's: A, B, C), then says it is done.
  const size_t round = r.err.find("round 1: cell");
  ASSERT_NE(round, std::string::npos) << r.err;
  const std::string named = r.err.substr(round, r.err.find('\n', round) - round);
  EXPECT_TRUE(named.find('A') != std::string::npos || named.find('C') != std::string::npos) << named;
  EXPECT_NE(r.err.find("round 1\n"), std::string::npos) << r.err;
  // Each cell's own solve says which cell and round it is.
  EXPECT_TRUE(hasLine(r, "progress: solve ")) << r.err;
  EXPECT_NE(r.err.find("(1 of "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("), round 1: shots"), std::string::npos) << r.err;

  r = cpgiEvery(dir, "0", "reference " + quote(scene) + " -o " + quote(dir / "ref") + atlas + " --spp 2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(hasLine(r, "progress: reference ")) << r.err;

  r = cpgiEvery(dir, "0", "decompose " + quote(scene) + " -o " + quote(dir / "dec") + " --voxel 0.1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(hasLine(r, "progress: watershed ")) << r.err;

  r = cpgiEvery(dir, "0", "view " + quote(dir / "global"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(hasLine(r, "progress: views ")) << r.err;

  // A long period: a stage shows once, after its first second, and not again while it runs; -q prints none at
  // all.
  r = cpgiEvery(dir, "1000",
                "bake " + quote(scene) + " -o " + quote(dir / "quiet") + atlas + " --unshot 0.2");
  ASSERT_EQ(r.status, 0) << r.err;
  std::string previous;
  for (const std::string& line : r.allErrLines()) {
    if (line.rfind("progress: ", 0) != 0) continue;
    const std::string stage = line.substr(10, line.find(' ', 10) - 10);
    EXPECT_NE(stage, previous) << r.err;
    previous = stage;
  }
  r = cpgiEvery(dir, "0",
                "bake " + quote(scene) + " -o " + quote(dir / "quiet") + atlas + " --unshot 0.2 -q");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

}  // namespace
}  // namespace cpgi
