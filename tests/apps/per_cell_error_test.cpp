// End to end (issue 11): bake and reference mark every texel with its cell, and compare-light reports each
// cell's ratio of means, relative RMSE and reference noise against that cell's own reference, and the worst
// cell. On the openings scene (room C two openings from the lamp), the far rooms' ratios are pinned for
// the global solve (the 3×3 item-buffer test and the fixed eyes made B +15 % and C +17 % converged) and
// cell by cell with both portal models (bench/RESULTS.md).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/suite_setup.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using test::cpgi;

using Options = std::function<void(BakeSettings&)>;
const Options kDefault = [](BakeSettings&) {};
const Options kConverged = [](BakeSettings& s) { s.solver.params.unshotFraction = 1e-4; };  // --unshot 1e-4
const Options kUnshotStopOnly = [](BakeSettings& s) { s.solver.ambientShare = 0.0; };  // --ambient-share 0
Options cellsWith(const Options& more) {  // --method cells --cells SCENE
  return [more](BakeSettings& s) {
    s.cells.method = BakeMethod::Cells;
    s.cells.source = s.input.scene;
    more(s);
  };
}
Options portals(PortalLight p) {  // --portals P
  return [p](BakeSettings& s) { s.cells.params.portals = p; };
}
Options twoLevels(const Options& more) {  // --solve-density 2.5
  return [more](BakeSettings& s) {
    s.solver.solveDensity = 2.5f;
    more(s);
  };
}

// The openings scene, its sampled reference, and the bakes `bakes` (folder name, options) against it, in
// process at --density 5 (their folders for compare-light). Each fixture bakes only what its tests compare.
// The scene and the reference are made once per process and kept for the fixtures after, which bake into
// folders of their own: CTest runs the four suites in one process (OpeningsBakes.SharedBakes,
// tests/CMakeLists.txt), one reference and each bake once.
class OpeningsBakes : public ::testing::Test {
 public:
  void SetUp() override { setup_.require(); }
  static inline test::SuiteSetup setup_;
  static void bakeAll(const std::vector<std::pair<std::string, Options>>& bakes) {
    if (!dir_) dir_ = std::make_unique<test::TempDir>();
    auto run = [](const std::string& args) { test::cpgiOrThrow(*dir_, args); };
    const std::string scene = test::quote(*dir_ / "openings.glb");
    if (!std::filesystem::exists(*dir_ / "ref/report.json")) {
      run("generate openings -o " + scene);
      run("reference " + scene + " -o " + test::quote(*dir_ / "ref") +
          " --density 5 --spp 1024 --texels 1500 -q");
    }
    for (const auto& [name, options] : bakes) {
      BakeSettings s;
      s.input.scene = *dir_ / "openings.glb";
      s.output.folder = *dir_ / name;
      s.output.views.width = 64;  // the lightmaps are compared, not the pictures
      s.atlas.densityAuto = false;
      s.atlas.params.density = 5;
      options(s);
      test::bakeHere(s);
    }
  }
  static nlohmann::json compare(const std::string& a) {
    const test::CommandRun r =
        cpgi(*dir_, "compare-light " + test::quote(*dir_ / a) + " " + test::quote(*dir_ / "ref") + " --json");
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out);
  }
  static std::unique_ptr<test::TempDir> dir_;
};
std::unique_ptr<test::TempDir> OpeningsBakes::dir_;

class PerCellError : public OpeningsBakes {
 protected:
  static void SetUpTestSuite() {
    setup_.run([] {
      bakeAll({{"converged", kConverged}, {"default", kDefault}, {"unshot-stop-only", kUnshotStopOnly}});
    });
  }
};

class PerCellPortals : public OpeningsBakes {
 protected:
  static void SetUpTestSuite() {
    setup_.run([] {
      bakeAll({{"cells-diffuse", cellsWith(portals(PortalLight::Diffuse))},
               {"cells-directional", cellsWith(portals(PortalLight::Directional))},
               {"cells-binned-converged", cellsWith(kConverged)}});
    });
  }
};

