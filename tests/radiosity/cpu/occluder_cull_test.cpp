#include "radiosity/cpu/occluder_cull.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;

LightmapAtlas atlasOf(const Scene& s) {
  Context ctx;
  return buildAtlas(s, findQuads(s), AtlasParams{}, ctx);
}

// A wall x = 2 between an eye and a tile of receivers: whole, it hides the tile. With a window in it, even
// one off the line to the tile's centre but inside the cone round the tile, it does not: the quad the line
// meets no longer covers the cone.
TEST(ConvexOccluders, AWallHidesATileAndAWindowInTheConeUndoesIt) {
  const glm::vec3 eye(0.0f, 2.0f, 0.0f);
  const glm::vec4 tile(4.0f, 2.0f, 0.0f, 0.3f);
  for (int variant : {0, 1, 2}) {
    Scene s;
    const uint32_t m = addMaterial(s, glm::vec3(0.5f));
    const glm::vec3 Y(0, 1, 0), Z(0, 0, 1);
    if (variant == 0) {
      addRect(s, {2, 0, -2}, 4.0f * Y, 4.0f * Z, m);
    } else {
      // A window at y in [w0, w0 + 0.1], z in [-0.05, 0.05]; the wall around it in four quads.
      const float w0 = variant == 1 ? 1.95f : 2.05f;  // on the line to the centre, or beside it
      addRect(s, {2, 0, -2}, w0 * Y, 4.0f * Z, m);
      addRect(s, {2, w0 + 0.1f, -2}, (3.9f - w0) * Y, 4.0f * Z, m);
      addRect(s, {2, w0, -2}, 0.1f * Y, 1.95f * Z, m);
      addRect(s, {2, w0, 0.05f}, 0.1f * Y, 1.95f * Z, m);
    }
    const LightmapAtlas atlas = atlasOf(s);
    const RayScene rays(s);
    const ConvexOccluders occluders(s, atlas);
    EXPECT_EQ(occluders.hides(rays, eye, tile, 1e-3f), variant == 0) << variant;
  }
}

// A point drawn in `sphere` (centre, radius).
glm::vec3 pointIn(const glm::vec4& sphere, std::mt19937& random) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const glm::vec3 d(unit(random) - 0.5f, unit(random) - 0.5f, unit(random) - 0.5f);
  return glm::vec3(sphere) + sphere.w * unit(random) * glm::normalize(d + 1e-6f);
}

// Whether the segment from `eye` to `p` meets a surface (short of p by a millimetre).
bool segmentMeetsSomething(const RayScene& rays, const glm::vec3& eye, const glm::vec3& p) {
  const float length = glm::distance(eye, p);
  return rays.occluded(eye, (p - eye) / length, 0.0f, length - 1e-3f);
}

// Never hides what a ray sees: boxes standing in a room, eyes and spheres drawn at random; wherever the
// cull says hidden, every segment from the eye to 64 points in the sphere meets something.
TEST(ConvexOccluders, WhatItHidesNoRaySees) {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(10.0f, 3.0f, 10.0f), m);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int b = 0; b < 12; ++b) {  // outward-facing boxes: walls, pillars, slabs
    const glm::vec3 lo(1.0f + 7.0f * unit(random), 0.0f, 1.0f + 7.0f * unit(random));
    const glm::vec3 size(0.1f + 2.0f * unit(random), 0.5f + 2.5f * unit(random), 0.1f + 2.0f * unit(random));
    const glm::vec3 X(size.x, 0, 0), Y(0, size.y, 0), Z(0, 0, size.z);
    addRect(s, lo, Y, X, m), addRect(s, lo + Z, X, Y, m), addRect(s, lo, Z, Y, m);
    addRect(s, lo + X, Y, Z, m), addRect(s, lo, X, Z, m), addRect(s, lo + Y, Z, X, m);
  }
  const LightmapAtlas atlas = atlasOf(s);
  const RayScene rays(s);
  const ConvexOccluders occluders(s, atlas);
  auto inRoom = [&] {
    return glm::vec3(0.2f + 9.6f * unit(random), 0.2f + 2.6f * unit(random), 0.2f + 9.6f * unit(random));
  };
  int hidden = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const glm::vec3 eye = inRoom();
    const glm::vec4 sphere(inRoom(), 0.05f + 0.5f * unit(random));
    if (!occluders.hides(rays, eye, sphere, 1e-3f)) continue;
    ++hidden;
    for (int k = 0; k < 64; ++k)
      ASSERT_TRUE(segmentMeetsSomething(rays, eye, pointIn(sphere, random)))
          << "trial " << trial << " sees a point the cull hid";
  }
  EXPECT_GT(hidden, 200);
}

