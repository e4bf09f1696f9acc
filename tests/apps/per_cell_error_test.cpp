// End to end (issue 11): bake and reference mark every texel with its cell, and compare-light reports each
// cell's ratio of means, relative RMSE and reference noise against that cell's own reference, and the worst
// cell. On the openings scene (room C two openings from the lamp), the far rooms' ratios are pinned for
// the global solve (the 3×3 item-buffer test and the fixed eyes made B +15 % and C +17 % converged) and
// cell by cell with both portal models (bench/RESULTS.md).
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using test::cpgi;

// The openings scene, its sampled reference, and the bakes `bakes` (folder name, options) against it.
// CTest runs every test in a process of its own: each fixture bakes only what its tests compare.
class OpeningsBakes : public ::testing::Test {
 protected:
  static void bakeAll(const std::vector<std::pair<std::string, std::string>>& bakes) {
    if (!dir_) dir_ = std::make_unique<test::TempDir>();
    auto run = [](const std::string& args) { test::cpgiOrThrow(*dir_, args); };
    const std::string scene = test::quote(*dir_ / "openings.glb");
    const std::string atlas = " --density 5 ";
    run("generate openings -o " + scene);
    run("reference " + scene + " -o " + test::quote(*dir_ / "ref") + atlas + "--spp 1024 --texels 1500 -q");
    for (const auto& [name, options] : bakes)
      run("bake " + scene + " -o " + test::quote(*dir_ / name) + atlas + options + " -q");
  }
  static void TearDownTestSuite() { dir_.reset(); }
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
  static void SetUpTestSuite() { bakeAll({{"converged", "--unshot 0.0001"}, {"default", ""}}); }
};

class PerCellPortals : public OpeningsBakes {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<test::TempDir>();
    const std::string cells = "--method cells --cells " + test::quote(*dir_ / "openings.glb");
    bakeAll({{"cells-diffuse", cells + " --portals diffuse"},
             {"cells-directional", cells + " --portals directional"}});
  }
};

TEST_F(PerCellError, LightmapsCarryEveryTexelsCell) {
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

TEST_F(PerCellError, CompareLightReportsEveryCellAndTheWorst) {
  const nlohmann::json j = compare("converged");
  ASSERT_TRUE(j["cells"].is_array());
  ASSERT_EQ(j["cells"].size(), 3u);
  for (const nlohmann::json& c : j["cells"]) {
    EXPECT_TRUE(c["ratio_of_means"].is_number()) << c.dump();
    EXPECT_TRUE(c["rel_rmse"].is_number()) << c.dump();
    EXPECT_TRUE(c["reference_noise"].is_number()) << c.dump();
  }
  EXPECT_TRUE(j["worst_cell"].is_string());
}

// Converged and at the default stop, every room within 5 % of the reference, plus twice the ratio's own
// error (1 % in C at this size). On 7089168 B read 1.15 and C 1.17 converged; on 531185c the eyes' lost
// light and the reference's back faces on the zero-thickness partition moved C by ±4 %; now
// A/B/C = 0.99/1.02/1.04 (both stops).
TEST_F(PerCellError, RoomsLitThroughOpeningsMatchTheReference) {
  for (const char* stop : {"converged", "default"}) {
    const nlohmann::json j = compare(stop);
    for (const nlohmann::json& c : j["cells"]) {
      const double ratio = c["ratio_of_means"], err = c["ratio_error"];
      EXPECT_LT(err, 0.03) << stop << " " << c.dump();
      EXPECT_NEAR(ratio, 1.0, 0.05 + 2.0 * err) << stop << " " << c.dump();
    }
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

}  // namespace
}  // namespace cpgi