class PerCellTwoLevels : public OpeningsBakes {
 protected:
  static void SetUpTestSuite() {
    setup_.run([] {
      bakeAll(
          {{"two-levels", twoLevels(kDefault)}, {"two-levels-unshot-stop-only", twoLevels(kUnshotStopOnly)}});
    });
  }
};

class PerCellHemisphere : public OpeningsBakes {
 protected:
  static void SetUpTestSuite() {
    setup_.run([] {
      bakeAll({{"hemisphere-converged", [](BakeSettings& s) {
                  s.solver.params.visibility = Visibility::Hemisphere;  // --visibility hemisphere
                  kConverged(s);
                }}});
    });
  }
};

void expectLightmapsCarryEveryTexelsCell() {
  const auto& dir_ = OpeningsBakes::dir_;
  for (const char* d : {"ref", "converged"}) {
    std::vector<ExrChannel> extra;
    readExr((std::filesystem::path(*dir_ / d) / "lightmap.exr").string(), &extra);
    bool found = false;
    for (const ExrChannel& c : extra)
      if (c.name == "cell") {
        found = true;
        float most = -1.0f;
        for (float v : c.values) most = std::max(most, v);
        EXPECT_EQ(most, 2.0f) << d;  // cells 0, 1, 2
      }
    EXPECT_TRUE(found) << d;
  }
}

void expectCompareLightReportsEveryCellAndTheWorst() {
  const nlohmann::json j = OpeningsBakes::compare("converged");
  ASSERT_TRUE(j["cells"].is_array());
  ASSERT_EQ(j["cells"].size(), 3u);
  for (const nlohmann::json& c : j["cells"]) {
    EXPECT_TRUE(c["ratio_of_means"].is_number()) << c.dump();
    EXPECT_TRUE(c["rel_rmse"].is_number()) << c.dump();
    EXPECT_TRUE(c["reference_noise"].is_number()) << c.dump();
  }
  EXPECT_TRUE(j["worst_cell"].is_string());
}

// Every room within 3 % of the reference converged (no early stop to hide a bias) and 5 % at the default
// stop, plus twice the ratio's own error (1.2 % in C at this size). On 7089168 B read 1.15 and C 1.17
// converged; on 531185c the eyes' lost light and the reference's back faces on the zero-thickness
// partition moved C by ±4 %; now A/B/C = 0.992 / 1.015 / 1.018 converged, C 1.022 at the default stop.
// With the two checks above, one test over the fixture's reference and bakes.
TEST_F(PerCellError, RoomsLitThroughOpeningsMatchTheReference) {
  expectLightmapsCarryEveryTexelsCell();
  expectCompareLightReportsEveryCellAndTheWorst();
  for (const auto& [stop, tolerance] : {std::pair{"converged", 0.03}, std::pair{"default", 0.05}}) {
    const nlohmann::json j = compare(stop);
    for (const nlohmann::json& c : j["cells"]) {
      const double ratio = c["ratio_of_means"], err = c["ratio_error"];
      EXPECT_LT(err, 0.03) << stop << " " << c.dump();
      EXPECT_NEAR(ratio, 1.0, tolerance + 2.0 * err) << stop << " " << c.dump();
    }
  }
}

