// The sky's first shot (radiosity/lightmap/sky_light.h) against closed forms: an open floor under a
// uniform sky gets π Lz, under a CIE overcast one 7π Lz / 9; through a hole in a ceiling, π Lz F with F
// the point-to-square form factor (Lambert's contour formula, inline here: the lightmap library's tests do
// not link the metrics); a closed box, and the closed seed scene's rooms, get none.
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/lightmap/sky_light.h"
#include "scenes/seed_scenes.h"
#include "tests/radiosity/test_scenes.h"
#include "tests/radiosity/test_sky_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;
using testing::atlasAtDensity;

constexpr double kPi = std::numbers::pi;

DirectLight gather(const Scene& s, const LightmapAtlas& atlas) {
  Context ctx;
  DirectLight d;
  addSkyLight(s.sky, RayScene(s), atlas, d, ctx);
  return d;
}

Sky skyOf(Sky::Kind kind, float zenith, float ground = 0.0f) {
  Sky sky;
  sky.kind = kind, sky.zenithRadiance = zenith, sky.groundRadiance = ground;
  return sky;
}

// The box open to the sky under a uniform sky of 3 W/m²/sr, gathered with `rays` directions a texel.
Scene openBox(int rays) {
  Scene s = testing::boxOpenToTheSky(0.5f);
  s.sky = skyOf(Sky::Kind::Uniform, 3.0f);
  s.sky.gatherRays = rays;
  return s;
}

// A gather whose deadline has already passed (bake --time-limit reached before it began), into `late`.
// The sky gathered with its deadline already past: stopped, at the first pass's 8 rays, said in one warning.
SkyGatherData gatherPastDeadline(const Scene& s, const LightmapAtlas& atlas, Context& ctx,
                                 DirectLight& late) {
  const SkyGatherData data =
      addSkyLight(s.sky, RayScene(s), atlas, late, ctx, std::chrono::steady_clock::now());
  EXPECT_TRUE(data.timedOut);
  EXPECT_EQ(data.rays, 8);
  EXPECT_EQ(ctx.warnings().size(), 1u);
  return data;
}

// F(point → square above it, facing it): Lambert's contour formula for a receiver of normal +y.
double formFactorUp(const glm::dvec3& x, const std::array<glm::dvec3, 4>& polygon) {
  double sum = 0.0;
  for (size_t i = 0; i < 4; ++i) {
    const glm::dvec3 a = polygon[i] - x, b = polygon[(i + 1) % 4] - x, c = glm::cross(a, b);
    sum += std::atan2(glm::length(c), glm::dot(a, b)) * c.y / glm::length(c);
  }
  return std::abs(sum) / (2.0 * kPi);
}

TEST(SkyLight, OpenFloorGetsTheWholeSky) {
  Scene s;
  addRect(s, {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, addMaterial(s, glm::vec3(0.5f)));
  const LightmapAtlas atlas = atlasAtDensity(s, 8.0f);
  for (const auto& [kind, irradiance] :
       {std::pair{Sky::Kind::Uniform, kPi}, {Sky::Kind::CieOvercast, 7.0 * kPi / 9.0}}) {
    s.sky = skyOf(kind, 2.0f, 5.0f);  // the ground below the horizon: a floor facing up never sees it
    const DirectLight d = gather(s, atlas);
    for (size_t i = 0; i < atlas.texelCount(); ++i) {
      if (atlas.patch[i] >= 0) {
        EXPECT_NEAR(d.irradiance[i].g, 2.0 * irradiance, 0.01 * 2.0 * irradiance);
      }
    }
    EXPECT_NEAR(d.landed, 3.0 * 4.0 * 2.0 * irradiance, 0.002 * d.landed);
    EXPECT_EQ(d.directionalLanded, d.landed);  // an infinite source emits what lands
  }
}

// A deadline already past (bake --time-limit reached in the density pilot, issue 46) stops the gather
// after its first pass: every texel keeps an estimate of 8 directions, still the hole's light within their
// noise and never more than an open sky's, with the gather's data and a warning saying so. Without a
// deadline the gather in passes is the same as its 1 024 directions in one.
TEST(SkyLight, ADeadlineStopsTheGatherAfterAWholePass) {
  const Scene s = openBox(1024);
  const LightmapAtlas atlas = atlasAtDensity(s, 8.0f);
  Context ctx;
  DirectLight late;
  const SkyGatherData data = gatherPastDeadline(s, atlas, ctx, late);
  EXPECT_EQ(data.requestedRays, 1024);
  ASSERT_EQ(ctx.warnings().size(), 1u);
  EXPECT_NE(ctx.warnings()[0].find("8 of 1024 rays"), std::string::npos);
  const DirectLight full = gather(s, atlas);
  double lateSum = 0.0, fullSum = 0.0;
  size_t lit = 0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) continue;
    EXPECT_LE(late.irradiance[i].g, 3.0 * kPi * 1.0001);
    EXPECT_GE(late.irradiance[i].g, 0.0f);
    lateSum += late.irradiance[i].g * atlas.area[i], fullSum += full.irradiance[i].g * atlas.area[i];
    lit += late.irradiance[i].g > 0.0f;
  }
  EXPECT_GT(lit, 0u);
  EXPECT_NEAR(lateSum, fullSum, 0.1 * fullSum);  // 8 directions a texel, averaged over the box
  EXPECT_NEAR(late.landed, 3.0 * lateSum, 1e-4 * late.landed);
  Context onTime;
  DirectLight again;
  const SkyGatherData all = addSkyLight(s.sky, RayScene(s), atlas, again, onTime,
                                        std::chrono::steady_clock::now() + std::chrono::hours(1));
  EXPECT_FALSE(all.timedOut);
  EXPECT_EQ(all.rays, 1024);
  EXPECT_EQ(again.irradiance, full.irradiance);
  EXPECT_EQ(again.landed, full.landed);
}

