// The artist's lightmap coordinates (issue 48, item 3): `bake --uv scene|own|auto` lays the engine lightmap
// in the scene's TEXCOORD_1 when it passes a lightmapper's checks, refuses it naming the mesh (scene) or
// falls back to cpgi's atlas with a warning (auto) when not.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "core/scene_io.h"
#include "tests/support/run_cpgi.h"
#include "tests/support/temp_dir.h"

namespace cpgi {
namespace {

using test::cpgi;
using test::quote;

nlohmann::json engineReport(const std::string& dir) {
  return nlohmann::json::parse(test::slurp(dir + "/report.json"))["engine_lightmap"];
}

// The mean of an image's pixels that hold light (the layout's texels on some triangle or its gutter).
glm::dvec3 litMean(const ImageRGB& image) {
  glm::dvec3 sum(0.0);
  size_t n = 0;
  for (const glm::vec3& p : image.pixels)
    if (p != glm::vec3(0.0f)) sum += glm::dvec3(p), ++n;
  return n ? sum / double(n) : sum;
}

TEST(EngineUv, TheScenesOwnTexcoord1HoldsTheLightmap) {
  test::TempDir dir;
  // A coarse atlas, an early stop and small item buffers: the layouts are compared, each bake alike.
  const std::string quick = " --density 3 --unshot 0.1 --item-buffer 128 -q";
  ASSERT_EQ(cpgi(dir, "generate seed1 -o " + quote(dir / "seed1.glb")).status, 0);
  ASSERT_EQ(cpgi(dir, "bake " + quote(dir / "seed1.glb") + " -o " + quote(dir / "a") + quick).status, 0);
  EXPECT_EQ(engineReport(dir / "a")["uv"], "own");  // seed1 brings no TEXCOORD_1
  // The preview's TEXCOORD_1 is an atlas laid out without overlap: an artist's UV2 as good as any.
  const test::CommandRun r =
      cpgi(dir, "bake " + quote(dir / "a/preview.glb") + " -o " + quote(dir / "b") + quick + " --uv scene");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = engineReport(dir / "b");
  EXPECT_EQ(report["uv"], "scene");
  EXPECT_EQ(report["width"], report["height"]);
  // baked.glb's TEXCOORD_1 is the scene's own, corner for corner.
  const LoadedScene scene = loadScene(dir / "a/preview.glb"), baked = loadScene(dir / "b/baked.glb");
  ASSERT_EQ(baked.lightmapUVs.size(), scene.lightmapUVs.size());
  float worst = 0.0f;
  for (size_t t = 0; t < scene.lightmapUVs.size(); ++t)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, glm::length(baked.lightmapUVs[t][k] - scene.lightmapUVs[t][k]));
  EXPECT_LT(worst, 1e-5f);
  // The light read into it is the light solved: the layouts' lit texels have about the same mean.
  const ImageRGB own = readExr(dir / "a/lightmap_irradiance.exr"),
                 moved = readExr(dir / "b/lightmap_irradiance.exr");
  EXPECT_EQ(moved.width, report["width"].get<int>());
  const glm::dvec3 a = litMean(own), b = litMean(moved);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c] / a[c], 1.0, 0.15) << "channel " << c;
  // `--uv own` ignores it.
  ASSERT_EQ(
      cpgi(dir, "bake " + quote(dir / "a/preview.glb") + " -o " + quote(dir / "c") + quick + " --uv own")
          .status,
      0);
  EXPECT_EQ(engineReport(dir / "c")["uv"], "own");
}

TEST(EngineUv, OverlappingOrMissingTexcoord1IsRefusedOrLeftWithAWarning) {
  test::TempDir dir;
  ASSERT_EQ(cpgi(dir, "generate seed1 --no-cells -o " + quote(dir / "seed1.glb")).status, 0);
  const test::CommandRun none = cpgi(
      dir, "bake " + quote(dir / "seed1.glb") + " -o " + quote(dir / "none") + " --density 2 --uv scene -q");
  EXPECT_EQ(none.status, 1);
  ASSERT_EQ(none.errLines().size(), 1u) << none.err;
  EXPECT_NE(none.err.find("no TEXCOORD_1"), std::string::npos) << none.err;

  // Every triangle's TEXCOORD_1 over the same corner of the square: charts laid on one another.
  LoadedScene loaded = loadScene(dir / "seed1.glb");
  std::vector<std::array<glm::vec2, 3>> stacked(
      loaded.scene.triangles.size(), {glm::vec2(0.1f, 0.1f), glm::vec2(0.9f, 0.1f), glm::vec2(0.9f, 0.9f)});
  GltfWriteOptions options;
  options.forEngines = true;
  options.lightmapUVs = &stacked;
  writeGltf(dir / "stacked.glb", loaded.scene, options);
  const test::CommandRun refused = cpgi(dir, "bake " + quote(dir / "stacked.glb") + " -o " +
                                                 quote(dir / "refused") + " --density 2 --uv scene -q");
  EXPECT_EQ(refused.status, 1);
  ASSERT_EQ(refused.errLines().size(), 1u) << refused.err;
  EXPECT_NE(refused.err.find("overlapping"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("mesh '"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "refused/report.json"));

  const test::CommandRun fallback =
      cpgi(dir, "bake " + quote(dir / "stacked.glb") + " -o " + quote(dir / "auto") + " --density 2");
  ASSERT_EQ(fallback.status, 0) << fallback.err;
  EXPECT_NE(fallback.err.find("TEXCOORD_1 is not used"), std::string::npos) << fallback.err;
  EXPECT_EQ(engineReport(dir / "auto")["uv"], "own");
}

}  // namespace
}  // namespace cpgi