// The default stop is per cell: the 1 % unshot stop alone left room C a fifth of its light to the flat
// ambient term (0.213 here; 5.9 % per texel against the reference without its noise, 5.3 % with the stop
// per cell, which shot 205 times instead of 155). At --ambient-share's default every room's share is
// within it, and the report says so.
TEST_F(PerCellError, TheDefaultStopLeavesNoRoomMostlyToTheAmbientTerm) {
  auto report = [](const std::string& bake) {
    return nlohmann::json::parse(test::slurp(*dir_ / (bake + "/report.json")));
  };
  const nlohmann::json perCell = report("default"), global = report("unshot-stop-only");
  EXPECT_EQ(perCell["ambient_share_target"], 0.1);
  EXPECT_GE(perCell["stop_checks"].get<int>(), 2);  // refused at least once
  EXPECT_GT(perCell["shots"].get<int>(), global["shots"].get<int>());
  ASSERT_EQ(perCell["ambient_share"].size(), 4u);  // A, B, C and texels in no cell
  for (const auto& [cell, share] : perCell["ambient_share"].items())
    EXPECT_LE(share.get<double>(), 0.1) << cell;
  EXPECT_GT(global["ambient_share"]["C"].get<double>(), 0.15);
  EXPECT_EQ(global["stop_checks"], 0);
}

// The interreflection solved on a coarser atlas (--solve-density, as --density auto does) stops per cell
// too: asked on the output's texels, the coarse solve's light interpolated onto them. Its unshot stop
// alone left room C to the ambient term as the one-level solve's did.
TEST_F(PerCellTwoLevels, TheStopPerCellHoldsInTwoLevels) {
  auto report = [](const std::string& bake) {
    return nlohmann::json::parse(test::slurp(*dir_ / (bake + "/report.json")));
  };
  const nlohmann::json perCell = report("two-levels"), global = report("two-levels-unshot-stop-only");
  ASSERT_EQ(perCell["solve_density"], 2.5);
  EXPECT_GE(perCell["stop_checks"].get<int>(), 2);
  EXPECT_GT(perCell["shots"].get<int>(), global["shots"].get<int>());
  for (const auto& [cell, share] : perCell["ambient_share"].items())
    EXPECT_LE(share.get<double>(), 0.1) << cell;
  EXPECT_GT(global["ambient_share"]["C"].get<double>(), 0.15);
  EXPECT_EQ(global["stop_checks"], 0);
  // In a local first: ranging over compare(...)["cells"] would read the temporary after it is destroyed.
  const nlohmann::json comparison = compare("two-levels");
  for (const nlohmann::json& c : comparison["cells"]) {
    const double ratio = c["ratio_of_means"], err = c["ratio_error"];
    EXPECT_NEAR(ratio, 1.0, 0.05 + 2.0 * err) << c.dump();
  }
}

// Cell by cell at the default stop, with either portal model, every room within 5 % (+ 2σ). On 45483fb:
// diffuse B 1.059 and C 1.366 (the lamp's beam spread by the portal, and the ambient term spread by area
// over the scene), directional C 1.189 (the ambient term alone). Now 1.00 / 1.00 / 0.97 with either.
TEST_F(PerCellPortals, RoomsLitThroughPortalsMatchTheReference) {
  for (const char* bake : {"cells-diffuse", "cells-directional"}) {
    const nlohmann::json j = compare(bake);
    for (const nlohmann::json& c : j["cells"]) {
      const double ratio = c["ratio_of_means"], err = c["ratio_error"];
      EXPECT_NEAR(ratio, 1.0, 0.05 + 2.0 * err) << bake << " " << c.dump();
    }
  }
}

// Converged with the cells bake's default portals (binned), every room within 3 % (+ 2σ): no early stop
// hides a bias of the portals. The thesis's Lambertian portals do not reach it in C (0.960 at density 10,
// bench/RESULTS.md): the light that crossed the interior window in line with the narrow door leaves C
// again more than it should when a portal re-emits it evenly; one lobe per texel reads 0.983.
TEST_F(PerCellPortals, ConvergedBinnedPortalsMatchTheReference) {
  const nlohmann::json j = compare("cells-binned-converged");
  for (const nlohmann::json& c : j["cells"]) {
    const double ratio = c["ratio_of_means"], err = c["ratio_error"];
    EXPECT_NEAR(ratio, 1.0, 0.03 + 2.0 * err) << c.dump();
  }
}

