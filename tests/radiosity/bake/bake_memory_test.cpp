// The bake's memory estimate (bake_limits.h, BakeMemory) against what its parts allocate, counted by this
// test program's operator new: the texel budget's layout takes no more than the atlas it keeps, a whole
// bake no more than its estimate, and --max-memory lowers the texel budget to fit or refuses the bake
// before anything is written. What the GL driver and Embree allocate (malloc, not new) is the estimate's
// base and ray scene, not counted here.
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>

#include <malloc.h>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/quads.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/bake_limits.h"
#include "radiosity/solve/auto_density.h"
#include "scenes/seed_scenes.h"
#include "tests/radiosity/test_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/temp_dir.h"

namespace {

std::atomic<long long> liveBytes{0}, peakBytes{0};

void counted(void* p) {
  const long long now = liveBytes += static_cast<long long>(malloc_usable_size(p));
  long long peak = peakBytes.load();
  while (now > peak && !peakBytes.compare_exchange_weak(peak, now)) {
  }
}

// The bytes operator new handed out at its peak while `f` ran, over those live when it started.
template <class F>
long long peakAllocation(F&& f) {
  const long long before = liveBytes.load();
  peakBytes = before;
  f();
  return peakBytes.load() - before;
}

}  // namespace

void* operator new(std::size_t n) {
  void* p = std::malloc(n == 0 ? 1 : n);
  if (!p) throw std::bad_alloc();
  counted(p);
  return p;
}
void operator delete(void* p) noexcept {
  if (!p) return;
  liveBytes -= static_cast<long long>(malloc_usable_size(p));
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  operator delete(p);
}

namespace cpgi {
namespace {

// A 10 × 10 m floor of 20 × 20 equal quads, one charted grid: the light asks 40 texels a metre of one
// quad and 2 of the rest, and the grid takes its largest, so its atlas holds 100 times the texels its area
// says (fitTexelBudget's byArea).
Scene floorWithOneBrightQuad(std::vector<float>& density) {
  Scene s;
  s.materials.push_back(Material{});
  const int n = 20;
  const float edge = 0.5f;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::vec3 a(float(i) * edge, 0.0f, float(j) * edge);
      testing::addRect(s, a, glm::vec3(0.0f, 0.0f, edge), glm::vec3(edge, 0.0f, 0.0f), 0);
      const float texels = i == 0 && j == 0 ? 40.0f : 2.0f;
      density.resize(s.triangles.size(), texels);
    }
  return s;
}

TEST(BakeMemory, TheTexelBudgetsLayoutAllocatesNoMoreThanTheAtlasItKeeps) {
  std::vector<float> density;
  const Scene s = floorWithOneBrightQuad(density);
  const QuadSet quads = findQuads(s);
  AtlasParams params;
  params.triangleDensity = density;
  Context ctx;
  LightmapAtlas atlas;
  const long long peak = peakAllocation([&] { atlas = fitTexelBudget(s, quads, params, 2000, ctx); });
  ASSERT_LE(atlas.validTexels(), 2000u);
  // The estimate's share of the atlas. Laid out at the area's scale first, the layout filled the grid at
  // 40 texels a metre, 160 000 texels (9 MB) for an atlas of 2 000 (0.8 MB at kBakeBytesPerTexel).
  EXPECT_LE(double(peak), double(atlas.texelCount()) * kBakeBytesPerTexel) << peak;
}

// A bake's estimate holds what the bake allocates, its base apart (the program's and the GL driver's,
// not counted here), and is not made of room to spare: its per-texel share is within 4 times what the
// bake allocates. Seed1 at 32 texels a quad: its atlas's texels, not the fixed costs, make the peak.
TEST(BakeMemory, ABakesEstimateHoldsWhatItAllocates) {
  const SeedScene seed = makeSeedScene(1);
  test::TempDir dir;
  BakeSettings s = test::quickSeed1();
  s.atlas.params.texelsPerQuad = 32;
  s.solver.params.maxShots = 10;  // the buffers are made before the first shot
  s.output.folder = dir / "out";
  BakeResult r;
  const long long peak = peakAllocation([&] { r = test::bakeHere(seed.scene, seed.cells, s); });
  const bake_steps::BakeMemory m = bake_steps::bakeMemory(
      s, seed.scene, r.atlas,
      bake_steps::largestViewBytes(bake_steps::expectedCameras(seed.scene, seed.cells), s.output.views));
  EXPECT_LE(double(peak), m.total() - m.base) << peak << " bytes for " << r.atlas.texelCount() << " texels";
  EXPECT_GE(4.0 * double(peak), m.atlas) << peak << " bytes for " << r.atlas.texelCount() << " texels";
}

// --max-memory under the bake at its texel budget: the budget lowered to what fits, said once, before
// the pilot; under the least budget, refused on `maximum memory` with nothing written.
TEST(BakeMemory, MaxMemoryLowersTheTexelBudgetOrRefusesTheBake) {
  const SeedScene seed = makeSeedScene(1);
  BakeSettings s = test::quickSeed1();
  s.atlas.densityAuto = true;
  s.atlas.autoDensity.maxTexels = 1'000'000;
  const std::vector<Camera> cameras = bake_steps::expectedCameras(seed.scene, seed.cells);
  const double views = bake_steps::largestViewBytes(cameras, s.output.views);
  const double atBudget = bake_steps::bakeMemory(s, seed.scene, 2'500'000, 1'000'000, views).total();
  s.atlas.params.memoryLimit = uint64_t(0.5 * atBudget);
  Context ctx;
  const BakeSettings fitted = bake_steps::withinMemory(s, seed.scene, cameras, ctx);
  EXPECT_LT(fitted.atlas.autoDensity.maxTexels, 1'000'000u);
  EXPECT_GE(fitted.atlas.autoDensity.maxTexels, bake_steps::kLeastTexelBudget);
  const size_t budget = fitted.atlas.autoDensity.maxTexels;
  EXPECT_LE(bake_steps::bakeMemory(
                s, seed.scene, size_t(bake_steps::kAtlasTexelsPerValidTexel * double(budget)), budget, views)
                .total(),
            double(s.atlas.params.memoryLimit));
  ASSERT_EQ(ctx.warnings().size(), 1u);
  EXPECT_EQ(ctx.warnings()[0].rfind("memory: the texel budget lowered from 1000000 to", 0), 0u)
      << ctx.warnings()[0];

  test::TempDir dir;
  s.output.folder = dir / "out";
  s.limits.maxMemory = 64u << 20;  // under the program and its GL driver alone
  BakeRun run;
  run.gl = &test::sharedGl();
  Context refused;
  try {
    bake(seed.scene, seed.cells, s, refused, run);
    ADD_FAILURE() << "a bake over --max-memory at its least texel budget";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "maximum memory");
    EXPECT_NE(e.problem().find("least texel budget"), std::string::npos) << e.problem();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace cpgi
