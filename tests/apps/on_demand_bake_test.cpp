// End to end: on-demand cell bakes (`--only-cells`, `--around X,Y,Z --depth K`, `--boundary`). With K
// covering every cell the lightmap is the whole cells bake's; with one room chosen only that room's texels
// have light, close to the whole bake's; bad names and points fail with one line and no output.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/suite_setup.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::slurp;

struct Lightmap {
  ImageRGB rgb;
  std::vector<float> area;
};

Lightmap readLightmap(const std::string& dir) {
  std::vector<ExrChannel> extra;
  Lightmap m;
  m.rgb = readExr(dir + "/lightmap.exr", &extra);
  for (const ExrChannel& c : extra)
    if (c.name == "area") m.area = c.values;
  return m;
}

class OnDemandBake : public ::testing::Test {
 protected:
  void SetUp() override { setup_.require(); }
  static inline test::SuiteSetup setup_;
  static void SetUpTestSuite() {
    setup_.run([] {
      dir_ = new test::TempDir;
      scene_ = *dir_ / "seed1.glb";
      ASSERT_EQ(cpgi(*dir_, "generate seed1 -o '" + scene_ + "'").status, 0);
      bakeHere("whole", settings());
    });
  }
  // The bakes of the tests, in process: --method cells --cells SCENE --texels-per-quad 4 --unshot 0.02
  // --item-buffer 256, into folder `out`.
  static BakeSettings settings() {
    BakeSettings s = test::cellsBake(scene_, scene_);
    s.atlas.densityAuto = false;
    s.atlas.params.texelsPerQuad = 4;
    s.solver.params.unshotFraction = 0.02;
    s.solver.params.itemBuffer = 256;
    return s;
  }
  static void bakeHere(const std::string& out, BakeSettings s) {
    s.output.folder = *dir_ / out;
    test::bakeHere(s);
  }
  // The same on the command line, for its refusals.
  static void TearDownTestSuite() { delete dir_; }
  static test::CommandRun bake(const std::string& out, const std::string& extra) {
    return cpgi(*dir_, "bake '" + scene_ + "' -o '" + *dir_ / out + "' --method cells --cells '" + scene_ +
                           "' --texels-per-quad 4 --unshot 0.02 --item-buffer 256 -q " + extra);
  }
  static nlohmann::json report(const std::string& out) {
    return nlohmann::json::parse(slurp(*dir_ / (out + "/report.json")));
  }
  static inline test::TempDir* dir_ = nullptr;
  static inline std::string scene_;
};

TEST_F(OnDemandBake, DepthCoveringEveryCellIsTheWholeBake) {
  // (6.2, 1.5, 2) is the middle of room B; A and C are one portal away.
  BakeSettings s = settings();  // --around 6.2,1.5,2 --depth 1
  s.cells.around = "6.2,1.5,2";
  s.cells.depth = 1;
  bakeHere("around", s);
  const nlohmann::json rep = report("around");
  EXPECT_EQ(rep["on_demand"]["around_cell"], "B");
  EXPECT_EQ(rep["on_demand"]["baked"], nlohmann::json({"A", "B", "C"}));
  EXPECT_TRUE(rep["on_demand"]["boundary"].empty());
  EXPECT_EQ(rep["on_demand"]["baked_texels"], rep["texels"]);
  const Lightmap a = readLightmap(*dir_ / "around"), b = readLightmap(*dir_ / "whole");
  ASSERT_EQ(a.rgb.pixels.size(), b.rgb.pixels.size());
  float worst = 0.0f, peak = 0.0f;
  for (size_t i = 0; i < a.rgb.pixels.size(); ++i) {
    worst = std::max(worst, glm::length(a.rgb.pixels[i] - b.rgb.pixels[i]));
    peak = std::max(peak, glm::length(b.rgb.pixels[i]));
  }
  EXPECT_LE(worst, 1e-5f * peak);
}

TEST_F(OnDemandBake, OneRoomIsLitThroughItsDoorsAndTheRestIsBlack) {
  BakeSettings s = settings();  // --only-cells B
  s.cells.onlyCells = "B";
  bakeHere("only-b", s);
  const nlohmann::json rep = report("only-b");
  EXPECT_EQ(rep["on_demand"]["baked"], nlohmann::json({"B"}));
  EXPECT_EQ(rep["on_demand"]["boundary"], nlohmann::json({"A", "C"}));
  EXPECT_EQ(rep["on_demand"]["boundary_mode"], "coarse");
  for (const auto& c : rep["cell_energy"]) EXPECT_EQ(c["written"].get<bool>(), c["name"] == "B") << c["name"];
  const size_t bakedTexels = rep["on_demand"]["baked_texels"].get<size_t>();
  EXPECT_GT(bakedTexels, 0u);
  EXPECT_LT(bakedTexels, rep["texels"].get<size_t>() / 2);

  // Lit texels: exactly B's (every texel of B gets light through the doors), and near the whole bake.
  const Lightmap one = readLightmap(*dir_ / "only-b"), whole = readLightmap(*dir_ / "whole");
  size_t lit = 0;
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < one.rgb.pixels.size(); ++i) {
    if (!(one.area[i] > 0.0f) || one.rgb.pixels[i] == glm::vec3(0.0f)) continue;
    ++lit;
    const glm::dvec3 d = glm::dvec3(one.rgb.pixels[i]) - glm::dvec3(whole.rgb.pixels[i]);
    num += one.area[i] * glm::dot(d, d);
    den += one.area[i] * glm::dot(glm::dvec3(whole.rgb.pixels[i]), glm::dvec3(whole.rgb.pixels[i]));
  }
  EXPECT_EQ(lit, bakedTexels);
  EXPECT_LT(std::sqrt(num / den), 0.07);  // measured 0.046 (boundary rooms at 2² texels per quad)

  // Dark boundary: B has no lamp, so nothing at all.
  s.cells.boundary = BoundaryMode::Dark;  // --boundary dark
  bakeHere("only-b-dark", s);
  const Lightmap dark = readLightmap(*dir_ / "only-b-dark");
  EXPECT_TRUE(std::all_of(dark.rgb.pixels.begin(), dark.rgb.pixels.end(),
                          [](const glm::vec3& v) { return v == glm::vec3(0.0f); }));
  EXPECT_EQ(report("only-b-dark")["on_demand"]["boundary_mode"], "dark");
}

TEST_F(OnDemandBake, BadNamesAndPointsFailWithOneLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"--only-cells B,D", "--only-cells"},
      {"--around 100,1.5,2", "in no cell"},
      {"--around 4.1,2.5,2", "in no cell"},  // inside the wall above the door
      {"--around 1,2", "--around"},
      {"--around 6,1,2 --only-cells B", "--only-cells"},
      {"--depth 1", "--depth"},
  };
  for (const auto& [args, expected] : cases) {
    const test::CommandRun r = bake("bad", args);
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(*dir_ / "bad")) << args;
  }
  const test::CommandRun r =
      cpgi(*dir_, "bake '" + scene_ + "' -o '" + *dir_ / "bad" + "' --only-cells A -q");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--method cells"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cpgi