// A region's eyes asked together (hidesFromEvery, as the interleaved eye sets are): hidden only where every
// segment from every one of them to the sphere meets something, and as often hidden as one eye alone.
TEST(ConvexOccluders, WhatItHidesFromAGroupNoRayFromAnyOfItSees) {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(10.0f, 3.0f, 10.0f), m);
  addRect(s, {5.0f, 0.0f, 0.0f}, {0, 0, 10.0f}, {0, 3.0f, 0}, m);  // a wall across the room, x = 5, both
  addRect(s, {5.0f, 0.0f, 0.0f}, {0, 3.0f, 0}, {0, 0, 10.0f}, m);  // faces, with no opening
  addRect(s, {6.0f, 0.0f, 2.0f}, {0, 2.0f, 0}, {1.0f, 0, 0}, m);   // a panel behind it, x in [6, 7]
  const LightmapAtlas atlas = atlasOf(s);
  const RayScene rays(s);
  const ConvexOccluders occluders(s, atlas);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int hiddenGroups = 0, hiddenFirst = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    // Four eyes within a metre on the near side of x = 5 (some beside the wall's end at z = 10 − 0.2 too).
    const glm::vec3 at(0.5f + 3.5f * unit(random), 0.2f + 2.6f * unit(random), 0.5f + 9.0f * unit(random));
    std::vector<glm::vec3> eyes;
    for (int e = 0; e < 4; ++e)
      eyes.push_back(glm::clamp(at + glm::vec3(unit(random), unit(random), unit(random)) - 0.5f,
                                glm::vec3(0.1f), glm::vec3(4.9f, 2.9f, 9.9f)));
    const glm::vec4 sphere(5.2f + 4.5f * unit(random), 0.3f + 2.4f * unit(random), 0.3f + 9.4f * unit(random),
                           0.05f + 0.3f * unit(random));
    hiddenFirst += occluders.hides(rays, eyes[0], sphere, 1e-3f) ? 1 : 0;
    if (!occluders.hidesFromEvery(rays, eyes, sphere, 1e-3f)) continue;
    ++hiddenGroups;
    for (const glm::vec3& eye : eyes)
      for (int k = 0; k < 16; ++k)
        ASSERT_TRUE(segmentMeetsSomething(rays, eye, pointIn(sphere, random)))
            << "trial " << trial << " sees a point the cull hid from the group";
  }
  EXPECT_GT(hiddenGroups, 0.9 * hiddenFirst);
}

// Tiles are the chart's texels in blocks of at most 8 × 8, each texel in one, with a sphere holding them.
TEST(ReceiverTiles, EveryTexelInOneTileInsideItsSphere) {
  Scene s;
  addClosedBox(s, glm::vec3(0.0f), glm::vec3(3.0f, 2.0f, 2.5f), addMaterial(s, glm::vec3(0.5f)));
  const LightmapAtlas atlas = atlasOf(s);
  std::vector<uint32_t> texels;
  for (size_t t = 0; t < atlas.texelCount(); ++t)
    if (atlas.patch[t] >= 0) texels.push_back(uint32_t(t));
  const ReceiverTiles tiles = receiverTiles(atlas, texels, 0.01f);
  std::vector<uint32_t> count(tiles.spheres.size(), 0);
  for (size_t k = 0; k < texels.size(); ++k) {
    const uint32_t tile = tiles.tileOf[k];
    ++count[tile];
    const glm::vec3 x = atlas.position[texels[k]] + 0.01f * atlas.normal[texels[k]];
    EXPECT_LE(glm::distance(x, glm::vec3(tiles.spheres[tile])), tiles.spheres[tile].w * 1.0001f + 1e-6f);
    EXPECT_EQ(tiles.patches[tile], atlas.patch[texels[k]]);
  }
  for (size_t tile = 0; tile < count.size(); ++tile) {
    EXPECT_EQ(count[tile], tiles.counts[tile]);
    EXPECT_LE(count[tile], 64u);
  }
}

}  // namespace
}  // namespace cpgi
