// Light probes (issue 48 item 5, `bake --probes`): placed in every room's empty space and named by it,
// written to probes.json and baked.glb's extras, and exact where the answer is known (a closed room of
// uniform radiosity: E = B for every normal).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "core/quads.h"
#include "radiosity/bake/light_probes.h"
#include "radiosity/lightmap/spherical_harmonics.h"
#include "scenes/seed_scenes.h"
#include "tests/radiosity/test_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

// The JSON chunk of a .glb.
nlohmann::json glbJson(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

TEST(LightProbes, EveryRoomGetsProbesInItsEmptySpaceNamedByIt) {
  test::TempDir dir;
  BakeSettings s = test::quickSeed1();
  s.output.folder = dir / "out";
  s.output.engine.probes = true;
  const SeedScene seed1 = makeSeedScene(1);
  test::bakeHere(seed1.scene, seed1.cells, s);
  std::ifstream in(dir / "out/probes.json");
  const nlohmann::json probes = nlohmann::json::parse(in);
  // seed1's rooms: 4 m × 3 m × 4 m each along x, A from 0, B from 4.2, C from 8.4 (0.2 m walls).
  std::set<std::string> rooms;
  for (const nlohmann::json& p : probes["probes"]) {
    const float x = p["position"][0], y = p["position"][1], z = p["position"][2];
    const std::string cell = p["cell"];
    rooms.insert(cell);
    const float start = cell == "A" ? 0.0f : cell == "B" ? 4.2f : 8.4f;
    EXPECT_GE(x, start + 0.25f) << cell;
    EXPECT_LE(x, start + 4.0f - 0.25f) << cell;
    EXPECT_GE(y, 0.25f);
    EXPECT_LE(y, 3.0f - 0.25f);
    EXPECT_GE(z, 0.25f);
    EXPECT_LE(z, 4.0f - 0.25f);
    EXPECT_EQ(p["sh"].size(), 9u);
  }
  EXPECT_EQ(rooms, (std::set<std::string>{"A", "B", "C"}));
  EXPECT_EQ(probes["count"], probes["probes"].size());
  EXPECT_GE(probes["probes"].size(), 3u * 3u * 3u * 3u);  // at least 3 × 3 × 3 a room at 1 m
  const nlohmann::json extras = glbJson(dir / "out/baked.glb")["extras"]["cpgi_lightmap"]["probes"];
  EXPECT_EQ(extras, probes);
  std::ifstream report(dir / "out/report.json");
  EXPECT_EQ(nlohmann::json::parse(report)["engine_lightmap"]["probes"]["count"], probes["count"]);
}

TEST(LightProbes, AClosedRoomOfUniformRadiosityGivesItAsIrradianceInEveryDirection) {
  // Inside a closed box whose every texel has radiosity B (a white furnace: emission E, albedo ρ,
  // B = E / (1 − ρ)), the radiance is B/π from every direction, so E(n) = B for every normal.
  Scene scene;
  const uint32_t m = testing::addMaterial(scene, glm::vec3(0.5f), glm::vec3(1.0f, 2.0f, 3.0f));
  testing::addClosedBox(scene, glm::vec3(0.0f), glm::vec3(3.0f, 2.5f, 4.0f), m);
  Context ctx;
  AtlasParams a;
  a.density = 4.0f;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), a, ctx);
  const glm::vec3 b = glm::vec3(1.0f, 2.0f, 3.0f) / 0.5f;
  std::vector<glm::vec3> radiosity(atlas.texelCount(), glm::vec3(0.0f));
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0) radiosity[i] = b;
  const LightProbes probes = gatherLightProbes(scene, CellGraph{}, atlas, radiosity, {}, ctx);
  ASSERT_GE(probes.probes.size(), 12u);
  for (const LightProbe& p : probes.probes) {
    EXPECT_EQ(p.cell, -1);
    for (const glm::vec3 n : {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::normalize(glm::vec3(1, 1, -1))}) {
      const glm::vec3 e = shIrradiance(p.sh, n);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], b[c], 0.02f * b[c]) << "probe at " << p.position.x;
    }
  }
}

}  // namespace
}  // namespace cpgi
