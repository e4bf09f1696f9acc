// bake() in process on the seed scenes: what comes back without a folder, the files with one (and that
// they hold what came back), the library's defaults, the backend choice and the settings it refuses.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_io.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/bake_jobs.h"
#include "scenes/seed_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

BakeSettings quick() {
  return test::quickSeed1();
}

class BakeSeed1 : public testing::Test {
 protected:
  static void SetUpTestSuite() { seed_ = new SeedScene(makeSeedScene(1)); }
  static void TearDownTestSuite() { delete seed_; }
  static const SeedScene& seed() { return *seed_; }

 private:
  static SeedScene* seed_;
};
SeedScene* BakeSeed1::seed_ = nullptr;

TEST_F(BakeSeed1, WithoutAFolderReturnsTheLightmapAndWritesNothing) {
  Context ctx;
  std::string sizeLine;
  BakeRun run;
  run.sized = [&](const std::string& line) { sizeLine = line; };
  const BakeResult r = bake(seed().scene, seed().cells, quick(), ctx, run);
  EXPECT_EQ(sizeLine.rfind("bake: " + std::to_string(r.atlas.validTexels()) + " texels", 0), 0u) << sizeLine;
  ASSERT_GT(r.atlas.validTexels(), 0u);
  ASSERT_EQ(r.radiosity.size(), size_t(r.atlas.width) * r.atlas.height);
  ASSERT_EQ(r.texelCell.size(), r.radiosity.size());
  EXPECT_EQ(r.cellNames, (std::vector<std::string>{"A", "B", "C"}));
  EXPECT_LE(r.unshotFraction, 0.05);
  EXPECT_GT(r.shots, 2);
  EXPECT_FALSE(r.partial);
  // Light in each room: A and C have lamps, B gets what comes through the doors.
  std::vector<double> light(3, 0.0);
  for (size_t i = 0; i < r.radiosity.size(); ++i)
    if (r.texelCell[i] >= 0.0f) light[size_t(r.texelCell[i])] += r.radiosity[i].g;
  for (double l : light) EXPECT_GT(l, 0.0);
  EXPECT_EQ(r.report["method"], "global");
  EXPECT_EQ(r.report["shots"], r.shots);
  EXPECT_TRUE(r.report["views"].empty());  // nothing written, no pictures
  const nlohmann::json& e = r.report["energy"];
  EXPECT_NEAR(e["absorbed_w"].get<double>() + e["unshot_w"].get<double>() + e["escaped_w"].get<double>(),
              e["emitted_w"].get<double>(), 1e-3 * e["emitted_w"].get<double>());
}

// Backend::Rays bakes with no GL at all (the lamps by shadow rays, every shot by Embree): each room gets
// the light the GL engine gives it, and the report says which engine shot.
TEST_F(BakeSeed1, TheRaysBackendNeedsNoGlAndLightsTheRoomsAsGlDoes) {
  auto roomLight = [](const BakeResult& r) {
    std::vector<double> sum(3, 0.0), area(3, 0.0);
    for (size_t i = 0; i < r.radiosity.size(); ++i)
      if (r.texelCell[i] >= 0.0f && r.atlas.emission[i] == glm::vec3(0.0f)) {
        const size_t c = size_t(r.texelCell[i]);
        sum[c] += double(r.radiosity[i].g) * r.atlas.area[i], area[c] += r.atlas.area[i];
      }
    for (size_t c = 0; c < 3; ++c) sum[c] /= area[c];
    return sum;
  };
  BakeSettings s = quick();
  s.solver.params.unshotFraction = 0.01;
  Context ctx;
  const BakeResult gl = bake(seed().scene, seed().cells, s, ctx);
  s.solver.backend = Backend::Rays;
  const BakeResult rays = bake(seed().scene, seed().cells, s, ctx);
  EXPECT_EQ(gl.report["backend"], "gl");
  EXPECT_EQ(rays.report["backend"], "rays");
  EXPECT_TRUE(rays.report["renderer"].is_null());
  const std::vector<double> a = roomLight(gl), b = roomLight(rays);
  EXPECT_NEAR(b[0] / a[0], 1.0, 0.03) << "A";
  EXPECT_NEAR(b[1] / a[1], 1.0, 0.05) << "B, lit through the doors";
  EXPECT_NEAR(b[2] / a[2], 1.0, 0.03) << "C";
  EXPECT_EQ(rays.report["energy"]["created_w"], 0.0);
  // Cells on rays through each portal model, the portals' lobes and bins too: every room as the GL
  // engine's cells bake lights it.
  s.cells.method = BakeMethod::Cells;
  for (const PortalLight portals : {PortalLight::Binned, PortalLight::Directional, PortalLight::Diffuse}) {
    s.cells.params.portals = portals;
    s.solver.backend = Backend::Gl;
    const BakeResult glCells = bake(seed().scene, seed().cells, s, ctx);
    s.solver.backend = Backend::Rays;
    const BakeResult rayCells = bake(seed().scene, seed().cells, s, ctx);
    EXPECT_EQ(rayCells.report["backend"], "rays");
    EXPECT_GT(rayCells.shots, 0);
    const std::vector<double> g = roomLight(glCells), r = roomLight(rayCells);
    const std::string name = glCells.report["portal_mode"].get<std::string>();
    EXPECT_NEAR(r[0] / g[0], 1.0, 0.03) << "A, " << name;
    EXPECT_NEAR(r[1] / g[1], 1.0, 0.05) << "B, " << name;
    EXPECT_NEAR(r[2] / g[2], 1.0, 0.03) << "C, " << name;
    EXPECT_EQ(rayCells.report["energy"]["created_w"], 0.0) << name;
    std::printf("cells %s: rays / gl per room %.4f %.4f %.4f\n", name.c_str(), r[0] / g[0], r[1] / g[1],
                r[2] / g[2]);
  }
}

