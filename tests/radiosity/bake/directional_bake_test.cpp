// The directional lightmap of a bake (issue 48 item 4, `bake --directional`): its files hold L1 SH whose
// irradiance at each texel's own normal is lightmap_irradiance.exr's; its gather, read from the baked
// radiosity by rays, finds the light the solve found; the GL and the ray engines' bakes give the same
// directions.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "radiosity/lightmap/directional_lightmap.h"
#include "radiosity/lightmap/engine_lightmap.h"
#include "radiosity/lightmap/spherical_harmonics.h"
#include "scenes/seed_scenes.h"
#include "tests/support/in_process_bake.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

BakeSettings directionalSeed1() {
  BakeSettings s = test::quickSeed1();
  s.atlas.params.texelsPerQuad = 8;
  s.output.engine.directional = true;
  return s;
}

TEST(DirectionalLightmapBake, TheIrradianceAtEachTexelsNormalIsTheIrradianceLightmap) {
  test::TempDir dir;
  BakeSettings s = directionalSeed1();
  s.output.folder = dir / "out";
  const SeedScene seed1 = makeSeedScene(1);
  const BakeResult r = test::bakeHere(seed1.scene, seed1.cells, s);
  const ImageRGB e = readExr(dir / "out/lightmap_irradiance.exr");
  std::array<ImageRGB, 4> sh;
  const std::array<const char*, 4> files = {"lightmap_sh_l0.exr", "lightmap_sh_l1y.exr",
                                            "lightmap_sh_l1z.exr", "lightmap_sh_l1x.exr"};
  for (size_t k = 0; k < 4; ++k) {
    sh[k] = readExr(dir / (std::string("out/") + files[k]));
    ASSERT_EQ(sh[k].width, r.atlas.width);
    ASSERT_EQ(sh[k].height, r.atlas.height);
  }
  double worst = 0.0;
  size_t checked = 0;
  for (size_t i = 0; i < r.atlas.texelCount(); ++i) {
    if (r.atlas.patch[i] < 0) continue;
    const std::array<glm::vec3, 4> c = {sh[0].pixels[i], sh[1].pixels[i], sh[2].pixels[i], sh[3].pixels[i]};
    for (int ch = 0; ch < 3; ++ch) {
      const glm::vec3 v = shIrradianceVector(c, ch);
      const double want = e.pixels[i][ch], got = glm::dot(v, r.atlas.normal[i]);
      // Half floats round each coefficient by 2⁻¹¹ of itself; a vector far off the normal (grazing
      // light) carries that rounding of its larger components into V · n.
      const double rounding = 2.0 * std::ldexp(glm::length(v), -11);
      const double error = std::abs(got - want) / std::max(want, 1e-6);
      EXPECT_LE(std::abs(got - want), 0.005 * want + rounding) << "texel " << i << " channel " << ch;
      worst = std::max(worst, error);
    }
    ++checked;
  }
  EXPECT_EQ(checked, r.atlas.validTexels());
  std::cout << "worst relative difference of V·n against the irradiance lightmap: " << worst << " over "
            << checked << " texels\n";

  std::ifstream in(dir / "out/report.json");
  const nlohmann::json report = nlohmann::json::parse(in)["engine_lightmap"]["directional"];
  EXPECT_EQ(report["files"].size(), 4u);
  EXPECT_EQ(report["texels"], r.atlas.validTexels());
  EXPECT_GT(report["rays"].get<double>(), 0.0);
}

// Σ a·E over the texels that emit nothing (the lamps' own texels are a gather's singular points).
double litPower(const LightmapAtlas& atlas, const std::vector<glm::vec3>& e) {
  double sum = 0.0;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0 && atlas.emission[i] == glm::vec3(0.0f))
      sum += (double(e[i].r) + e[i].g + e[i].b) * atlas.area[i];
  return sum;
}

TEST(DirectionalLightmapBake, TheGatherFindsTheLightTheSolveFound) {
  const SeedScene seed1 = makeSeedScene(1);
  const BakeResult r = test::bakeHere(seed1.scene, seed1.cells, directionalSeed1());
  const std::vector<glm::vec3> e = irradianceFromRadiosity(r.atlas, r.radiosity);
  Context ctx;
  const DirectionalLightmap map = gatherDirectionalLightmap(seed1.scene, r.atlas, r.radiosity, e, {}, ctx);
  // The gather reads the solve's radiosity, lamps by area, the rest by rays: over the rooms it finds what
  // the solve delivered, less what the solve's stop left to its ambient term, read again from the walls.
  const double ratio = litPower(r.atlas, map.gathered) / litPower(r.atlas, e);
  std::cout << "gathered / solved irradiance over the lit texels: " << ratio << "\n";
  EXPECT_NEAR(ratio, 1.0, 0.03);
  EXPECT_EQ(map.undirected, 0u);
}

TEST(DirectionalLightmapBake, TheGlAndTheRayEnginesGiveTheSameDirections) {
  const SeedScene seed1 = makeSeedScene(1);
  std::array<DirectionalLightmap, 2> maps;
  std::array<double, 2> power{};
  LightmapAtlas atlas;
  for (int k = 0; k < 2; ++k) {
    BakeSettings s = directionalSeed1();
    // Every shot by GL item buffers (the interreflection too), or every shot by rays.
    s.solver.backend = k == 0 ? Backend::Gl : Backend::Rays;
    s.solver.indirect = k == 0 ? IndirectSolver::Gpu : IndirectSolver::Rays;
    // The rays' bake opens no GL context: the shared one would be taken whatever the backend.
    Context bakeCtx;
    BakeRun run;
    run.gl = k == 0 ? &test::sharedGl() : nullptr;
    const BakeResult r = bake(seed1.scene, seed1.cells, s, bakeCtx, run);
    EXPECT_EQ(r.report["backend"], k == 0 ? "gl" : "rays");
    Context ctx;
    maps[size_t(k)] = gatherDirectionalLightmap(seed1.scene, r.atlas, r.radiosity,
                                                irradianceFromRadiosity(r.atlas, r.radiosity), {}, ctx);
    power[size_t(k)] = litPower(r.atlas, r.radiosity);
    atlas = r.atlas;
  }
  // The irradiance-weighted mean angle between the two bakes' vectors (green), over the lit texels.
  double weighted = 0.0, weights = 0.0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0 || atlas.emission[i] != glm::vec3(0.0f)) continue;
    const glm::vec3 a = shIrradianceVector(texelSh(maps[0], i), 1),
                    b = shIrradianceVector(texelSh(maps[1], i), 1);
    if (glm::length(a) <= 0.0f || glm::length(b) <= 0.0f) continue;
    const double c = std::clamp(double(glm::dot(glm::normalize(a), glm::normalize(b))), -1.0, 1.0);
    const double w = double(glm::dot(a, atlas.normal[i])) * atlas.area[i];
    weighted += w * std::acos(c) * 180.0 / std::numbers::pi;
    weights += w;
  }
  ASSERT_GT(weights, 0.0);
  std::cout << "mean angle between the GL and the ray bakes' irradiance vectors: " << weighted / weights
            << " degrees; their lit power differs by " << power[1] / power[0] - 1.0 << "\n";
  EXPECT_LT(weighted / weights, 3.0);
}

}  // namespace
}  // namespace cpgi
