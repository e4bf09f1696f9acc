// End to end: `cpgi compare-cells SCENE A B --bake` bakes SCENE with each decomposition's cells and measures
// both against one path-traced reference; its figures are those of `cpgi bake --method cells`,
// `cpgi reference` and `cpgi compare-light` run one by one. Bad options exit 1 with one line.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using test::cpgi;

// A coarse atlas and a noisy reference keep it to seconds; the figures stay comparable since every bake is
// measured against the same reference.
const std::string kBakeOptions = " --texels-per-quad 4 --spp 32 --item-buffer 256 --unshot 0.02";

TEST(CompareCellsBake, AutomaticAgainstManualCellsOfSeed1) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  test::CommandRun r =
      cpgi(dir, "compare-cells '" + scene + "' auto '" + scene + "' --voxel 0.1 --bake --json" + kBakeOptions);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_GE(j["adjusted_rand_index"].get<double>(), 0.95);
  ASSERT_TRUE(j.contains("bake"));
  const nlohmann::json& bake = j["bake"];
  for (const char* key : {"texels_per_quad", "unshot_target", "same_atlas", "references", "a", "b",
                          "difference_points"})
    EXPECT_TRUE(bake.contains(key)) << key;
  EXPECT_EQ(bake["texels_per_quad"], 4);
  ASSERT_EQ(bake["references"].size(), bake["same_atlas"].get<bool>() ? 1u : 2u);
  for (const auto& ref : bake["references"]) {
    EXPECT_EQ(ref["spp"], 32);
    EXPECT_GT(ref["noise"].get<double>(), 0.0);
    // The lamps are bright and noiseless (their B is mostly E): without them the relative noise is larger.
    EXPECT_GT(ref["noise_nonemissive"].get<double>(), ref["noise"].get<double>());
  }

  for (const char* side : {"a", "b"}) {
    const nlohmann::json& s = bake[side];
    SCOPED_TRACE(side);
    for (const char* key : {"seconds", "solve_seconds", "shots", "rounds", "unshot_fraction", "rel_rmse",
                            "rel_rmse_nonemissive", "rel_mean_error", "rel_mean_error_nonemissive",
                            "reference_noise", "reference_noise_nonemissive"})
      EXPECT_TRUE(s.contains(key)) << key;
    EXPECT_EQ(s["cells"], 3);
    EXPECT_EQ(s["portals"], 2);
    EXPECT_GT(s["seconds"].get<double>(), 0.0);
    EXPECT_GT(s["shots"].get<int>(), 0);
    EXPECT_GE(s["rounds"].get<int>(), 2);  // room B has no lamp: its light needs a sync
    // Per cell, as compare-light gives them (issue 11): every room compared, the worst named. At 4²/quad
    // and 32 spp the room lit through doors reads within 10 % (measured 0.99–1.01).
    ASSERT_TRUE(s["cells_error"].is_array());
    EXPECT_EQ(s["cells_error"].size(), 3u);
    for (const auto& c : s["cells_error"]) {
      EXPECT_GT(c["texels"].get<size_t>(), 0u) << c.dump();
      EXPECT_NEAR(c["ratio_of_means"].get<double>(), 1.0, 0.1 + 2.0 * c["ratio_error"].get<double>()) << c.dump();
    }
    EXPECT_TRUE(s["worst_cell"].is_string());
    EXPECT_LE(s["unshot_fraction"].get<double>(), 0.02);
    // Against a noisy reference the error cannot fall much below the reference's own noise, and a cell bake
    // of seed1 is within a few points of it (bench/RESULTS.md: 5.7 % at 8² against 2 % noise).
    const double error = s["rel_rmse_nonemissive"].get<double>();
    EXPECT_GT(error, 0.5 * s["reference_noise_nonemissive"].get<double>());
    EXPECT_LT(error, s["reference_noise_nonemissive"].get<double>() + 0.10);
    EXPECT_LT(s["rel_rmse"].get<double>(), 0.05);
  }
  // The automatic cells of seed1 are the hand-made rooms: bakes with either agree within about the target
  // of issue 4 (one point of relative RMSE). At 4² texels a quad and 32 paths a texel both sit on a 7 %
  // noise floor, and how the lamps' beam edges fall on 1 m texels moves the room lit through doors by
  // ±5 %: measured 0.93 points apart before the lamps' edge texels were resampled, 1.02 after.
  const double a = bake["a"]["rel_rmse_nonemissive"].get<double>(), b = bake["b"]["rel_rmse_nonemissive"].get<double>();
  EXPECT_NEAR(bake["difference_points"]["rel_rmse_nonemissive"].get<double>(), 100.0 * (a - b), 1e-9);
  EXPECT_LT(std::abs(a - b), 0.015) << "automatic " << a << ", manual " << b;
  EXPECT_LT(std::abs(bake["difference_points"]["rel_rmse"].get<double>()), 1.0);

  // The same figure for B, step by step with the commands it stands for.
  const std::string atlas = " --texels-per-quad 4";
  r = cpgi(dir, "bake '" + scene + "' -o '" + dir / "cells" + "' --method cells --cells '" + scene + "'" + atlas +
                    " --item-buffer 256 --unshot 0.02 -q");
  ASSERT_EQ(r.status, 0) << r.err;
  // compare-cells --bake traces --spp paths on every texel: no extra paths for noisy cells.
  r = cpgi(dir, "reference '" + scene + "' -o '" + dir / "ref" + "'" + atlas + " --spp 32 --cell-noise 0 -q");
  ASSERT_EQ(r.status, 0) << r.err;
  r = cpgi(dir, "compare-light '" + dir / "cells" + "' '" + dir / "ref" + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json light = nlohmann::json::parse(r.out);
  EXPECT_NEAR(light["rel_rmse"].get<double>(), bake["b"]["rel_rmse"].get<double>(), 1e-4);
  EXPECT_NEAR(light["rel_rmse_nonemissive"].get<double>(), b, 1e-4);
  EXPECT_NEAR(light["reference_noise_nonemissive"].get<double>(),
              bake["b"]["reference_noise_nonemissive"].get<double>(), 1e-6);
}