TEST_F(BakeSeed1, WithAFolderWritesTheResultSetOfWhatItReturns) {
  test::TempDir dir;
  BakeSettings s = quick();
  s.output.folder = dir / "out";
  Context ctx;
  const BakeResult r = bake(seed().scene, seed().cells, s, ctx);
  for (const char* f : {"lightmap.exr", "lightmap.png", "baked.glb", "report.json", "report.html"})
    EXPECT_TRUE(std::filesystem::exists(dir / (std::string("out/") + f))) << f;
  std::ifstream in(dir / "out/report.json");
  EXPECT_EQ(nlohmann::json::parse(in), r.report);
  EXPECT_FALSE(r.report["views"].empty());
  const ImageRGB lightmap = readExr(dir / "out/lightmap.exr");
  ASSERT_EQ(lightmap.pixels.size(), r.radiosity.size());
  size_t compared = 0;  // the texels of charts (the gutters around them are dilated in the file)
  for (size_t i = 0; i < r.radiosity.size(); ++i)
    if (r.atlas.patch[i] >= 0) {
      ASSERT_EQ(lightmap.pixels[i], r.radiosity[i]) << i;
      ++compared;
    }
  EXPECT_EQ(compared, r.atlas.validTexels());
}

TEST_F(BakeSeed1, CellByCellWithTheLibrarysDefaultPortalsAndLampRays) {
  BakeSettings s = quick();
  s.cells.method = BakeMethod::Cells;
  Context ctx;
  const BakeResult r = bake(seed().scene, seed().cells, s, ctx);
  EXPECT_EQ(r.report["method"], "cells");
  EXPECT_EQ(r.report["portal_mode"], "binned");
  EXPECT_EQ(r.report["lamp_rays"], 64);
  EXPECT_EQ(r.report["cells"], 3);
  EXPECT_EQ(r.report["portals"], 2);
  EXPECT_GE(r.report["rounds"].get<int>(), 1);
}

TEST_F(BakeSeed1, RefusesWhatTheSceneCannotTake) {
  Context ctx;
  BakeSettings onDemand = quick();
  onDemand.cells.onlyCells = "A";  // on demand is a cells bake's
  EXPECT_THROW(bake(seed().scene, seed().cells, onDemand, ctx), InputError);
  BakeSettings tooLarge = quick();
  tooLarge.limits.maxMemory = 1 << 20;  // 1 MB: not even the item buffers
  EXPECT_THROW(bake(seed().scene, seed().cells, tooLarge, ctx), InputError);
  BakeSettings plan = quick();  // cell jobs are a cells bake's
  test::TempDir dir;
  EXPECT_THROW(planBakeJobs(dir.path() / "plan", plan, ctx), InputError);
}

// A process that bakes many times (a cell-job server, this test binary) keeps one context; a bake that
// opens and closes one of its own in between leaves the kept one drawing, and its bake unchanged.
TEST_F(BakeSeed1, ABakeOnItsOwnContextLeavesTheKeptOneDrawing) {
  const BakeResult before = test::bakeHere(seed().scene, seed().cells, quick());
  Context ctx;
  const BakeResult own = bake(seed().scene, seed().cells, quick(), ctx);  // run.gl null: a context of its own
  EXPECT_EQ(own.report["backend"], "gl");
  const BakeResult after = test::bakeHere(seed().scene, seed().cells, quick());
  EXPECT_EQ(after.shots, before.shots);
  ASSERT_EQ(after.radiosity.size(), before.radiosity.size());
  EXPECT_TRUE(after.radiosity == before.radiosity);
}

TEST(BakeBackend, IndirectByRaysFollowsTheSettingAndAutoTheRenderer) {
  Context ctx;
  const EglContext gl(ctx);
  EXPECT_TRUE(indirectByRays(IndirectSolver::Rays, gl));
  EXPECT_FALSE(indirectByRays(IndirectSolver::Gpu, gl));
  const bool software = gl.renderer().find("llvmpipe") != std::string::npos ||
                        gl.renderer().find("softpipe") != std::string::npos;
  EXPECT_EQ(indirectByRays(IndirectSolver::Auto, gl), software) << gl.renderer();
}

TEST(BakeNotes, SayTheSizeAndTheFirstEstimateOnceEach) {
  BakeSettings s;
  s.limits.timeLimit = 10.0;
  std::vector<std::string> notes;
  int passed = 0;
  auto size = std::make_shared<std::string>();
  const Context::ProgressFn fn =
      bakeNotes([&](const Progress&) { ++passed; }, s, std::chrono::steady_clock::now(), size,
                [&](const std::string& n) { notes.push_back(n); });
  fn(Progress{"atlas", 0.5, ""});
  fn(Progress{"solve", 0.0, ""});  // no size yet
  *size = "bake: 10 texels";
  Progress p{"solve", 0.1, ""};
  p.shots = 5, p.secondsLeft = 60.0;
  fn(p);
  fn(p);
  EXPECT_EQ(passed, 4);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_EQ(notes[0].rfind("bake: 10 texels (", 0), 0u) << notes[0];
  EXPECT_EQ(notes[1].rfind("bake: after 5 shots, about 1 min", 0), 0u) << notes[1];
  EXPECT_NE(notes[1].find("the time limit stops it"), std::string::npos) << notes[1];
  EXPECT_FALSE(bakeNotes(nullptr, s, std::chrono::steady_clock::now(), size, [](const std::string&) {}));
}

}  // namespace
}  // namespace cpgi
