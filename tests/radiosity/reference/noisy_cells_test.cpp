#include "radiosity/reference/noisy_cells.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/reference/path_test_scenes.h"

namespace cpgi {
namespace {

using namespace cpgi::testing;
using namespace cpgi::pathtest;

TEST(NoisyCells, MergeIsThePathWeightedMeanAndItsError) {
  ReferenceResult a, b;
  a.radiosity = {glm::vec3(1.0f), glm::vec3(2.0f)};
  a.standardError = {glm::vec3(0.4f), glm::vec3(0.1f)};
  b.radiosity = {glm::vec3(3.0f), glm::vec3(9.0f)};
  b.standardError = {glm::vec3(0.2f), glm::vec3(5.0f)};
  std::vector<int> paths{16, 16};
  const std::vector<int> more{48, 0};  // the second texel was not traced again
  mergeReference(a, paths, b, more);
  EXPECT_FLOAT_EQ(a.radiosity[0].x, (16.0f * 1.0f + 48.0f * 3.0f) / 64.0f);
  EXPECT_FLOAT_EQ(a.standardError[0].x, std::sqrt(16.0f * 16.0f * 0.16f + 48.0f * 48.0f * 0.04f) / 64.0f);
  EXPECT_EQ(paths[0], 64);
  EXPECT_FLOAT_EQ(a.radiosity[1].x, 2.0f);
  EXPECT_FLOAT_EQ(a.standardError[1].x, 0.1f);
  EXPECT_EQ(paths[1], 16);
}

// A grey box lit by its ceiling. Cell "corner" is a single floor texel: its mean is one texel's, so at
// 32 paths it is several times noisier than the 1 % target, whereas "rest" averages hundreds of texels.
// Only the corner's texel is traced again, until it meets the target, and the same call gives the
// same result.
TEST(NoisyCells, OnlyTheNoisyCellIsTracedAgainUntilItMeetsTheTarget) {
  Scene scene;
  const uint32_t grey = addMaterial(scene, glm::vec3(0.5f));
  const uint32_t lamp = addMaterial(scene, glm::vec3(0.5f), glm::vec3(10.0f));
  addFaces(scene, boxFaces(2.0f, {grey, lamp, grey, grey, grey, grey}));
  Context ctx;
  AtlasParams atlasParams;
  atlasParams.texelsPerQuad = 6;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), atlasParams, ctx);
  std::vector<float> cell(atlas.texelCount(), -1.0f), weight(atlas.texelCount(), 0.0f);
  size_t corner = atlas.texelCount();
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0 || atlas.emission[i] != glm::vec3(0.0f)) continue;
    if (corner == atlas.texelCount()) corner = i;
    cell[i] = i == corner ? 0.0f : 1.0f;
    weight[i] = atlas.area[i];
  }
  ReferenceParams params;
  params.spp = 32;
  const CellNoiseTarget target{.meanNoise = 0.01, .maxSpp = 32 * 1024};
  const RefinedReference r =
      traceToCellNoise(scene, atlas, params, {}, cell, weight, {"corner", "rest"}, target, ctx);
  ASSERT_EQ(r.cells.size(), 2u);
  EXPECT_LE(r.cells[0].meanNoise, 0.01);
  EXPECT_LE(r.cells[1].meanNoise, 0.01);
  EXPECT_GE(r.passes, 1);
  EXPECT_GT(r.paths[corner], 32);
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0 || i == corner) continue;
    EXPECT_EQ(r.paths[i], 32) << "texel " << i;
  }
  // The corner's estimate is still right: a grey box lit by its ceiling, within 5 standard errors of a
  // trace of the same texel with as many paths from the first stream.
  ReferenceParams many = params;
  many.spp = r.paths[corner];
  size_t rank = 0;
  for (size_t i = 0; i < corner; ++i) rank += atlas.patch[i] >= 0;
  const std::vector<size_t> only{rank};
  const ReferenceResult direct = traceReference(scene, atlas, many, ctx, only);
  EXPECT_NEAR(r.result.radiosity[corner].x, direct.radiosity[corner].x,
              5.0f * std::hypot(r.result.standardError[corner].x, direct.standardError[corner].x));

  const RefinedReference again =
      traceToCellNoise(scene, atlas, params, {}, cell, weight, {"corner", "rest"}, target, ctx);
  EXPECT_EQ(again.result.radiosity[corner], r.result.radiosity[corner]);
  EXPECT_EQ(again.paths, r.paths);
}

}  // namespace
}  // namespace cpgi
