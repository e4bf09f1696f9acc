// End to end (issue 12 item 6): `bake --time-limit SECONDS` stops the solve at the limit and writes a
// valid result marked partial, with the energy still balanced, for a global and a cells bake; the size
// line comes before the first shot.
#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using nlohmann::json;
using test::cpgi;
using test::slurp;

const char* kAtlas = " --texels-per-quad 8 --item-buffer 128";

void expectBalanced(const json& energy) {
  const double emitted = energy["emitted_w"].get<double>();
  const double out = energy["absorbed_w"].get<double>() + energy["unshot_w"].get<double>() +
                     energy["escaped_w"].get<double>();
  EXPECT_NEAR(out, emitted, 1e-3 * emitted);
  EXPECT_GE(energy["escaped_w"].get<double>(), -1e-3 * emitted);
}

TEST(TimeLimit, TinyLimitWritesAPartialResultForBothMethods) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  // The default --density auto's pilot shot counts against the limit too.
  for (const auto& [method, atlas] :
       {std::pair{"global", kAtlas}, std::pair{"cells", kAtlas}, std::pair{"global", " --item-buffer 128"}}) {
    SCOPED_TRACE(std::string(method) + atlas);
    const std::string out = dir / (std::string(method) + (atlas == kAtlas ? "" : "-auto"));
    const test::CommandRun r = cpgi(dir, "bake '" + scene + "' -o '" + out + "' --method " + method +
                                             " --cells '" + scene + "'" + atlas + " --time-limit 0.5");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("texels in"), std::string::npos) << r.err;  // the size, before the first shot
    EXPECT_NE(r.out.find("partial"), std::string::npos) << r.out;
    for (const char* f : {"lightmap.exr", "baked.glb", "report.json", "report.html"})
      EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / f)) << f;
    const json report = json::parse(slurp(out + "/report.json"));
    EXPECT_EQ(report["partial"], true);
    EXPECT_NE(report["partial_reason"].get<std::string>().find("time limit"), std::string::npos);
    EXPECT_DOUBLE_EQ(report["time_limit_s"].get<double>(), 0.5);
    EXPECT_GT(report["energy"]["unshot_w"].get<double>(), 0.0);  // what the limit left unshot, reported
    expectBalanced(report["energy"]);
    if (std::string(method) == "cells") {
      for (const json& c : report["cell_energy"]) {
        const double in = c["emitted_w"].get<double>() + c["received_w"].get<double>();
        const double outW = c["absorbed_w"].get<double>() + c["sent_w"].get<double>() +
                            c["unshot_w"].get<double>() + c["escaped_w"].get<double>();
        EXPECT_NEAR(outW, in, 1e-3 * in + 1e-9) << c["name"];
      }
    }
  }
}

// A limit under the least the bake writes (its least layout, its lightmap's files and report), or one that
// passes while the scene is read, is refused at once in one line, nothing written: it would end past the
// limit.
TEST(TimeLimit, ALimitUnderTheLeastIsRefusedInOneLine) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  const std::string out = dir / "out";
  const test::CommandRun r =
      cpgi(dir, "bake '" + scene + "' -o '" + out + "'" + kAtlas + " --time-limit 0.000001");
  EXPECT_EQ(r.status, 1);
  // A microsecond passes while the scene is read: the reading stops there (or, read within it, the least
  // the bake writes is more than what is left), one line either way.
  EXPECT_EQ(r.err.rfind("cpgi: --time-limit: ", 0), 0u) << r.err;
  EXPECT_TRUE(r.err.find("was read") != std::string::npos ||
              r.err.find("1e-06 s is less than the least a bake of this scene writes") != std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("raise it"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(out) / "report.json"));
}

TEST(TimeLimit, LimitNotReachedIsNoPartialResult) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  BakeSettings s;  // in process: kAtlas --unshot 0.2 --time-limit 3600
  s.input.scene = scene;
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 8;
  s.solver.params.itemBuffer = 128;
  s.solver.params.unshotFraction = 0.2;
  s.limits.timeLimit = 3600;
  const BakeResult r = test::bakeHere(s);
  EXPECT_FALSE(r.partial);
  const json& report = r.report;
  EXPECT_EQ(report["partial"], false);
  EXPECT_FALSE(report.contains("partial_reason"));
  EXPECT_LE(report["unshot_fraction"].get<double>(), 0.2);
}

TEST(TimeLimit, NegativeOrNotANumberIsRefused) {
  test::TempDir dir;
  const std::string scene = dir / "seed1.glb";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + scene + "'").status, 0);
  for (const char* bad : {"-1", "nan", "abc"}) {
    const test::CommandRun r = cpgi(dir, "bake '" + scene + "' -o '" + dir / "out" + "' --time-limit " + bad);
    EXPECT_EQ(r.status, 1) << bad;
    EXPECT_NE(r.err.find("--time-limit"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out/report.json"));
  }
}

}  // namespace
}  // namespace cpgi
