#include "radiosity/lightmap/seam_gutters.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/quads.h"
#include "radiosity/lightmap/lightmap_sampling.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;
using testing::addTriangle;

// Light rising 2 W/m² a metre along x: bilinear lookups reproduce it exactly between texel centres.
glm::vec3 rampAt(const glm::vec3& p) {
  return glm::vec3(1.0f + 2.0f * p.x);
}

// The ramp on every valid texel of `atlas`, dilated as the outputs are.
std::vector<glm::vec3> dilatedRamp(const LightmapAtlas& atlas) {
  std::vector<glm::vec3> v(atlas.texelCount(), glm::vec3(0.0f));
  for (size_t t = 0; t < v.size(); ++t)
    if (atlas.patch[t] >= 0) v[t] = rampAt(atlas.position[t]);
  dilate(atlas, v);
  return v;
}

// The lightmap at world point q of triangle `tri`, as an engine reads it: the corners' coordinates
// interpolated over the triangle, a bilinear lookup.
float lookup(const Scene& s, const LightmapAtlas& atlas, const std::vector<glm::vec3>& v, size_t tri,
             glm::vec3 q) {
  const Triangle& t = s.triangles[tri];
  const glm::vec3 n = glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
  const float area = glm::dot(n, n);
  const float b1 = glm::dot(glm::cross(q - t.p[0], t.p[2] - t.p[0]), n) / area;
  const float b2 = glm::dot(glm::cross(t.p[1] - t.p[0], q - t.p[0]), n) / area;
  const auto& uv = atlas.triangleUV[tri];
  return sampleBilinear(atlas.width, atlas.height, v, (1.0f - b1 - b2) * uv[0] + b1 * uv[1] + b2 * uv[2]).x;
}

bool inside(const Triangle& t, glm::vec3 q) {
  const glm::vec3 n = t.geometricNormal();
  for (int k = 0; k < 3; ++k)
    if (glm::dot(glm::cross(t.p[(k + 1) % 3] - t.p[k], q - t.p[k]), n) < 0.0f) return false;
  return true;
}

// The largest miss of the ramp over points of the floor z = 0 at y, x in [from, to], each read on the
// triangle holding it.
float worstMiss(const Scene& s, const LightmapAtlas& atlas, const std::vector<glm::vec3>& v, float y,
                float from, float to) {
  float worst = 0.0f;
  for (float x = from; x <= to; x += 0.005f) {
    const glm::vec3 q(x, y, 0.0f);
    for (size_t tri = 0; tri < s.triangles.size(); ++tri)
      if (inside(s.triangles[tri], q)) {
        worst = std::max(worst, std::abs(lookup(s, atlas, v, tri, q) - rampAt(q).x));
        break;
      }
  }
  return worst;
}

LightmapAtlas build(const Scene& s, const AtlasParams& params) {
  Context ctx;
  return buildAtlas(s, findQuads(s), params, ctx);
}

// Two quads of one floor side by side, [0, 1] and [1, 2] along x, at 4 and 16 texels a metre.
Scene twoDensityFloor(AtlasParams& params) {
  Scene s;
  const uint32_t floor = addMaterial(s, glm::vec3(0.5f));
  addRect(s, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), floor, 0);
  addRect(s, glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), floor, 1);
  params.triangleDensity = {4.0f, 4.0f, 16.0f, 16.0f};
  return s;
}

// Two quads of one floor side by side at 4 and 16 texels a metre: with each gutter holding the other
// chart's light, lookups across the seam follow the ramp; holding their own edge texel, the coarse side
// stopped rising 12.5 cm short of the seam (a step of a quarter of the light's rise a metre).
TEST(SeamGutters, ChartsOfOneFloorAtTwoDensitiesMeetWithoutAStep) {
  AtlasParams params;
  const Scene s = twoDensityFloor(params);
  LightmapAtlas atlas = build(s, params);
  ASSERT_EQ(atlas.patches.size(), 2u);
  EXPECT_FALSE(atlas.gutter.empty());
  // Between the coarse chart's first centre (12.5 cm) and the fine one's last (2 m − 3.1 cm).
  EXPECT_LT(worstMiss(s, atlas, dilatedRamp(atlas), 0.5f, 0.13f, 1.96f), 1e-3f);
  atlas.gutter.clear();  // each chart's gutter from its own edge
  EXPECT_GT(worstMiss(s, atlas, dilatedRamp(atlas), 0.5f, 0.13f, 1.96f), 0.2f);
}

// Past its deadline the gutters stop before their first chart (a large atlas's take seconds): the layout
// is told (AtlasLayoutStopped) and laid out again coarse by its caller; without one they are all made.
TEST(SeamGutters, PastTheDeadlineTheGuttersStopAndSaySo) {
  AtlasParams params;
  const Scene s = twoDensityFloor(params);
  const LightmapAtlas atlas = build(s, params);
  EXPECT_THROW(seamGutters(atlas, s, params.padding, std::chrono::steady_clock::now()), AtlasLayoutStopped);
  EXPECT_EQ(seamGutters(atlas, s, params.padding).size(), atlas.gutter.size());
  EXPECT_FALSE(atlas.gutter.empty());
}

