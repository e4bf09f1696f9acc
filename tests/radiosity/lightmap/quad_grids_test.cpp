// Grids of equal coplanar quads become one chart with the texels they would have had one chart each.
#include "radiosity/lightmap/quad_grids.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "radiosity/lightmap/atlas.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;

// A 4 × 3 floor of 0.5 m tiles, every other tile turned (its corners start elsewhere), in scene order.
Scene tiledFloor() {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      const glm::vec3 o(0.5f * i, 0.0f, 0.5f * j);
      if ((i + j) % 2 == 0)
        addRect(s, o, glm::vec3(0, 0, 0.5f), glm::vec3(0.5f, 0, 0), m);
      else
        addRect(s, o + glm::vec3(0.5f, 0, 0.5f), glm::vec3(0, 0, -0.5f), glm::vec3(-0.5f, 0, 0), m);
    }
  return s;
}

std::vector<std::array<float, 3>> sortedTexels(const LightmapAtlas& a) {
  std::vector<std::array<float, 3>> out;
  for (size_t t = 0; t < a.texelCount(); ++t)
    if (a.patch[t] >= 0) out.push_back({a.position[t].x, a.position[t].y, a.position[t].z});
  std::sort(out.begin(), out.end());
  return out;
}

TEST(QuadGrids, TiledFloorIsOneChartWithTheSameTexels) {
  const Scene s = tiledFloor();
  const QuadSet quads = findQuads(s);
  ASSERT_EQ(quads.quads.size(), 12u);
  const std::vector<QuadGrid> grids = findQuadGrids(quads, std::vector<char>(12, 1), s, 64);
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_EQ(grids[0].size.x * grids[0].size.y, 12);
  EXPECT_NEAR(glm::length(glm::cross(grids[0].corners[1] - grids[0].corners[0], grids[0].corners[3] - grids[0].corners[0])),
              3.0f, 1e-4f);

  Context ctx;
  const LightmapAtlas merged = buildAtlas(s, quads, AtlasParams{.texelsPerQuad = 4}, ctx);
  const LightmapAtlas apart = buildAtlas(s, quads, AtlasParams{.texelsPerQuad = 4, .mergeTexels = 0}, ctx);
  ASSERT_EQ(merged.patches.size(), 1u);
  ASSERT_EQ(apart.patches.size(), 12u);
  EXPECT_EQ(merged.patches[0].triangles.size(), 24u);
  EXPECT_EQ(merged.validTexels(), apart.validTexels());
  const auto a = sortedTexels(merged), b = sortedTexels(apart);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(a[i][k], b[i][k], 1e-5f) << i;
  // Every triangle's lightmap UVs land on its own tile: the UV centre maps back to the triangle's centre.
  const Patch& p = merged.patches[0];
  for (int32_t tri : p.triangles) {
    glm::vec2 uv(0.0f);
    glm::vec3 centre(0.0f);
    for (int k = 0; k < 3; ++k) uv += merged.triangleUV[tri][k] / 3.0f, centre += s.triangles[tri].p[k] / 3.0f;
    const glm::vec2 chart = uv * glm::vec2(merged.width, merged.height) - glm::vec2(p.x, p.y);
    const glm::vec3 at = p.origin + chart.x * p.texelU + chart.y * p.texelV;
    EXPECT_NEAR(glm::length(at - centre), 0.0f, 1e-4f) << tri;
  }
}

TEST(QuadGrids, WallStandingOnASharedEdgeSplitsTheGrid) {
  Scene s = tiledFloor();
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  // A zero-thickness wall along x = 1 (between tile columns 1 and 2), both faces.
  addRect(s, glm::vec3(1, 0, 0), glm::vec3(0, 0, 1.5f), glm::vec3(0, 2, 0), m);
  addRect(s, glm::vec3(1, 0, 0), glm::vec3(0, 2, 0), glm::vec3(0, 0, 1.5f), m);
  const QuadSet quads = findQuads(s);
  std::vector<char> usable(quads.quads.size(), 0);
  for (size_t q = 0; q < quads.quads.size(); ++q) usable[q] = std::abs(quads.quads[q].normal.y) > 0.5f;
  const std::vector<QuadGrid> grids = findQuadGrids(quads, usable, s, 64);
  ASSERT_EQ(grids.size(), 2u);
  for (const QuadGrid& g : grids) {
    EXPECT_EQ(g.quads.size(), 6u);
    int left = 0, right = 0;  // every grid lies on one side of the wall
    for (const glm::vec3& c : g.corners) left += c.x <= 1.0f + 1e-4f, right += c.x >= 1.0f - 1e-4f;
    EXPECT_TRUE(left == 4 || right == 4) << left << " " << right;
  }
}

TEST(QuadGrids, MergeLimitCutsLongGrids) {
  const Scene s = tiledFloor();
  const QuadSet quads = findQuads(s);
  Context ctx;
  // 4 texels a tile, at most 8 texels a chart edge: 2 × 2 tiles per chart at most → 2 × 2 charts.
  const LightmapAtlas a = buildAtlas(s, quads, AtlasParams{.texelsPerQuad = 4, .mergeTexels = 8}, ctx);
  ASSERT_EQ(a.patches.size(), 4u);
  size_t tiles = 0;
  for (const Patch& p : a.patches) {
    EXPECT_LE(p.w, 8);
    EXPECT_LE(p.h, 8);
    tiles += p.quads.size();
  }
  EXPECT_EQ(tiles, 12u);
}

}  // namespace
}  // namespace cpgi
