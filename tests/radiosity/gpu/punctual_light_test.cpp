// KHR_lights_punctual in the progressive solve: the exact first shot (radiosity/lightmap/direct_light.h)
// enters as light already shot, so the bookkeeping counts the lights' power as emitted (emitted = absorbed
// + escaped + unshot, nothing created), and the solve then bounces it as usual. The white furnace with a
// point lamp: a closed box of albedo ρ reflects in all ρΦ/(1 − ρ), Σ B a over its walls.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;

struct Solved {
  LightmapAtlas atlas;
  SolveResult result;
};

Solved solve(const Scene& scene, float density, double unshot, const SolveControls& controls = {}) {
  Context ctx;
  EglContext context(ctx);
  AtlasParams atlasParams;
  atlasParams.density = density;
  Solved s;
  s.atlas = buildAtlas(scene, findQuads(scene), atlasParams, ctx);
  SolverParams params;
  params.unshotFraction = unshot;
  s.result = solveProgressive(scene, s.atlas, params, context, ctx, controls);
  return s;
}

Scene furnaceWithALamp(float albedo, PunctualLight lamp) {
  Scene s;
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(2.0f), addMaterial(s, glm::vec3(albedo)));
  s.lights.push_back(lamp);
  return s;
}

TEST(PunctualLights, WhiteFurnaceWithAPointLamp) {
  PunctualLight lamp;
  lamp.position = {0.7f, 1.3f, 1.1f};  // off-centre: the walls are lit unevenly
  lamp.intensity = glm::vec3(1.0f, 2.0f, 0.5f);
  const float rho = 0.5f;
  const Solved s = solve(furnaceWithALamp(rho, lamp), 8.0f, 1e-4);
  const EnergyTotals& e = s.result.energy;
  const double power = 4.0 * std::numbers::pi * 3.5;  // R + G + B
  EXPECT_NEAR(e.emitted, power, power * 1e-4);
  EXPECT_LE(e.created, 2e-3 * e.emitted);
  EXPECT_NEAR(e.absorbed + e.unshot + e.escaped(), e.emitted, e.emitted * 1e-4);
  EXPECT_GE(e.escaped(), -2e-3 * e.emitted);
  EXPECT_LE(e.escaped(), 2e-2 * e.emitted);  // a closed box: only form-factor error escapes
  ASSERT_FALSE(s.result.history.empty());
  // Before the first reflector shot: the lamp's shot alone, received in full (closed box) by texel
  // quadrature.
  EXPECT_NEAR(s.result.history.front().received, power, power * 2e-3);
  EXPECT_NEAR(s.result.history.front().shot, power, power * 1e-9);
  glm::dvec3 reflected(0.0);
  for (size_t i = 0; i < s.atlas.texelCount(); ++i)
    reflected += glm::dvec3(s.result.radiosity[i]) * double(s.atlas.area[i]);
  const double want = rho / (1.0 - rho) * 4.0 * std::numbers::pi;  // per unit intensity
  EXPECT_NEAR(reflected.r / want, 1.0, 0.02);
  EXPECT_NEAR(reflected.g / want, 2.0, 0.04);
  EXPECT_NEAR(reflected.b / want, 0.5, 0.01);
}

TEST(PunctualLights, DirectLightIsReadBackAsReceivedIrradiance) {
  PunctualLight lamp;
  lamp.position = {1.0f, 1.0f, 1.0f};
  lamp.intensity = glm::vec3(1.0f);
  // Albedo 0: nothing bounces, so what each texel received is the lamp's I cosθ/d² at its sample point,
  // and its radiosity stays 0. At 4 texels/m the texel centres of this closed box sum to 0.4 % more than
  // the lamp emits: the shot is scaled back to its power (no light made up), hence 0.5 %.
  const Solved s = solve(furnaceWithALamp(0.0f, lamp), 4.0f, 1e-2, SolveControls{.readTransfer = true});
  EXPECT_EQ(s.result.shots, 0);
  size_t checked = 0;
  for (size_t i = 0; i < s.atlas.texelCount(); ++i) {
    if (s.atlas.patch[i] < 0) continue;
    const glm::vec3 to = lamp.position - s.atlas.position[i];
    const float r2 = glm::dot(to, to), cosine = glm::dot(to, s.atlas.normal[i]) / std::sqrt(r2);
    EXPECT_NEAR(s.result.incident[i].g, cosine / r2, 5e-3f * cosine / r2);
    EXPECT_EQ(s.result.radiosity[i], glm::vec3(0.0f));
    ++checked;
  }
  EXPECT_GT(checked, 300u);
  EXPECT_NEAR(s.result.energy.absorbed, s.result.energy.emitted, s.result.energy.emitted * 1e-4);
  EXPECT_LE(s.result.energy.absorbed, s.result.energy.emitted * (1.0 + 1e-6));
}

TEST(PunctualLights, SpotLightsOnlyInsideItsCone) {
  PunctualLight spot;
  spot.kind = PunctualLight::Kind::Spot;
  spot.position = {1.0f, 1.9f, 1.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};  // straight down at the floor, 1.9 m below
  spot.innerCone = 0.2f, spot.outerCone = 0.3f;
  spot.intensity = glm::vec3(1.0f);
  const Solved s = solve(furnaceWithALamp(0.0f, spot), 8.0f, 1e-2, SolveControls{.readTransfer = true});
  const float reach = 1.9f * std::tan(0.3f);  // the outer cone's radius on the floor
  for (size_t i = 0; i < s.atlas.texelCount(); ++i) {
    if (s.atlas.patch[i] < 0) continue;
    const glm::vec3 p = s.atlas.position[i];
    const float r = glm::length(glm::vec2(p.x - 1.0f, p.z - 1.0f));
    if (p.y < 0.01f && r < 1.9f * std::tan(0.2f) * 0.95f) {
      EXPECT_GT(s.result.incident[i].r, 0.2f);
    }
    if (p.y > 0.01f || r > reach * 1.05f) {
      EXPECT_EQ(s.result.incident[i].r, 0.0f);
    }
  }
}

}  // namespace
}  // namespace cpgi
