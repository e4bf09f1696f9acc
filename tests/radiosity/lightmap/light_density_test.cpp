#include "radiosity/lightmap/light_density.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;

// A 4 × 3 × 2.5 m room (each face one quad) on a pilot atlas of 10 texels per metre.
struct PilotRoom {
  Scene scene;
  LightmapAtlas pilot;
  PilotRoom() {
    addClosedBox(scene, glm::vec3(0.0f), glm::vec3(4.0f, 3.0f, 2.5f), addMaterial(scene, glm::vec3(0.7f)));
    Context ctx;
    AtlasParams p;
    p.density = 10.0f;
    pilot = buildAtlas(scene, findQuads(scene), p, ctx);
  }
  template <class Light>
  std::vector<glm::vec3> lit(Light light) const {
    std::vector<glm::vec3> values(pilot.texelCount(), glm::vec3(0.0f));
    for (size_t t = 0; t < pilot.texelCount(); ++t)
      if (pilot.patch[t] >= 0) values[t] = glm::vec3(light(pilot.position[t], pilot.normal[t]));
    return values;
  }
  // The density of the face whose normal is `n` (both of its triangles alike).
  float faceDensity(const std::vector<float>& density, glm::vec3 n) const {
    float d = -1.0f;
    for (size_t i = 0; i < scene.triangles.size(); ++i)
      if (glm::dot(scene.triangles[i].geometricNormal(), n) > 0.99f) {
        if (d >= 0.0f) {
          EXPECT_EQ(density[i], d) << "the two triangles of one quad differ";
        }
        d = density[i];
      }
    return d;
  }
};

const glm::vec3 kFloor(0, 0, 1), kCeiling(0, 0, -1), kWallX(1, 0, 0);

TEST(LightDensity, LinearLightNeedsTheFewestTexels) {
  const PilotRoom room;
  // Bilinear interpolation is exact on light linear in position: no surface needs more than the minimum.
  const auto light = room.lit([](glm::vec3 x, glm::vec3) { return 1.0f + 0.4f * x.x + 0.2f * x.y + 0.1f * x.z; });
  const LightDensityParams params;
  const std::vector<float> density = lightDensity(room.pilot, light, room.scene.triangles.size(), params);
  for (float d : density) EXPECT_NEAR(d, params.minDensity, 1e-3f);
}

TEST(LightDensity, AShadowEdgeAsksForTexelsOnItsSurfaceAlone) {
  const PilotRoom room;
  // The floor dark beyond x = 1.95 (a step between two texel centres); every other surface evenly lit.
  const auto light = room.lit([](glm::vec3 x, glm::vec3 n) { return n.z > 0.5f && x.x > 1.95f ? 0.1f : 1.0f; });
  LightDensityParams params;
  const std::vector<float> density = lightDensity(room.pilot, light, room.scene.triangles.size(), params);
  EXPECT_GT(room.faceDensity(density, kFloor), 2.0f * params.minDensity);
  EXPECT_FLOAT_EQ(room.faceDensity(density, kCeiling), params.minDensity);
  EXPECT_FLOAT_EQ(room.faceDensity(density, kWallX), params.minDensity);
  // A harsher tolerance asks for more, up to the limit.
  params.tolerance = 0.001f;
  EXPECT_FLOAT_EQ(room.faceDensity(lightDensity(room.pilot, light, room.scene.triangles.size(), params), kFloor),
                  params.maxDensity);
}

TEST(LightDensity, CurvedLightGetsTheSpacingItsBendNeeds) {
  const PilotRoom room;
  // On the floor B = 10 + c (x − 2)²: B'' = 2c everywhere, and over x in [0, 4] the mean of (B + f)² is
  // (10 + f)² + (8/3)(10 + f) c + (16/5) c², f the floor term (5 % of the mean light, ≈ 0.5). The need
  // is √(2c / (8 tol RMS(B + f))) texels per metre.
  for (float c : {0.5f, 2.0f, 8.0f}) {
    const auto light = room.lit(
        [c](glm::vec3 x, glm::vec3 n) { return n.z > 0.5f ? 10.0f + c * (x.x - 2.0f) * (x.x - 2.0f) : 10.0f; });
    LightDensityParams params;
    params.minDensity = 0.5f;
    params.maxDensity = 1000.0f;
    params.tolerance = 0.02f;
    const float got =
        room.faceDensity(lightDensity(room.pilot, light, room.scene.triangles.size(), params), kFloor);
    const double a = 10.5, rms = std::sqrt(a * a + 8.0 / 3.0 * a * c + 16.0 / 5.0 * c * c);
    const double expected = std::sqrt(2.0 * c / (8.0 * 0.02 * rms));
    EXPECT_NEAR(got, expected, 0.1 * expected) << "c = " << c;
  }
}

