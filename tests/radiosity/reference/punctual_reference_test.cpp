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

TEST(PunctualReference, FloorUnderAPointLampInABlackBoxIsExact) {
  Scene s;
  const uint32_t black = addMaterial(s, glm::vec3(0.0f)), grey = addMaterial(s, glm::vec3(0.5f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f), black);
  s.triangles.erase(s.triangles.begin() + 8, s.triangles.begin() + 10);  // the black floor (y = 0) ...
  addRect(s, {0, 0, 0}, {0, 0, 2}, {2, 0, 0}, grey);                     // ... made grey
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

}  // namespace
}  // namespace cpgi