TEST(CompareCellsBake, TextReport) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const test::CommandRun r = cpgi(dir, "compare-cells '" + scene + "' '" + scene + "' '" + scene +
                                           "' --voxel 0.1 --bake --texels-per-quad 2 --spp 4 --item-buffer 128");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* line : {"adjusted Rand index", "reference on", "rel RMSE", "per cell (without lamps)", "A - B: +0.000 points"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
}

TEST(CompareCellsBake, BadOptionsFailWithOneLine) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const std::string base = "compare-cells '" + scene + "' auto '" + scene + "' --voxel 0.1";
  for (const std::string& bad :
       {std::string(" --bake --spp 1"), std::string(" --spp 16"), std::string(" --bake --texels-per-quad 0"),
        std::string(" --bake --density -2"), std::string(" --bake --unshot 1.5"),
        std::string(" --bake --texels-per-quad 4 --density 8"), std::string(" --texels-per-quad 4")}) {
    const test::CommandRun r = cpgi(dir, base + bad);
    EXPECT_EQ(r.status, 1) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << bad;
  }
}

// No exit 0 with a non-finite figure (issue 15, as bake and reference): a lamp of 5e-19 m² (a legal 5e19
// W) that no reference path finds leaves the reference dark where the bake is lit, so the relative error
// without lamps is inf. It printed null and exited 0; now one line names the figure and nothing is printed.
TEST(CompareCellsBake, NonFiniteFigureFailsWithOneLine) {
  test::TempDir dir;
  std::ofstream(dir / "tiny.mtl")
      << "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 1e38 1e38 1e38\n";
  // A closed box facing in, the speck of a lamp at its centre facing down.
  std::ofstream(dir / "tiny.obj")
      << "mtllib tiny.mtl\n"
         "v -2 -1.5 -2\nv 2 -1.5 -2\nv 2 -1.5 2\nv -2 -1.5 2\n"
         "v -2 1.5 -2\nv 2 1.5 -2\nv 2 1.5 2\nv -2 1.5 2\n"
         "v 0 0 0\nv 1e-9 0 0\nv 0 0 1e-9\n"
         "usemtl wall\nf 4 3 2 1\nf 6 7 8 5\nf 2 6 5 1\nf 3 7 6 2\nf 4 8 7 3\nf 1 5 8 4\n"
         "usemtl lamp\nf 9 10 11\n";
  const test::CommandRun r =
      cpgi(dir, "compare-cells '" + (dir / "tiny.obj") +
                    "' auto auto --bake --json --texels-per-quad 4 --spp 16 --item-buffer 128");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(r.out.empty()) << r.out;
  ASSERT_FALSE(r.errLines().empty());
  const std::string line = r.errLines().back();
  EXPECT_EQ(line.rfind("cpgi: " + (dir / "tiny.obj") + ": the bake's figure a.", 0), 0u) << r.err;
  EXPECT_NE(line.find(" is inf, not a measurement"), std::string::npos) << line;
}

}  // namespace
}  // namespace cpgi
