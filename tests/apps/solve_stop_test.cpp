// End to end (issue 15, item 5): a bake that cannot converge is refused up front, not left to run the
// default 100,000 shots: a closed box of albedo 1 (light never dies out) or 0.999 (thousands of bounces)
// stops with exit 1 and one line naming --max-shots, before anything is written; with --max-shots the
// user's bound holds and the bake succeeds.
#include <filesystem>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/scene_io.h"
#include "scenes/scene_builder.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

namespace fs = std::filesystem;

// A closed 2 m box of albedo `albedo` lit by a 0.5 m lamp on its floor.
fs::path writeBox(const test::TempDir& dir, float albedo) {
  Scene scene;
  SceneBuilder b(scene);
  const uint32_t wall = b.material("wall", glm::vec3(albedo));
  const uint32_t lamp = b.material("lamp", glm::vec3(albedo), glm::vec3(10.0f));
  const uint32_t node = b.node("box");
  const float s = 2.0f;
  const glm::vec3 X(s, 0, 0), Y(0, s, 0), Z(0, 0, s), o(0.0f);
  b.quad(o, X, Y, wall, node);
  b.quad(o + Z, Y, X, wall, node);
  b.quad(o, Y, Z, wall, node);
  b.quad(o + X, Z, Y, wall, node);
  b.quad(o, Z, X, wall, node);
  b.quad(o + Y, X, Z, wall, node);
  b.quad(glm::vec3(0.75f, 0.75f, 0.01f), glm::vec3(0.5f, 0, 0), glm::vec3(0, 0.5f, 0), lamp, node);
  const fs::path path = dir.path() / ("box-" + std::to_string(albedo) + ".glb");
  writeGltf(path.string(), scene);
  return path;
}

TEST(SolveStop, AlbedoNearOneWithoutMaxShotsIsRefusedUpFront) {
  test::TempDir dir;
  for (const float albedo : {1.0f, 0.999f}) {
    const fs::path scene = writeBox(dir, albedo);
    const fs::path out = dir.path() / "out";
    const test::CommandRun r = test::cpgi(
        dir.path(), "bake " + test::quote(scene) + " -q --texels-per-quad 2 -o " + test::quote(out));
    EXPECT_EQ(r.status, 1) << r.err;
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_NE(r.errLines()[0].find(scene.string() + ": mean albedo "), std::string::npos) << r.err;
    EXPECT_NE(r.errLines()[0].find(albedo == 1.0f ? "for ever" : "about 4602 times"), std::string::npos)
        << r.err;
    EXPECT_NE(r.errLines()[0].find("--max-shots N"), std::string::npos) << r.err;
    EXPECT_NE(r.errLines()[0].find("--unshot"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_empty(out)) << "nothing written";
  }
}

// --no-ambient: the ambient term's random walks (radiosity/solve/ambient_transfer.cpp) bounce in a closed
// box of albedo 1 until a ray slips out of it, 35 of the bake's 36 CPU seconds; the count of shots is what
// is checked here, not the ambient term.
TEST(SolveStop, MaxShotsBoundsTheSolve) {
  test::TempDir dir;
  const fs::path out = dir.path() / "out";
  const test::CommandRun r = test::cpgi(
      dir.path(), "bake " + test::quote(writeBox(dir, 1.0f)) +
                      " -q --texels-per-quad 2 --no-ambient --max-shots 30 -o " + test::quote(out));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(test::slurp((out / "report.json").string()));
  EXPECT_EQ(report["shots"], 30);
  EXPECT_GT(double(report["unshot_fraction"]), 0.5);  // albedo 1: the light is all still there
}

// The reference by the same rule (issue 15): its paths' Russian roulette would end long before the light
// of a box of albedo near 1 dies out (at 1 it never does), so it is refused up front unless --max-bounces
// bounds the paths, which the report then records.
TEST(SolveStop, ReferenceOfAlbedoNearOneNeedsMaxBounces) {
  test::TempDir dir;
  for (const float albedo : {1.0f, 0.999f}) {
    const fs::path scene = writeBox(dir, albedo);
    const fs::path out = dir.path() / "out";
    const test::CommandRun r =
        test::cpgi(dir.path(), "reference " + test::quote(scene) + " -q --texels-per-quad 2 --spp 8 -o " +
                                   test::quote(out));
    EXPECT_EQ(r.status, 1) << r.err;
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_NE(r.errLines()[0].find(scene.string() + ": mean albedo "), std::string::npos) << r.err;
    EXPECT_NE(r.errLines()[0].find(albedo == 1.0f ? "for ever" : "about 4602 times"), std::string::npos)
        << r.err;
    EXPECT_NE(r.errLines()[0].find("bound the paths with --max-bounces N"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out / "report.json")) << "nothing written";
  }
  const fs::path out = dir.path() / "bounded";
  const test::CommandRun r =
      test::cpgi(dir.path(), "reference " + test::quote(writeBox(dir, 1.0f)) +
                                 " -q --texels-per-quad 2 --spp 8 --max-bounces 40 -o " + test::quote(out));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(test::slurp((out / "report.json").string()));
  EXPECT_EQ(report["max_bounces"], 40);
}

}  // namespace
}  // namespace cpgi