// A deadline already past on an atlas of more texels than a chunk of the gather (32 768) stops even the
// first pass once every chart row has a texel in 16 gathered: the others take the estimate of the one
// before them in their row, so every texel of the open box has sky light to within the 8 directions' noise.
TEST(SkyLight, ADeadlineCutsTheFirstPassOfALargeAtlasPartWay) {
  const Scene s = openBox(32);  // the whole gather to compare with, kept short
  const LightmapAtlas atlas = atlasAtDensity(s, 80.0f);
  ASSERT_GT(atlas.validTexels(), 3u * 32768u);
  Context ctx;
  DirectLight late;
  gatherPastDeadline(s, atlas, ctx, late);
  ASSERT_EQ(ctx.warnings().size(), 1u);
  EXPECT_NE(ctx.warnings()[0].find("in the first pass"), std::string::npos) << ctx.warnings()[0];
  const DirectLight full = gather(s, atlas);
  double lateSum = 0.0, fullSum = 0.0;
  size_t copied = 0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) continue;
    EXPECT_LE(late.irradiance[i].g, 3.0 * kPi * 1.0001);
    // Within a row the copies run after their seed: a texel with the one before it in its row.
    if (i > 0 && atlas.patch[i - 1] == atlas.patch[i] && late.irradiance[i] == late.irradiance[i - 1])
      ++copied;
    lateSum += late.irradiance[i].g * atlas.area[i], fullSum += full.irradiance[i].g * atlas.area[i];
  }
  EXPECT_GT(copied, atlas.validTexels() / 4);  // most of the texels were not reached
  EXPECT_NEAR(lateSum, fullSum, 0.1 * fullSum);
  EXPECT_NEAR(late.landed, 3.0 * lateSum, 1e-4 * late.landed);
}

// A deadline already past on an atlas with more seeds than the first pass's first chunk (8 192 texels)
// stops after that chunk: the seeds it gathered lie all over the atlas, those it did not take their
// chart's mean, the rest of each row its seed's, so the box's sky light is still there within the noise,
// and no more than one chunk of rays was traced past the deadline.
TEST(SkyLight, ADeadlineStopsTheFirstPassAfterItsFirstChunkOfSeeds) {
  const Scene s = openBox(32);
  const LightmapAtlas atlas = atlasAtDensity(s, 160.0f);
  ASSERT_GT(atlas.validTexels() / 16, 2u * 8192u);  // seeds enough for more than two chunks
  Context ctx;
  DirectLight late;
  gatherPastDeadline(s, atlas, ctx, late);
  ASSERT_EQ(ctx.warnings().size(), 1u);
  EXPECT_EQ(ctx.warnings()[0].rfind("sky light: the deadline came in the first pass, after 8192 of ", 0), 0u)
      << ctx.warnings()[0];
  EXPECT_NE(ctx.warnings()[0].find("its chart's mean"), std::string::npos) << ctx.warnings()[0];
  const DirectLight full = gather(s, atlas);
  double lateSum = 0.0, fullSum = 0.0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) continue;
    EXPECT_LE(late.irradiance[i].g, 3.0 * kPi * 1.0001);
    lateSum += late.irradiance[i].g * atlas.area[i], fullSum += full.irradiance[i].g * atlas.area[i];
  }
  EXPECT_NEAR(lateSum, fullSum, 0.1 * fullSum);
  EXPECT_NEAR(late.landed, 3.0 * lateSum, 1e-4 * late.landed);
}

TEST(SkyLight, ThroughAHoleInTheCeilingMatchesTheFormFactor) {
  const Scene s = openBox(1024);
  const LightmapAtlas atlas = atlasAtDensity(s, 8.0f);
  const DirectLight d = gather(s, atlas);
  double got = 0.0, want = 0.0;
  testing::forEachTexelOf(atlas, 0, [&](size_t t) {
    const double exact = kPi * 3.0 * formFactorUp(glm::dvec3(atlas.position[t]), testing::skyHole());
    EXPECT_NEAR(d.irradiance[t].r, exact, 0.1 * exact + 0.02) << "texel " << t;
    got += d.irradiance[t].r * atlas.area[t], want += exact * atlas.area[t];
  });
  EXPECT_NEAR(got, want, 0.01 * want);
  for (int ceiling = 10; ceiling < 18; ++ceiling)  // facing down, it sees only the box
    testing::forEachTexelOf(atlas, ceiling, [&](size_t t) { EXPECT_EQ(d.irradiance[t], glm::vec3(0.0f)); });
}

TEST(SkyLight, ClosedScenesGetNoneInside) {
  Scene box;
  addClosedBox(box, glm::vec3(0.0f), glm::vec3(2.0f), addMaterial(box, glm::vec3(0.5f)));
  box.sky = skyOf(Sky::Kind::CieOvercast, 4.0f, 1.0f);
  const DirectLight closed = gather(box, atlasAtDensity(box, 4.0f));
  EXPECT_EQ(closed.landed, 0.0);

  // seed1's faces all face into its rooms (its walls have no outer faces): none sees the sky.
  Scene seed = makeSeedScene(1).scene;
  seed.sky = box.sky;
  const LightmapAtlas atlas = atlasAtDensity(seed, 4.0f);
  const DirectLight d = gather(seed, atlas);
  EXPECT_EQ(d.landed, 0.0);
  for (const glm::vec3& e : d.irradiance) EXPECT_EQ(e, glm::vec3(0.0f));
}

}  // namespace
}  // namespace cpgi
