// Light probes (issue 48 item 5, `bake --probes`): placed in every room's empty space and named by it,
// written to probes.json and baked.glb's extras, and exact where the answer is known (a closed room of
// uniform radiosity: E = B for every normal).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <numbers>
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
    EXPECT_EQ(p["sh_l4"].size(), 9u);
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

// Under one small lamp in a black room, the irradiance at a probe is the lamp's alone and known (the lamp
// summed as 40 × 40 points): nearly a point light, the hardest case for truncated SH, whose L2 is 6 % of
// the peak too bright facing it and 9 % beside it. Per probe, the RMS error over the axes and diagonals
// over their mean irradiance (a quarter of the peak: only the upper normals see the lamp): band 4 halves
// L2's, at the median and at the worst probe.
TEST(LightProbes, BandFourHalvesTheErrorOfAPointLikeLamp) {
  Scene scene;
  const uint32_t black = testing::addMaterial(scene, glm::vec3(0.0f));
  const glm::vec3 emission(100.0f);
  const uint32_t lamp = testing::addMaterial(scene, glm::vec3(0.0f), emission);
  testing::addClosedBox(scene, glm::vec3(0.0f), glm::vec3(4.0f, 3.0f, 4.0f), black);
  const glm::vec3 corner(1.9f, 2.99f, 1.9f), u(0.2f, 0.0f, 0.0f), v(0.0f, 0.0f, 0.2f);
  testing::addRect(scene, corner, u, v, lamp, 1);  // u × v points down
  Context ctx;
  AtlasParams a;
  a.density = 10.0f;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), a, ctx);
  std::vector<glm::vec3> radiosity(atlas.texelCount(), glm::vec3(0.0f));
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0) radiosity[i] = atlas.emission[i];
  const LightProbes probes = gatherLightProbes(scene, CellGraph{}, atlas, radiosity, {}, ctx);
  ASSERT_GE(probes.probes.size(), 8u);
  std::vector<glm::vec3> normals = {glm::vec3(1, 0, 0),  glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                    glm::vec3(0, -1, 0), glm::vec3(0, 0, 1),  glm::vec3(0, 0, -1)};
  for (int k = 0; k < 8; ++k)
    normals.push_back(glm::normalize(glm::vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1)));
  std::vector<double> errorsL2, errorsL4;
  for (const LightProbe& p : probes.probes) {
    double e2 = 0.0, e4 = 0.0, mean = 0.0;
    for (const glm::vec3& n : normals) {
      double want = 0.0;  // radiance E/π over the lamp's area, seen from the probe
      for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) {
          const glm::vec3 q = corner + (float(i) + 0.5f) / 40.0f * u + (float(j) + 0.5f) / 40.0f * v;
          const glm::vec3 w = q - p.position;
          const double r2 = glm::dot(w, w), cosLamp = glm::normalize(w).y;
          want += emission.g / std::numbers::pi * (0.04 / 1600.0) * cosLamp *
                  std::max(0.0f, glm::dot(n, glm::normalize(w))) / r2;
        }
      const double l2 = shIrradiance(p.sh, n).g, l4 = l2 + shIrradianceBand4(p.sh4, n).g;
      e2 += (l2 - want) * (l2 - want), e4 += (l4 - want) * (l4 - want), mean += want;
    }
    mean /= double(normals.size());
    errorsL2.push_back(std::sqrt(e2 / double(normals.size())) / mean);
    errorsL4.push_back(std::sqrt(e4 / double(normals.size())) / mean);
  }
  std::sort(errorsL2.begin(), errorsL2.end());
  std::sort(errorsL4.begin(), errorsL4.end());
  const size_t median = errorsL2.size() / 2;
  std::cout << probes.probes.size()
            << " probes, error (RMS over 14 normals / their mean), median and worst: L2 " << errorsL2[median]
            << ", " << errorsL2.back() << "; L2 + band 4 " << errorsL4[median] << ", " << errorsL4.back()
            << "\n";
  EXPECT_LT(errorsL4[median], 0.5 * errorsL2[median]);
  EXPECT_LT(errorsL4.back(), 0.6 * errorsL2.back());
}

}  // namespace
}  // namespace cpgi
