// End to end: `cpgi bake` on a generated seed scene writes every output with the documented keys, the
// lightmap's area channel adds up to the scene's surface, and bad options fail with one line.
#include <sys/wait.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "core/scene_io.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/bake_settings.h"
#include "scenes/seed_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"

namespace cpgi {
namespace {

using CliRun = test::CommandRun;
using test::cpgi;
using test::slurp;

TEST(Bake, SeedSceneWritesAllOutputs) {
  test::TempDir dir;
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + dir / "seed1.glb" + "'").status, 0);
  const CliRun r = cpgi(dir, "bake '" + dir / "seed1.glb" + "' -o '" + dir / "out" +
                                 "' --texels-per-quad 8 --unshot 0.05 --visibility hemicube");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"lightmap.exr", "lightmap.png", "baked.glb", "report.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;

  const nlohmann::json report = nlohmann::json::parse(slurp(dir / "out/report.json"));
  for (const char* key : {"method", "seconds", "solve_seconds", "texels", "shots", "unshot_fraction", "cells",
                          "portals", "visibility", "item_buffer", "atlas", "renderer", "timings", "energy"})
    EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_EQ(report["method"], "global");
  EXPECT_EQ(report["cells"], 1);
  EXPECT_EQ(report["portals"], 0);
  EXPECT_LE(report["unshot_fraction"].get<double>(), 0.05);
  EXPECT_GT(report["shots"].get<int>(), 2);  // two lamps, then reflectors
  const auto& e = report["energy"];
  EXPECT_NEAR(e["absorbed_w"].get<double>() + e["unshot_w"].get<double>() + e["escaped_w"].get<double>(),
              e["emitted_w"].get<double>(), 1e-3 * e["emitted_w"].get<double>());

  std::vector<ExrChannel> extra;
  const ImageRGB lightmap = readExr(dir / "out/lightmap.exr", &extra);
  EXPECT_EQ(lightmap.width, report["atlas"]["width"].get<int>());
  ASSERT_EQ(extra.size(), 3u);  // area, emissive, cell (compare-light's per-cell figures)
  auto named = [&](const std::string& n) -> const ExrChannel& {
    for (const ExrChannel& c : extra)
      if (c.name == n) return c;
    ADD_FAILURE() << "no channel " << n;
    return extra[0];
  };
  const auto& areas = named("area");
  const auto& emissive = named("emissive");
  const auto& cells = named("cell");
  EXPECT_EQ(areas.name, "area");
  EXPECT_EQ(emissive.name, "emissive");
  EXPECT_EQ(*std::max_element(cells.values.begin(), cells.values.end()), 2.0f);  // seed1's cells A, B, C
  double area = 0.0, lit = 0.0, lampArea = 0.0;
  for (size_t i = 0; i < areas.values.size(); ++i) {
    area += areas.values[i];
    lit += areas.values[i] * lightmap.pixels[i].r;
    lampArea += areas.values[i] * emissive.values[i];
  }
  EXPECT_NEAR(lampArea, 2.0, 1e-3);  // two 1 m × 1 m lamps
  EXPECT_FALSE(report["views"].empty());
  for (const auto& v : report["views"])
    EXPECT_TRUE(std::filesystem::exists(dir / ("out/view-" + v.get<std::string>() + ".png"))) << v;
  double sceneArea = 0.0;
  for (const Triangle& t : makeSeedScene(1).scene.triangles) sceneArea += t.area();
  EXPECT_NEAR(area, sceneArea, 1e-3 * sceneArea);
  EXPECT_GT(lit, 0.0);
}

TEST(Bake, PreviewGlbKeepsTheCellsAndPortals) {
  test::TempDir dir;
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + dir / "seed1.glb" + "'").status, 0);
  BakeSettings s;  // in process: --texels-per-quad 2 --unshot 0.2
  s.input.scene = dir / "seed1.glb";
  s.output.folder = dir / "out";
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 2;
  s.solver.params.unshotFraction = 0.2;
  test::bakeHere(s);
  const LoadedScene preview = loadScene(dir / "out/preview.glb", LoadOptions{});
  EXPECT_EQ(preview.cells.cells.size(), 3u);
  EXPECT_EQ(preview.cells.portals.size(), 2u);
  // The engine's glb keeps the rooms as node names, without the portals' helper quads.
  const LoadedScene engine = loadScene(dir / "out/baked.glb", LoadOptions{});
  EXPECT_EQ(engine.cells.cells.size(), 3u);
  EXPECT_EQ(engine.cells.portals.size(), 0u);
}

