// The sky model (core/sky.h): its radiance integrates to the closed-form horizontal irradiance, a sky
// given by irradiance gets the zenith radiance that gives it back, the ground reflects sky and sun, the
// sun becomes a directional light, and values out of range are refused naming their parameter.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene.h"
#include "core/sky.h"

namespace cpgi {
namespace {

// ∫ L cos θ dω over the upper hemisphere, by the midpoint rule in θ (L depends on θ alone).
double integrateUpper(const Sky& sky) {
  const int n = 2000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double theta = (k + 0.5) * (std::numbers::pi / 2) / n;
    const glm::vec3 dir(float(std::sin(theta)), float(std::cos(theta)), 0.0f);
    sum += skyRadiance(sky, dir) * std::cos(theta) * std::sin(theta);
  }
  return 2.0 * std::numbers::pi * sum * (std::numbers::pi / 2) / n;
}

TEST(Sky, RadianceIntegratesToTheHorizontalIrradiance) {
  for (Sky::Kind kind : {Sky::Kind::Uniform, Sky::Kind::CieOvercast}) {
    Sky sky;
    sky.kind = kind, sky.zenithRadiance = 2.0f, sky.groundRadiance = 9.0f;
    EXPECT_NEAR(integrateUpper(sky), horizontalIrradiance(kind, 2.0f), 1e-4) << skyKindName(kind);
    EXPECT_EQ(skyRadiance(sky, {0.0f, -1.0f, 0.0f}), 9.0f);
  }
  Sky overcast;
  overcast.kind = Sky::Kind::CieOvercast, overcast.zenithRadiance = 3.0f;
  EXPECT_FLOAT_EQ(skyRadiance(overcast, {0, 1, 0}), 3.0f);
  EXPECT_NEAR(skyRadiance(overcast, {1, 1e-6f, 0}), 1.0f, 1e-5f);  // a third at the horizon
}

TEST(Sky, MadeFromIrradianceGroundAndSun) {
  SkyRequest r;
  r.kind = Sky::Kind::CieOvercast;
  r.horizontalIrradiance = 70.0f;
  r.towardsSun = glm::vec3(0.0f, 1.0f, 1.0f);
  r.sunIrradiance = 200.0f;
  Scene scene;
  applySky(r, scene);
  EXPECT_NEAR(horizontalIrradiance(scene.sky.kind, scene.sky.zenithRadiance), 70.0f, 1e-3f);
  const float sunOnGround = 200.0f / std::sqrt(2.0f);
  EXPECT_NEAR(scene.sky.groundRadiance, 0.2f * (70.0f + sunOnGround) / std::numbers::pi_v<float>, 1e-4f);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].kind, PunctualLight::Kind::Directional);
  EXPECT_NEAR(scene.lights[0].direction.z, -1.0f / std::sqrt(2.0f), 1e-6f);
  EXPECT_TRUE(scene.hasLight());

  SkyRequest none;  // the default: no sky, no sun, nothing lit
  Scene dark;
  applySky(none, dark);
  EXPECT_FALSE(dark.sky.lights());
  EXPECT_FALSE(dark.hasLight());
  r.groundAlbedo.reset();
  EXPECT_EQ(makeSky(r).groundRadiance, 0.0f);
}

TEST(Sky, OutOfRangeValuesAreRefusedByName) {
  auto refused = [](SkyRequest r) -> std::string {
    try {
      makeSky(r);
    } catch (const InputError& e) {
      return e.where();
    }
    return "accepted";
  };
  SkyRequest r;
  r.kind = Sky::Kind::Uniform;
  SkyRequest both = r;
  both.zenithRadiance = 1.0f, both.horizontalIrradiance = 1.0f;
  EXPECT_EQ(refused(both), "sky zenith");
  SkyRequest negative = r;
  negative.horizontalIrradiance = -1.0f;
  EXPECT_EQ(refused(negative), "sky irradiance");
  SkyRequest low = r;
  low.towardsSun = glm::vec3(1.0f, -0.1f, 0.0f), low.sunIrradiance = 100.0f;
  EXPECT_EQ(refused(low), "sun");
  SkyRequest nan = r;
  nan.towardsSun = glm::vec3(NAN, 1.0f, 0.0f);
  EXPECT_EQ(refused(nan), "sun");
  SkyRequest bright = r;
  bright.groundAlbedo = 1.5f;
  EXPECT_EQ(refused(bright), "ground albedo");
  SkyRequest noSky;
  noSky.horizontalIrradiance = 10.0f;
  EXPECT_EQ(refused(noSky), "sky");
}

}  // namespace
}  // namespace cpgi