TEST(LightDensity, DarkWigglesBelowTheFloorNeedNothing) {
  const PilotRoom room;
  // A lit ceiling (B = 10) and a floor whose light wiggles by 1e-3 of that: under the floor term.
  const auto light = room.lit([](glm::vec3 x, glm::vec3 n) {
    if (n.z < -0.5f) return 10.0f;
    return n.z > 0.5f ? 0.01f * (1.0f + 0.5f * std::sin(8.0f * x.x)) : 0.0f;
  });
  const LightDensityParams params;
  const std::vector<float> density = lightDensity(room.pilot, light, room.scene.triangles.size(), params);
  EXPECT_LT(room.faceDensity(density, kFloor), 2.0f * params.minDensity);
}

TEST(LightDensity, RefusesAPilotLightOfTheWrongSize) {
  const PilotRoom room;
  std::vector<glm::vec3> light(3);
  EXPECT_THROW(lightDensity(room.pilot, light, room.scene.triangles.size(), {}), std::invalid_argument);
}

}  // namespace
}  // namespace cpgi

namespace cpgi {
namespace {

TEST(LightDensity, OneFlatSurfaceGetsOneDensity) {
  Scene s;
  const uint32_t grey = testing::addMaterial(s, glm::vec3(0.5f)), red = testing::addMaterial(s, glm::vec3(0.7f, 0.1f, 0.1f));
  // A floor of two quads side by side (z = 0), a wall standing on the first's edge, a red quad beside the
  // second in the floor's plane, and a grey quad in the plane but apart from the rest.
  testing::addRect(s, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, grey);     // 0, 1
  testing::addRect(s, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}, grey);     // 2, 3
  testing::addRect(s, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}, grey);     // 4, 5: the wall x = 0
  testing::addRect(s, {2, 0, 0}, {1, 0, 0}, {0, 1, 0}, red);      // 6, 7
  testing::addRect(s, {5, 0, 0}, {1, 0, 0}, {0, 1, 0}, grey);     // 8, 9
  std::vector<float> density = {4, 4, 20, 20, 6, 6, 4, 4, 5, 5};
  evenOverSurfaces(s, density);
  EXPECT_EQ(density, (std::vector<float>{20, 20, 20, 20, 6, 6, 4, 4, 5, 5}));
  // Triangles not in the atlas stay out.
  std::vector<float> partly = {4, 4, 20, 20, 0, 0, 4, 4, 5, 5};
  evenOverSurfaces(s, partly);
  EXPECT_EQ(partly[4], 0.0f);
}

// A long floor with a shadow's edge on one of its eight quads: one density over all of it would take
// 6.25 times the texels of a density per quad, so each quad keeps its own (the seam gutters join them).
TEST(LightDensity, ALargeSurfaceEvenedOnlyWhereItCostsLittle) {
  Scene s;
  const uint32_t grey = testing::addMaterial(s, glm::vec3(0.5f));
  for (int i = 0; i < 8; ++i) testing::addRect(s, {float(i), 0, 0}, {1, 0, 0}, {0, 1, 0}, grey);
  std::vector<float> density(16, 4.0f);
  density[6] = density[7] = 20.0f;
  const std::vector<float> own = density;
  evenOverSurfaces(s, density);
  EXPECT_EQ(density, own);
  evenOverSurfaces(s, density, 7.0);  // allowed to grow 7 times: one density
  EXPECT_EQ(density, std::vector<float>(16, 20.0f));
}

}  // namespace
}  // namespace cpgi
