// The reference's next-event estimation to KHR_lights_punctual lights: in a black box with one grey floor,
// nothing bounces back to the floor, so its B is ρ I cosθ/d² exactly (a deterministic shadow ray, no
// noise); in a closed grey box the walls reflect ρΦ/(1 − ρ) in all (the white furnace with a lamp).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/reference/reference_tracer.h"
#include "tests/radiosity/reference/path_test_scenes.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;
using testing::forEachTexelOf;

// A black 2 m box whose floor (y = 0, its last two triangles) is grey, albedo 0.5; material 0 is black.
Scene greyFloorInABlackBox() {
  Scene s;
  const uint32_t black = addMaterial(s, glm::vec3(0.0f)), grey = addMaterial(s, glm::vec3(0.5f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f), black);
  s.triangles.erase(s.triangles.begin() + 8, s.triangles.begin() + 10);  // the black floor (y = 0) ...
  addRect(s, {0, 0, 0}, {0, 0, 2}, {2, 0, 0}, grey);                     // ... made grey
  return s;
}

TEST(PunctualReference, FloorUnderAPointLampInABlackBoxIsExact) {
  Scene s = greyFloorInABlackBox();
  PunctualLight lamp;
  lamp.position = {0.6f, 1.5f, 1.2f};
  lamp.intensity = glm::vec3(2.0f);
  s.lights.push_back(lamp);
  const std::vector<SamplePoint> points = pathtest::floorPoints({0.3f, 1.0f, 1.7f}, {0.2f, 1.1f, 1.9f});
  Context ctx;
  ReferenceParams params;
  params.spp = 16;
  const ReferenceResult r = traceReference(s, points, params, ctx);
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::vec3 to = lamp.position - points[i].position;
    const float r2 = glm::dot(to, to), want = 0.5f * 2.0f * (to.y / std::sqrt(r2)) / r2;
    EXPECT_NEAR(r.radiosity[i].r, want, 1e-5f * want) << i;
    EXPECT_LT(r.standardError[i].r, 1e-5f * want) << i;
  }
}

TEST(PunctualReference, WhiteFurnaceWithAPointLamp) {
  Scene s;
  const float rho = 0.5f;
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f), addMaterial(s, glm::vec3(rho)));
  PunctualLight lamp;
  lamp.position = {0.7f, 1.3f, 1.1f};
  lamp.intensity = glm::vec3(1.0f);
  s.lights.push_back(lamp);
  Context ctx;
  AtlasParams atlasParams;
  atlasParams.density = 6.0f;
  const LightmapAtlas atlas = buildAtlas(s, findQuads(s), atlasParams, ctx);
  ReferenceParams params;
  params.spp = 64;
  const ReferenceResult r = traceReference(s, atlas, params, ctx);
  double reflected = 0.0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) reflected += double(r.radiosity[i].g) * atlas.area[i];
  const double want = rho / (1.0 - rho) * 4.0 * std::numbers::pi;
  EXPECT_NEAR(reflected / want, 1.0, 0.02);
}

// A point lamp's hard shadow edge across the floor's texels: each texel's value is B's mean over the texel
// (its power over its area), not B at its centre, which reads a texel a quarter lit as dark.
TEST(PunctualReference, ATexelAcrossAShadowEdgeIsItsMeanOverTheTexel) {
  Scene s = greyFloorInABlackBox();
  const int floorTriangle = int(s.triangles.size()) - 1;
  addRect(s, {0, 0.75f, 0}, {1.1f, 0, 0}, {0, 0, 2}, 0);  // a black blind over x < 1.1, edge under the lamp
  PunctualLight lamp;
  lamp.position = {1.1f, 1.5f, 1.0f};
  lamp.intensity = glm::vec3(2.0f);
  s.lights.push_back(lamp);
  auto lit = [&](const glm::vec3& p) {
    if (p.x < 1.1f) return 0.0;
    const glm::vec3 to = lamp.position - p;
    const double r2 = glm::dot(to, to);
    return 0.5 * 2.0 * (to.y / std::sqrt(r2)) / r2;
  };
  Context ctx;
  AtlasParams atlasParams;
  atlasParams.density = 2.5f;  // 0.4 m texels: those from x = 0.8 to 1.2 are a quarter lit
  const LightmapAtlas atlas = buildAtlas(s, findQuads(s), atlasParams, ctx);
  ReferenceParams params;
  params.spp = 4096;
  const ReferenceResult mean = traceReference(s, atlas, params, ctx);
  params.texelMean = false;
  const ReferenceResult centre = traceReference(s, atlas, params, ctx);
  int straddling = 0;
  forEachTexelOf(atlas, floorTriangle, [&](size_t t) {
    const Patch& patch = atlas.patches[size_t(atlas.patch[t])];
    constexpr int n = 200;
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        sum += lit(atlas.position[t] + ((i + 0.5f) / n - 0.5f) * patch.texelU +
                   ((j + 0.5f) / n - 0.5f) * patch.texelV);
    const double want = sum / (n * n), atCentre = lit(atlas.position[t]);
    EXPECT_NEAR(mean.radiosity[t].r, want, 5.0 * mean.standardError[t].r + 1e-4 * want) << t;
    EXPECT_NEAR(centre.radiosity[t].r, atCentre, 1e-5 * atCentre) << t;
    if (atCentre == 0.0 && want > 0.0) {
      ++straddling;
      EXPECT_GT(mean.radiosity[t].r, 0.2 * lit(atlas.position[t] + glm::vec3(0.2f, 0, 0))) << t;
    }
  });
  EXPECT_EQ(straddling, 5);  // the column of texels the edge crosses
}

}  // namespace
}  // namespace cpgi
