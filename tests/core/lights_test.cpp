// KHR_lights_punctual: the falloff every back end evaluates (core/lights.h), the glTF reader's lights
// (placement, units, validation), the writer's round trip, and --emit / --albedo by material name.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/lights.h"
#include "core/scene_io.h"
#include "tests/support/expect_vec.h"
#include "tests/support/glb_builder.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using nlohmann::json;

using test::expectNear;

TEST(PunctualLight, PointIsInverseSquareTimesTheReceiverCosine) {
  PunctualLight p;
  p.position = {0, 2, 0};
  p.intensity = glm::vec3(4.0f);
  const LightArrival below = lightArrival(p, {0, 0, 0}, {0, 1, 0});
  expectNear(below.irradiance, glm::vec3(1.0f));  // 4 W/sr / 2² m²
  EXPECT_FLOAT_EQ(below.distance, 2.0f);
  expectNear(below.toLight, {0, 1, 0});
  // 45° off: cos 45° / (2√2)² = 0.707 / 8.
  expectNear(lightArrival(p, {2, 0, 0}, {0, 1, 0}).irradiance, glm::vec3(4.0f * std::sqrt(0.5f) / 8.0f));
  expectNear(lightArrival(p, {0, 0, 0}, {0, -1, 0}).irradiance, glm::vec3(0.0f));  // facing away
  p.range = 4.0f;  // glTF's window (1 − (d/r)⁴)² at d = 2: (15/16)²
  expectNear(below.irradiance * (225.0f / 256.0f), lightArrival(p, {0, 0, 0}, {0, 1, 0}).irradiance);
}