// A spherical-harmonic coefficient of the light's direction is negative as often as not: its gutters are
// extrapolated as they are, where light's are kept at 0 or more (the SH maps' gutters clamped at 0 turned
// the light's direction at chart edges).
TEST(SeamGutters, SignedValuesAreExtrapolatedAsTheyAre) {
  AtlasParams params;
  const Scene s = twoDensityFloor(params);
  const LightmapAtlas atlas = build(s, params);
  ASSERT_FALSE(atlas.gutter.empty());
  auto negativeRamp = [&](DilatedValues kind) {
    std::vector<glm::vec3> v(atlas.texelCount(), glm::vec3(0.0f));
    for (size_t t = 0; t < v.size(); ++t)
      if (atlas.patch[t] >= 0) v[t] = -rampAt(atlas.position[t]);
    dilate(atlas, v, 2, kind);
    for (glm::vec3& x : v) x = -x;  // worstMiss compares with the ramp
    return v;
  };
  EXPECT_LT(worstMiss(s, atlas, negativeRamp(DilatedValues::Signed), 0.5f, 0.13f, 1.96f), 1e-3f);
  EXPECT_GT(worstMiss(s, atlas, negativeRamp(DilatedValues::Light), 0.5f, 0.13f, 1.96f), 0.2f);
}

// Two rooms' floors meeting under a partition of no thickness (openings' B|C): the wall on the seam hides
// each floor from the other, and a gutter reading the other room's light put a bright rim along the dark
// room's wall (openings' C: rel RMSE 4.4 → 26 %). Where the partition has a door, the floor goes on.
TEST(SeamGutters, AWallOnTheSeamKeepsEachSideItsOwnLight) {
  for (bool door : {false, true}) {
    Scene s;
    const uint32_t floor = addMaterial(s, glm::vec3(0.5f)), wall = addMaterial(s, glm::vec3(0.7f));
    addRect(s, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), floor, 0);
    addRect(s, glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), floor,
            1);
    // Back-to-back faces on x = 1, over y in [-0.5, 1.5] or, with the door, [-0.5, 0.5].
    const glm::vec3 along(0.0f, door ? 1.0f : 2.0f, 0.0f), up(0.0f, 0.0f, 1.0f);
    addRect(s, glm::vec3(1.0f, -0.5f, 0.0f), along, up, wall, 2);
    addRect(s, glm::vec3(1.0f, -0.5f, 0.0f), up, along, wall, 3);
    AtlasParams params;
    params.triangleDensity = {4.0f, 4.0f, 16.0f, 16.0f, 4.0f, 4.0f, 4.0f, 4.0f};
    const LightmapAtlas atlas = build(s, params);
    const std::vector<glm::vec3> v = dilatedRamp(atlas);
    if (door) {  // behind the wall's end the floor reads across; in the doorway too
      EXPECT_FALSE(atlas.gutter.empty());
      EXPECT_LT(worstMiss(s, atlas, v, 0.8f, 0.13f, 1.96f), 1e-3f);
      EXPECT_GT(worstMiss(s, atlas, v, 0.2f, 0.13f, 1.96f), 0.2f);
    } else {
      EXPECT_TRUE(atlas.gutter.empty());
    }
  }
}

// Across a change of material or of facing the light may step: the gutters keep their own chart's light.
TEST(SeamGutters, AnotherMaterialOrFacingIsNotTheSameSurface) {
  for (int variant : {0, 1}) {
    Scene s;
    const uint32_t a = addMaterial(s, glm::vec3(0.5f));
    const uint32_t b = variant == 0 ? addMaterial(s, glm::vec3(0.8f)) : a;
    addRect(s, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), a, 0);
    if (variant == 0)
      addRect(s, glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), b, 1);
    else  // the same material facing down
      addRect(s, glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), b, 1);
    const LightmapAtlas atlas = build(s, AtlasParams{});
    EXPECT_TRUE(atlas.gutter.empty()) << variant;
  }
}

// A floor that is no rectangle comes as loose triangles, each chart a square half empty: the texels past
// the diagonal read the other triangle's light (each chart extrapolating affinely from its three nearest
// valid centres), so lookups across the diagonal follow the ramp; with the edge texels held they missed
// it by up to 0.15.
TEST(SeamGutters, LooseTrianglesOfOneFloorReadEachOthersLight) {
  Scene s;
  const uint32_t floor = addMaterial(s, glm::vec3(0.5f));
  const glm::vec3 a(0.0f), b(2.0f, 0.0f, 0.0f), c(2.5f, 1.0f, 0.0f), d(0.3f, 1.0f, 0.0f);
  addTriangle(s, a, b, c, floor, 0);
  addTriangle(s, a, c, d, floor, 0);
  LightmapAtlas atlas = build(s, AtlasParams{});
  ASSERT_EQ(atlas.patches.size(), 2u);
  ASSERT_EQ(atlas.patches[0].quad, -1);
  // Across the diagonal from (0, 0) to (2.5, 1), at y = 0.4 and 0.6 it lies at x = 1 and 1.5.
  float with = 0.0f, without = 0.0f;
  for (float y : {0.4f, 0.6f}) with = std::max(with, worstMiss(s, atlas, dilatedRamp(atlas), y, 0.8f, 1.7f));
  atlas.gutter.clear();
  for (float y : {0.4f, 0.6f})
    without = std::max(without, worstMiss(s, atlas, dilatedRamp(atlas), y, 0.8f, 1.7f));
  EXPECT_LT(with, 1e-3f);
  EXPECT_GT(without, 0.1f);
}

}  // namespace
}  // namespace cpgi
