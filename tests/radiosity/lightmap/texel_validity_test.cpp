#include "radiosity/lightmap/texel_validity.h"

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;

// A 2 × 2 m floor (y = 0, 10 texels a metre) with a room's wall standing on its edge at x = 2 (facing the
// floor) and a box [0.5, 1]² × [0, 0.5] on it, closed but for its bottom: the floor runs under the box.
Scene floorUnderABox() {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.5f));
  addRect(s, {0, 0, 0}, {0, 0, 2}, {2, 0, 0}, grey);  // floor, normal +y
  addRect(s, {2, 0, 0}, {0, 0, 2}, {0, 1, 0}, grey);  // wall x = 2, normal −x
  const glm::vec3 lo(0.5f, 0.0f, 0.5f), d(0.5f);
  addRect(s, lo, {0, 0, d.z}, {0, d.y, 0}, grey);                         // x = 0.5, normal −x
  addRect(s, lo + glm::vec3(d.x, 0, 0), {0, d.y, 0}, {0, 0, d.z}, grey);  // x = 1, normal +x
  addRect(s, lo, {0, d.y, 0}, {d.x, 0, 0}, grey);                         // z = 0.5, normal −z
  addRect(s, lo + glm::vec3(0, 0, d.z), {d.x, 0, 0}, {0, d.y, 0}, grey);  // z = 1, normal +z
  addRect(s, lo + glm::vec3(0, d.y, 0), {0, 0, d.z}, {d.x, 0, 0}, grey);  // top, normal +y
  return s;
}

LightmapAtlas floorAtlas(const Scene& s, bool outOfSolids) {
  AtlasParams params;
  params.density = 10.0f;
  Context ctx;
  LightmapAtlas atlas = buildAtlas(s, findQuads(s), params, ctx);
  if (outOfSolids) atlas.movedSamplePoints = moveSamplePointsOutOfSolids(atlas, s, RayScene(s));
  return atlas;
}

bool underTheBox(const glm::vec3& x) {
  return x.x > 0.5f && x.x < 1.0f && x.z > 0.5f && x.z < 1.0f;
}

// Of the 5 × 5 floor texels under the box, the ring of 16 within a texel of its sides moves just out of
// it, onto the open floor beside its own texel; the 3 × 3 deeper inside stay. No other texel moves: the
// floor along the wall keeps its points, a corner's light is its own.
TEST(SamplePointsOutOfSolids, FloorTexelsUnderABoxMoveOutWithinATexelAndNoOtherMoves) {
  const Scene s = floorUnderABox();
  const LightmapAtlas centred = floorAtlas(s, false), moved = floorAtlas(s, true);
  ASSERT_EQ(centred.texelCount(), moved.texelCount());
  EXPECT_EQ(centred.movedSamplePoints, 0u);
  EXPECT_EQ(moved.movedSamplePoints, 16u);
  size_t under = 0, out = 0;
  for (size_t t = 0; t < moved.texelCount(); ++t) {
    if (moved.patch[t] < 0) continue;
    const glm::vec3 c = centred.position[t], x = moved.position[t];
    if (c == x) continue;
    EXPECT_NEAR(c.y, 0.0f, 1e-6f);
    ASSERT_TRUE(underTheBox(c)) << c.x << " " << c.z;
    ++under;
    out += !underTheBox(x);
    EXPECT_EQ(x.y, c.y);                   // on the floor's plane
    EXPECT_LT(glm::distance(c, x), 0.1f);  // within a texel
  }
  EXPECT_EQ(under, 16u);
  EXPECT_EQ(out, 16u);
}

// buildAtlas leaves every sample point at its texel's centre, inside the box too.
TEST(SamplePointsOutOfSolids, BuildAtlasLeavesTheCentres) {
  const Scene s = floorUnderABox();
  AtlasParams params;
  params.density = 10.0f;
  Context ctx;
  const LightmapAtlas atlas = buildAtlas(s, findQuads(s), params, ctx);
  EXPECT_EQ(atlas.movedSamplePoints, 0u);
  size_t under = 0;
  for (size_t t = 0; t < atlas.texelCount(); ++t)
    under += atlas.patch[t] >= 0 && atlas.normal[t].y > 0.5f && atlas.position[t].y < 1e-6f &&
             underTheBox(atlas.position[t]);
  EXPECT_EQ(under, 25u);
}

}  // namespace
}  // namespace cpgi