TEST(PunctualLight, SpotFallsOffBetweenItsCones) {
  PunctualLight s;
  s.kind = PunctualLight::Kind::Spot;
  s.innerCone = 0.2f, s.outerCone = 0.4f;
  EXPECT_FLOAT_EQ(spotFactor(s, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(spotFactor(s, std::cos(0.2f)), 1.0f);
  EXPECT_FLOAT_EQ(spotFactor(s, std::cos(0.4f)), 0.0f);
  EXPECT_FLOAT_EQ(spotFactor(s, std::cos(0.6f)), 0.0f);
  const float mid = (std::cos(0.2f) + std::cos(0.4f)) / 2;
  EXPECT_NEAR(spotFactor(s, mid), 0.25f, 1e-4f);  // the ramp squared
  // Its power is ∫ I f dΩ: compare the closed form with a sum over rings of the sphere.
  s.intensity = glm::vec3(1.0f, 2.0f, 3.0f);
  double sum = 0.0;
  const int rings = 200000;
  for (int i = 0; i < rings; ++i) {
    const double c = 1.0 - (i + 0.5) * 2.0 / rings;  // cos θ, uniform in [−1, 1]
    sum += spotFactor(s, float(c)) * 2.0 / rings * 2.0 * std::numbers::pi;
  }
  EXPECT_NEAR(punctualPower(s).g, 2.0 * sum, 2e-3 * 2.0 * sum);
  PunctualLight p;
  p.intensity = glm::vec3(1.0f);
  EXPECT_NEAR(punctualPower(p).r, 4.0 * std::numbers::pi, 1e-9);
  p.kind = PunctualLight::Kind::Directional;
  EXPECT_EQ(punctualPower(p).r, 0.0);
}

TEST(PunctualLight, DirectionalIsParallelAndUniform) {
  PunctualLight d;
  d.kind = PunctualLight::Kind::Directional;
  d.direction = glm::normalize(glm::vec3(0, -1, -1));
  d.intensity = glm::vec3(2.0f);
  const LightArrival a = lightArrival(d, {5, 0, 7}, {0, 1, 0});
  EXPECT_TRUE(std::isinf(a.distance));
  expectNear(a.irradiance, glm::vec3(2.0f * std::sqrt(0.5f)));
  expectNear(lightArrival(d, {-50, 3, 1}, {0, 1, 0}).irradiance, a.irradiance);
}

// A floor triangle and a glTF document with lights attached to nodes.
test::GlbBuilder sceneWithLights(const json& lights) {
  test::GlbBuilder g;
  g.addNode({{"name", "floor"}, {"mesh", g.addMesh({0, 0, 0, 0, 0, 1, 1, 0, 0})}});
  g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  g.doc["extensions"]["KHR_lights_punctual"]["lights"] = lights;
  return g;
}

LoadedScene load(const test::GlbBuilder& g, const LoadOptions& options = {}) {
  test::TempDir dir;
  g.writeGlb(dir / "lit.glb");
  return loadScene(dir / "lit.glb", options);
}

std::string loadError(const test::GlbBuilder& g, const LoadOptions& options = {}) {
  test::TempDir dir;
  g.writeGlb(dir / "lit.glb");
  try {
    loadScene(dir / "lit.glb", options);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir / "lit.glb");  // the file is named
    return e.problem();
  }
  return "no error";
}

TEST(GltfLights, PlacedByTheirNodesInCpgisUnits) {
  test::GlbBuilder g = sceneWithLights(
      {{{"type", "point"}, {"name", "bulb"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 683.0}},
       {{"type", "spot"},
        {"intensity", 1366.0},
        {"range", 9.0},
        {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.3}}}},
       {{"type", "directional"}, {"name", "sun"}, {"intensity", 6830.0}}});
  g.doc["extensionsRequired"] = {"KHR_lights_punctual"};
  const double s = std::sqrt(0.5);
  // The point light under a translated parent; the spot turned 90° about +y (its −Z becomes −X); the sun
  // turned −90° about +x (its −Z becomes −Y: straight down).
  const int bulb = g.addNode({{"name", "bulb-node"},
                              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
                              {"translation", {0, 1, 0}}},
                             false);
  g.addNode({{"name", "parent"}, {"translation", {1, 2, 3}}, {"children", {bulb}}});
  g.addNode({{"name", "spot-node"},
             {"translation", {0, 2, 0}},
             {"rotation", {0, s, 0, s}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  g.addNode({{"name", "sun-node"},
             {"rotation", {-s, 0, 0, s}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  const Scene scene = load(g).scene;
  ASSERT_EQ(scene.lights.size(), 3u);
  const PunctualLight& point = scene.lights[0];
  EXPECT_EQ(point.kind, PunctualLight::Kind::Point);
  EXPECT_EQ(point.name, "bulb");
  expectNear(point.position, {1, 3, 3});
  expectNear(point.intensity, {1.0f, 0.5f, 0.25f});  // 683 cd = 1 W/sr
  const PunctualLight& spot = scene.lights[1];
  EXPECT_EQ(spot.kind, PunctualLight::Kind::Spot);
  EXPECT_EQ(spot.name, "spot-node");  // unnamed light: its node's name
  expectNear(spot.direction, {-1, 0, 0});
  expectNear(spot.intensity, glm::vec3(2.0f));
  EXPECT_FLOAT_EQ(spot.innerCone, 0.1f);
  EXPECT_FLOAT_EQ(spot.outerCone, 0.3f);
  EXPECT_FLOAT_EQ(spot.range, 9.0f);
  const PunctualLight& sun = scene.lights[2];
  EXPECT_EQ(sun.kind, PunctualLight::Kind::Directional);
  expectNear(sun.direction, {0, -1, 0});
  expectNear(sun.intensity, glm::vec3(10.0f));  // 6830 lux = 10 W/m²
  EXPECT_TRUE(scene.hasLight());
}

TEST(GltfLights, BadLightsAreRefusedNamingTheFileAndTheLight) {
  auto errorFor = [](const json& light, const json& reference = {{"light", 0}}) {
    test::GlbBuilder g = sceneWithLights(json::array({light}));
    g.addNode({{"name", "lamp"}, {"extensions", {{"KHR_lights_punctual", reference}}}});
    return loadError(g);
  };
  EXPECT_EQ(errorFor({{"type", "point"}, {"name", "l"}, {"intensity", -1.0}}),
            "light 'l': intensity -1 is negative or not finite");
  EXPECT_EQ(errorFor({{"type", "point"}, {"name", "l"}, {"color", {1, -1, 1}}}),
            "light 'l': color is negative or not finite");
  EXPECT_EQ(errorFor({{"type", "area"}, {"name", "l"}}),
            "light 'l': unknown type 'area' (expected point, spot or directional)");
  EXPECT_EQ(
      errorFor(
          {{"type", "spot"}, {"name", "l"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.4}}}}),
      "light 'l': spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
  EXPECT_EQ(errorFor({{"type", "spot"}, {"name", "l"}, {"spot", {{"outerConeAngle", 2.0}}}}),
            "light 'l': spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
  EXPECT_EQ(errorFor({{"type", "point"}}, {{"light", 3}}), "node 'lamp': light 3 does not exist");
  EXPECT_EQ(errorFor({{"type", "point"}}, {{"lamp", 0}}),
            "node 'lamp': KHR_lights_punctual without a light index");
  // 1e30 cd: 1.8e28 W, far past what the solver's floats can carry.
  EXPECT_NE(errorFor({{"type", "point"}, {"intensity", 1e30}}).find("more than 1e+20 W"), std::string::npos);
  test::GlbBuilder flat = sceneWithLights({{{"type", "point"}}});
  flat.addNode(
      {{"name", "flat"}, {"scale", {0, 0, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  EXPECT_EQ(loadError(flat), "node 'flat': the transform of light 'flat' is degenerate or not finite");
}

TEST(GltfLights, WrittenAndReadBackUnchanged) {
  Scene scene;
  scene.materials.push_back(Material{"floor", glm::vec3(0.5f), glm::vec3(0.0f)});
  Triangle t;
  t.p = {glm::vec3(0, 0, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)};
  t.n = {glm::vec3(0, 1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)};
  scene.triangles.push_back(t);
  scene.nodePaths.push_back("floor");
  PunctualLight spot;
  spot.kind = PunctualLight::Kind::Spot;
  spot.name = "spot";
  spot.position = {1, 2, 3};
  spot.direction = glm::normalize(glm::vec3(1, -1, 0.5f));
  spot.intensity = {3, 2, 1};
  spot.innerCone = 0.2f, spot.outerCone = 0.5f;
  spot.range = 7.0f;
  PunctualLight sun;
  sun.kind = PunctualLight::Kind::Directional;
  sun.name = "sun";
  sun.direction = {0, 0, 1};  // opposite to a node's −Z: the rotation must still be found
  sun.intensity = glm::vec3(5.0f);
  scene.lights = {spot, sun};
  test::TempDir dir;
  writeGltf(dir / "lights.glb", scene);
  const Scene back = loadScene(dir / "lights.glb").scene;
  ASSERT_EQ(back.lights.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.lights[i].kind, scene.lights[i].kind);
    EXPECT_EQ(back.lights[i].name, scene.lights[i].name);
    expectNear(back.lights[i].position, scene.lights[i].position, 1e-5f);
    expectNear(back.lights[i].direction, scene.lights[i].direction, 1e-5f);
    expectNear(back.lights[i].intensity, scene.lights[i].intensity, 1e-4f);
    EXPECT_NEAR(back.lights[i].innerCone, scene.lights[i].innerCone, 1e-6f);
    EXPECT_NEAR(back.lights[i].outerCone, scene.lights[i].outerCone, 1e-6f);
    EXPECT_NEAR(back.lights[i].range, scene.lights[i].range, 1e-6f);
  }
}

TEST(MaterialOverrides, EmitAndAlbedoByNameOrAnErrorNamingTheFile) {
  test::GlbBuilder g;
  const int wall =
      g.addMaterial({{"name", "wall"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
  const int lamp = g.addMaterial({{"name", "lamp shade"}});
  g.addNode({{"name", "w"}, {"mesh", g.addMesh({0, 0, 0, 0, 0, 1, 1, 0, 0}, {}, wall)}});
  g.addNode({{"name", "l"}, {"mesh", g.addMesh({0, 1, 0, 1, 1, 0, 0, 1, 1}, {}, lamp)}});
  LoadOptions options;
  options.overrides.push_back({"lamp shade", glm::vec3(100.0f), std::nullopt});
  options.overrides.push_back({"wall", std::nullopt, glm::vec3(0.7f, 0.1f, 0.1f)});
  const Scene scene = load(g, options).scene;
  ASSERT_TRUE(scene.hasLight());
  for (const Material& m : scene.materials) {
    if (m.name == "lamp shade") expectNear(m.emission, glm::vec3(100.0f));
    if (m.name == "wall") expectNear(m.albedo, {0.7f, 0.1f, 0.1f});
  }
  EXPECT_NEAR(scene.emittedPower().r, 50.0f, 1e-3f);  // 0.5 m² at 100 W/m²

  LoadOptions unknown;
  unknown.overrides.push_back({"lamp", glm::vec3(1.0f), std::nullopt});
  test::TempDir dir;
  g.writeGlb(dir / "lit.glb");
  try {
    loadScene(dir / "lit.glb", unknown);
    ADD_FAILURE() << "an unknown material was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "emit");
    EXPECT_EQ(e.problem(),
              "no material named 'lamp' in " + (dir / "lit.glb") + " (it has: wall, lamp shade)");
  }
  LoadOptions tooMuch;  // an override is checked like the file's own numbers
  tooMuch.overrides.push_back({"wall", glm::vec3(1e30f), std::nullopt});
  EXPECT_THROW(loadScene(dir / "lit.glb", tooMuch), InputError);
}

}  // namespace
}  // namespace cpgi