// The thesis's hemispherical item buffer, converged (no early stop to hide a bias), every room within 3 %
// (+ 2σ) and the light kept in the closed scene. On 9956b29 (a tessellation even in parameters,
// interpolated depths, rim pixels that showed nothing) A/B/C were 0.985 / 0.975 / 1.068 ± 0.012 at this
// size and 2.5 W of 192 escaped; now 0.993 / 0.999 / 1.014 and 0.7 W (the default stop alike).
TEST_F(PerCellHemisphere, RoomsLitThroughOpeningsMatchTheReference) {
  for (const char* bake : {"hemisphere-converged"}) {
    const nlohmann::json j = compare(bake);
    for (const nlohmann::json& c : j["cells"]) {
      const double ratio = c["ratio_of_means"], err = c["ratio_error"];
      EXPECT_NEAR(ratio, 1.0, 0.03 + 2.0 * err) << bake << " " << c.dump();
    }
    const nlohmann::json report =
        nlohmann::json::parse(test::slurp(*dir_ / (std::string(bake) + "/report.json")));
    const double emitted = report["energy"]["emitted_w"], escaped = report["energy"]["escaped_w"];
    EXPECT_LT(std::abs(escaped), 0.005 * emitted) << bake << " " << report["energy"].dump();
  }
}

std::vector<float> channelOf(const std::filesystem::path& dir, const std::string& name) {
  std::vector<ExrChannel> extra;
  readExr((dir / "lightmap.exr").string(), &extra);
  for (ExrChannel& c : extra)
    if (c.name == name) return std::move(c.values);
  return {};
}

// A raw model without cells (openings without its hand-made ones): bake and reference label every texel
// by the room of the automatic decomposition in front of it, alike, so compare-light reports the three
// rooms; before, the whole scene was one figure and a dark room could not be seen.
TEST(PerCellErrorWithoutCells, RoomsOfTheAutomaticDecomposition) {
  test::TempDir dir;
  const std::string scene = test::quote(dir / "raw.glb"), atlas = " --density 2 ";
  test::cpgiOrThrow(dir, "generate openings --no-cells -o " + scene);
  BakeSettings s;  // in process: --density 2
  s.input.scene = dir / "raw.glb";
  s.output.folder = dir / "bake";
  s.atlas.densityAuto = false;
  s.atlas.params.density = 2;
  test::bakeHere(s);
  test::cpgiOrThrow(dir, "reference " + scene + " -o " + test::quote(dir / "ref") + atlas + "--spp 32 -q");
  const std::vector<float> baked = channelOf(dir / "bake", "cell"), traced = channelOf(dir / "ref", "cell");
  const std::vector<float> area = channelOf(dir / "bake", "area");
  ASSERT_FALSE(baked.empty());
  ASSERT_EQ(area.size(), baked.size());
  EXPECT_EQ(baked, traced);
  EXPECT_EQ(*std::max_element(baked.begin(), baked.end()), 2.0f);
  size_t surface = 0, unlabelled = 0;
  for (size_t i = 0; i < area.size(); ++i)
    if (area[i] > 0.0f) ++surface, unlabelled += baked[i] < 0.0f;
  const nlohmann::json report = nlohmann::json::parse(test::slurp(dir / "bake/report.json"));
  EXPECT_EQ(report["cell_names"].size(), 3u);
  const test::CommandRun r =
      cpgi(dir, "compare-light " + test::quote(dir / "bake") + " " + test::quote(dir / "ref") + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["cells"].size(), 3u);
  for (const nlohmann::json& c : j["cells"]) EXPECT_GT(c["texels"].get<size_t>(), 0u) << c.dump();
  // Every surface faces a room (only padding is −1).
  EXPECT_GT(surface, 0u);
  EXPECT_EQ(unlabelled, 0u);
}

}  // namespace
}  // namespace cpgi