TEST(Bake, BadOptionsFailWithOneLine) {
  test::TempDir dir;
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + dir / "s.glb" + "'").status, 0);
  // Checked by the solver: exactly one line naming the option.
  const CliRun bad = cpgi(dir, "bake '" + dir / "s.glb" + "' -o '" + dir / "out" + "' --item-buffer 7");
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(bad.err.rfind("cpgi: --item-buffer: ", 0), 0u) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out/report.json"));
  // Checked by the parser (CLI11 adds its "Run with --help" line): the first line names the option.
  for (const std::string& args :
       {std::string("--visibility cube"), std::string("--texels-per-quad 8 --density 4"),
        std::string("--unshot 2"), std::string("--regions 0"), std::string("--regions 5"),
        std::string("--lamp-rays 6"), std::string("--lamp-rays -4")}) {
    const CliRun r = cpgi(dir, "bake '" + dir / "s.glb" + "' -o '" + dir / "out" + "' " + args);
    EXPECT_EQ(r.status, 1) << args;
    const std::string option = args.substr(0, args.find(' '));
    EXPECT_NE(r.err.substr(0, r.err.find('\n')).find(option), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out/report.json")) << args;
  }
  const CliRun missing = cpgi(dir, "bake '" + dir / "none.glb" + "' -o '" + dir / "out" + "'");
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("none.glb"), std::string::npos) << missing.err;
}

// A library caller who fills nothing gets the command line's bake: the settings `cpgi bake` keeps in a
// cell-job plan, given no option but the method, are BakeSettings' defaults.
TEST(Bake, CommandLineDefaultsAreTheLibrarys) {
  test::TempDir dir;
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + dir / "s.glb" + "'").status, 0);
  const CliRun r =
      cpgi(dir, "bake '" + dir / "s.glb" + "' -o '" + dir / "out" + "' --method cells --cells '" +
                    dir / "s.glb" + "' --plan '" + dir / "plan" + "' -q");
  ASSERT_EQ(r.status, 0) << r.err;
  BakeSettings expected;
  expected.input.scene = dir / "s.glb";
  expected.output.folder = dir / "out";
  expected.cells.method = BakeMethod::Cells;
  expected.cells.source = dir / "s.glb";
  const nlohmann::json plan = nlohmann::json::parse(slurp(dir / "plan/plan.json"));
  EXPECT_EQ(plan["bake_settings"], bakeSettingsJson(expected));
}

// bake() in process writes the command line's files: the same lightmap, byte for byte.
TEST(Bake, InProcessBakeWritesTheCommandLinesLightmap) {
  test::TempDir dir;
  ASSERT_EQ(cpgi(dir, "generate seed1 -o '" + dir / "s.glb" + "'").status, 0);
  const CliRun r =
      cpgi(dir, "bake '" + dir / "s.glb" + "' -o '" + dir / "cli" +
                    "' --texels-per-quad 4 --unshot 0.05 --item-buffer 128 --view-size 64x48 -q");
  ASSERT_EQ(r.status, 0) << r.err;
  BakeSettings s;
  s.input.scene = dir / "s.glb";
  s.output.folder = dir / "lib";
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 4;
  s.solver.params.unshotFraction = 0.05;
  s.solver.params.itemBuffer = 128;
  s.output.views.width = 64;
  s.output.views.height = 48;
  const BakeResult b = test::bakeHere(s);
  EXPECT_EQ(slurp(dir / "lib/lightmap.exr"), slurp(dir / "cli/lightmap.exr"));
  EXPECT_EQ(b.report["shots"], nlohmann::json::parse(slurp(dir / "cli/report.json"))["shots"]);
}

}  // namespace
}  // namespace cpgi
