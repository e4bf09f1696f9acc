#include "radiosity/lightmap/lightmap_sampling.h"

#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addTriangle;

TEST(LightmapSampling, BilinearIsTheTexelAtItsCentreAndTheMeanBetween) {
  const std::vector<glm::vec3> map = {glm::vec3(1.0f), glm::vec3(3.0f), glm::vec3(5.0f), glm::vec3(7.0f)};
  EXPECT_FLOAT_EQ(sampleBilinear(2, 2, map, {0.25f, 0.25f}).x, 1.0f);
  EXPECT_FLOAT_EQ(sampleBilinear(2, 2, map, {0.75f, 0.75f}).x, 7.0f);
  EXPECT_FLOAT_EQ(sampleBilinear(2, 2, map, {0.5f, 0.5f}).x, 4.0f);
  EXPECT_FLOAT_EQ(sampleBilinear(2, 2, map, {0.0f, 0.25f}).x, 1.0f);  // clamped at the border
}

TEST(LightmapSampling, MatchesTrianglesByTheirCornersWhateverTheOrder) {
  Scene a;
  const uint32_t m = addMaterial(a, glm::vec3(0.5f));
  addClosedBox(a, glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 3.0f), m);
  Scene b = a;
  std::reverse(b.triangles.begin(), b.triangles.end());
  b.triangles.pop_back();  // a's first triangle is missing from b
  const std::vector<int32_t> match = matchTriangles(a, b);
  ASSERT_EQ(match.size(), a.triangles.size());
  EXPECT_EQ(match[0], -1);
  for (size_t i = 1; i < a.triangles.size(); ++i) EXPECT_EQ(match[i], int32_t(a.triangles.size() - 1 - i));
}

// A lightmap on a 5 texels/m atlas read at the texels of a 20 texels/m atlas of the same room (and a
// loose triangle): light linear in position comes back exactly between the coarse centres, and within a
// texel's change of the light next to chart borders (the dilated gutter holds the edge texel's value).
TEST(LightmapSampling, ACoarseLightmapReadAtFineTexelsAsAnEngineReadsIt) {
  Scene scene;
  const uint32_t wall = addMaterial(scene, glm::vec3(0.7f));
  addClosedBox(scene, glm::vec3(0.0f), glm::vec3(4.0f, 3.0f, 2.5f), wall);
  addTriangle(scene, glm::vec3(2.0f, 0.5f, 0.3f), glm::vec3(2.0f, 0.9f, 0.3f), glm::vec3(2.0f, 0.5f, 1.1f), wall, 3);
  Context ctx;
  AtlasParams p;
  p.density = 20.0f;
  const LightmapAtlas fine = buildAtlas(scene, findQuads(scene), p, ctx);
  p.density = 5.0f;
  const LightmapAtlas coarse = buildAtlas(scene, findQuads(scene), p, ctx);
  auto light = [](glm::vec3 x) { return 1.0f + 0.5f * x.x + 0.25f * x.y + 0.1f * x.z; };
  std::vector<glm::vec3> coarseMap(coarse.texelCount(), glm::vec3(0.0f));
  for (size_t t = 0; t < coarse.texelCount(); ++t)
    if (coarse.patch[t] >= 0) coarseMap[t] = glm::vec3(light(coarse.position[t]));
  dilate(coarse, coarseMap);
  std::vector<int32_t> identity(scene.triangles.size());
  std::iota(identity.begin(), identity.end(), 0);
  size_t missing = 7;
  const std::vector<glm::vec3> read =
      sampleAtTexels(fine, scene, identity, coarse.triangleUV, coarse.width, coarse.height, coarseMap, &missing);
  EXPECT_EQ(missing, 0u);
  size_t exact = 0;
  for (size_t t = 0; t < fine.texelCount(); ++t) {
    if (fine.patch[t] < 0) {
      EXPECT_EQ(read[t], glm::vec3(0.0f));
      continue;
    }
    const float truth = light(fine.position[t]);
    // Within the light's change over one coarse texel (0.2 m × the largest slope 0.5) everywhere.
    EXPECT_NEAR(read[t].x, truth, 0.2f * 0.5f + 1e-4f) << "fine texel " << t;
    exact += std::abs(read[t].x - truth) < 1e-3f;
  }
  EXPECT_GT(exact * 2, fine.validTexels());  // most texels lie between coarse centres

  // A triangle the lightmap has no coordinates for: its texels counted as missing and left 0.
  std::vector<int32_t> lacking = identity;
  lacking[0] = -1;
  sampleAtTexels(fine, scene, lacking, coarse.triangleUV, coarse.width, coarse.height, coarseMap, &missing);
  EXPECT_GT(missing, 0u);
}

}  // namespace
}  // namespace cpgi
