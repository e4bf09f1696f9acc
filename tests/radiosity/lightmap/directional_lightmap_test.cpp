// The directional lightmap's gather (issue 48 item 4): texels lit by one lamp get an irradiance vector
// pointing at it; the vector at the texel's normal is the irradiance it is scaled to; the SH basis and
// its irradiance evaluation against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/quads.h"
#include "radiosity/lightmap/directional_lightmap.h"
#include "radiosity/lightmap/spherical_harmonics.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;

constexpr float kPi = std::numbers::pi_v<float>;

float degreesBetween(const glm::vec3& a, const glm::vec3& b) {
  const float c = glm::dot(glm::normalize(a), glm::normalize(b));
  return std::acos(std::clamp(c, -1.0f, 1.0f)) * 180.0f / kPi;
}

// A 4 m × 4 m grey floor under one small lamp facing down, off its centre, nothing else: every floor
// texel's light comes from the lamp alone.
struct LampOverFloor {
  Scene scene;
  LightmapAtlas atlas;
  glm::vec3 lampCentre{1.0f, 2.2f, -0.5f};
  LampOverFloor() {
    const uint32_t floor = addMaterial(scene, glm::vec3(0.5f));
    const uint32_t lamp = addMaterial(scene, glm::vec3(0.0f), glm::vec3(100.0f, 60.0f, 30.0f));
    addRect(scene, {-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, floor);  // normal (4,0,0)×(0,0,−4) = +y
    const float h = 0.1f;
    addRect(scene, lampCentre + glm::vec3(-h, 0, -h), {2 * h, 0, 0}, {0, 0, 2 * h}, lamp);  // normal −y
    Context ctx;
    AtlasParams p;
    p.density = 4.0f;
    atlas = buildAtlas(scene, findQuads(scene), p, ctx);
  }
};

TEST(DirectionalLightmap, ATexelLitByOneLampPointsAtIt) {
  LampOverFloor s;
  ASSERT_EQ(s.scene.triangles[0].geometricNormal().y, 1.0f);
  // The lamp's radiosity is its emission (albedo 0); the floor's does not reach the floor.
  // Irradiance 1 on the floor (the direction does not depend on it), none on the lamp.
  std::vector<glm::vec3> radiosity = s.atlas.emission, irradiance(s.atlas.texelCount(), glm::vec3(0.0f));
  for (size_t i = 0; i < s.atlas.texelCount(); ++i)
    if (s.atlas.patch[i] >= 0 && s.atlas.normal[i].y > 0.5f) irradiance[i] = glm::vec3(1.0f);
  Context ctx;
  const DirectionalLightmap map = gatherDirectionalLightmap(s.scene, s.atlas, radiosity, irradiance, {}, ctx);
  size_t floorTexels = 0;
  float worst = 0.0f;
  for (size_t i = 0; i < s.atlas.texelCount(); ++i) {
    if (s.atlas.patch[i] < 0 || s.atlas.normal[i].y < 0.5f) continue;
    const std::array<glm::vec3, 4> sh = texelSh(map, i);
    const glm::vec3 towardsLamp = s.lampCentre - s.atlas.position[i];
    for (int c = 0; c < 3; ++c) {
      const glm::vec3 v = shIrradianceVector(sh, c);
      worst = std::max(worst, degreesBetween(v, towardsLamp));
      // Scaled to the irradiance it was given, 1, at the texel's normal (float rounding).
      EXPECT_NEAR(glm::dot(v, s.atlas.normal[i]), 1.0f, 1e-4f);
    }
    ++floorTexels;
  }
  EXPECT_GE(floorTexels, 200u);
  EXPECT_EQ(map.undirected, 0u);
  // The lamp is 0.2 m across and 1.2–2.2 m away: its centre seen within its own angular radius at worst.
  EXPECT_LT(worst, 3.0f) << "worst angle between the irradiance vector and the lamp's centre";
  std::cout << "worst angle to the lamp: " << worst << " degrees over " << floorTexels << " texels\n";
}

TEST(DirectionalLightmap, GatheredIrradianceMatchesTheLampsExactLight) {
  // The gather's own irradiance (before scaling) against the lamp's closed form at the floor below it:
  // a small square lamp at height h right above, E ≈ Le · A / (π h²) (point form, A ≪ h²).
  LampOverFloor s;
  std::vector<glm::vec3> radiosity = s.atlas.emission, irradiance(s.atlas.texelCount(), glm::vec3(1.0f));
  Context ctx;
  const DirectionalLightmap map = gatherDirectionalLightmap(s.scene, s.atlas, radiosity, irradiance, {}, ctx);
  int checked = 0;
  for (size_t i = 0; i < s.atlas.texelCount(); ++i) {
    if (s.atlas.patch[i] < 0 || s.atlas.normal[i].y < 0.5f) continue;
    const glm::vec3 d = s.lampCentre - s.atlas.position[i];
    const float r2 = glm::dot(d, d), cosine = d.y / std::sqrt(r2);
    const glm::vec3 exact = glm::vec3(100.0f, 60.0f, 30.0f) * 0.04f * cosine * cosine / (kPi * r2);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(map.gathered[i][c], exact[c], 0.02f * exact[c]) << "texel " << i;
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

TEST(SphericalHarmonics, IrradianceOfAUniformSkyIsPiL) {
  // Uniform radiance L over the sphere: L00 = L·4π·Y00, the rest 0; E = πL for any normal (L2 included).
  std::array<glm::vec3, 9> sh{};
  sh[0] = glm::vec3(4.0f * kPi * kShY00);
  for (const glm::vec3 n : {glm::vec3(0, 1, 0), glm::normalize(glm::vec3(1, -2, 3))})
    EXPECT_NEAR(shIrradiance(sh, n).g, kPi, 1e-4f);
}

TEST(SphericalHarmonics, OneDirectionsVectorIrradianceIsItsCosine) {
  // Light Φ (W/m²) from one direction w: L1m = Φ Y1m(w). V = Φ w, and the L1 evaluation
  // E(n) = Φ/4 + Φ (w · n)/2 (Ramamoorthi & Hanrahan's L1 truncation).
  const glm::vec3 w = glm::normalize(glm::vec3(0.3f, 0.9f, -0.2f)), n(0, 1, 0);
  const std::array<float, 9> y = shBasis(w);
  std::array<glm::vec3, 4> sh{};
  for (size_t k = 0; k < 4; ++k) sh[k] = glm::vec3(2.0f * y[k]);
  const glm::vec3 v = shIrradianceVector(sh, 1);
  EXPECT_NEAR(glm::length(v - 2.0f * w), 0.0f, 1e-4f);
  EXPECT_NEAR(shIrradiance(sh, n).g, 2.0f * (0.25f + 0.5f * glm::dot(w, n)), 1e-4f);
}

}  // namespace
}  // namespace cpgi
