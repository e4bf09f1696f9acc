// The punctual lights' exact first shot (radiosity/lightmap/direct_light.h) against closed forms: the
// irradiance a square receives from a point above its centre integrates to I·Ω, Ω = 4 asin(a²/(a² + h²))
// the square's solid angle; shadows are hard; a directional light delivers E cosθ × area.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/lightmap/direct_light.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;
using testing::atlasAtDensity;

// A 2 m × 2 m floor (y = 0, facing up) centred on the origin.
Scene floorScene() {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addRect(s, {-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, m);
  return s;
}

TEST(DirectLight, PointAboveASquareDeliversIntensityTimesSolidAngle) {
  Scene s = floorScene();
  PunctualLight lamp;
  lamp.position = {0, 1, 0};
  lamp.intensity = {1.0f, 2.0f, 3.0f};
  s.lights.push_back(lamp);
  const LightmapAtlas atlas = atlasAtDensity(s, 64.0f);
  Context ctx;
  const DirectLight d = shootPunctualLights(s.lights, RayScene(s), atlas, ctx);
  const double omega = 4.0 * std::asin(0.5);  // a = h = 1
  EXPECT_NEAR(d.landed, 6.0 * omega, 6.0 * omega * 2e-3);
  EXPECT_EQ(d.directionalLanded, 0.0);
  // Every texel: exactly I cosθ / d² at its sample point.
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) {
      EXPECT_EQ(d.irradiance[i], glm::vec3(0.0f));
      continue;
    }
    const glm::vec3 to = lamp.position - atlas.position[i];
    const float r2 = glm::dot(to, to), cosine = to.y / std::sqrt(r2);
    EXPECT_NEAR(d.irradiance[i].b, 3.0f * cosine / r2, 1e-5f);
  }
  EXPECT_NEAR(punctualEmitted(s.lights, 0.0), 6.0 * 4.0 * std::numbers::pi, 1e-9);
}

TEST(DirectLight, OccludersCastHardShadowsAndSkippedPatchesGetNothing) {
  Scene s = floorScene();
  // A 0.5 m square blocker half-way up, over the floor's quarter x, z in [0, 0.5].
  addRect(s, {0, 0.5f, 0}, {0.5f, 0, 0}, {0, 0, 0.5f}, 0);
  PunctualLight lamp;
  lamp.position = {0, 1, 0};
  lamp.intensity = glm::vec3(1.0f);
  s.lights.push_back(lamp);
  const LightmapAtlas atlas = atlasAtDensity(s, 32.0f);
  Context ctx;
  const RayScene rays(s);
  const DirectLight d = shootPunctualLights(s.lights, rays, atlas, ctx);
  size_t shadowed = 0, lit = 0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    const glm::vec3 p = atlas.position[i];
    if (atlas.patch[i] < 0 || atlas.normal[i].y < 0.5f || p.y > 0.1f) continue;
    // The blocker's shadow from (0, 1, 0) on y = 0 is x, z in [0, 1]; stay clear of its edges.
    const bool inside = p.x > 0.05f && p.x < 0.95f && p.z > 0.05f && p.z < 0.95f;
    const bool outside = p.x < -0.05f || p.z < -0.05f;
    if (inside) {
      EXPECT_EQ(d.irradiance[i], glm::vec3(0.0f));
      ++shadowed;
    }
    if (outside) {
      EXPECT_GT(d.irradiance[i].r, 0.0f);
      ++lit;
    }
  }
  EXPECT_GT(shadowed, 100u);
  EXPECT_GT(lit, 100u);
  std::vector<char> skip(atlas.patches.size(), 1);
  const DirectLight none = shootPunctualLights(s.lights, rays, atlas, ctx, skip);
  EXPECT_EQ(none.landed, 0.0);
}

TEST(DirectLight, DirectionalDeliversIrradianceTimesCosineTimesArea) {
  Scene s = floorScene();
  PunctualLight sun;
  sun.kind = PunctualLight::Kind::Directional;
  sun.direction = glm::normalize(glm::vec3(1, -1, 0));
  sun.intensity = glm::vec3(2.0f);
  s.lights.push_back(sun);
  const LightmapAtlas atlas = atlasAtDensity(s, 8.0f);
  Context ctx;
  const DirectLight d = shootPunctualLights(s.lights, RayScene(s), atlas, ctx);
  const double expected = 3.0 * 2.0 * std::sqrt(0.5) * 4.0;  // RGB × E × cos 45° × 4 m²
  EXPECT_NEAR(d.landed, expected, expected * 1e-5);
  EXPECT_DOUBLE_EQ(d.directionalLanded, d.landed);
  EXPECT_DOUBLE_EQ(punctualEmitted(s.lights, d.directionalLanded), d.landed);  // no escaped sunlight
}

}  // namespace
}  // namespace cpgi
