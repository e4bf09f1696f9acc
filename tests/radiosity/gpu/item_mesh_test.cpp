#include "radiosity/gpu/item_mesh.h"

#include <gtest/gtest.h>

#include "core/quads.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;
using testing::addTriangle;

int32_t patchOfTriangle(const LightmapAtlas& atlas, int32_t t) {
  for (size_t i = 0; i < atlas.patches.size(); ++i)
    for (int32_t u : atlas.patches[i].triangles)
      if (u == t) return int32_t(i);
  return -2;
}

// A floor and a wall meeting along an edge, and a zero-area triangle: each rectangle's two triangles share
// their diagonal's corners, the floor and the wall share none (another patch, another normal, though the
// same positions), the sliver is not drawn, and every drawn triangle keeps its corners in order.
TEST(ItemMesh, SharesCornersWithinAPatchOnly) {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addRect(s, glm::vec3(0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), m);         // floor z = 0
  addRect(s, glm::vec3(0.0f), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), m);         // wall y = 0, normal +y
  addTriangle(s, glm::vec3(0, 0, 2), glm::vec3(1, 0, 2), glm::vec3(2, 0, 2), m);  // collinear
  Context ctx;
  const LightmapAtlas atlas = buildAtlas(s, findQuads(s), AtlasParams{.texelsPerQuad = 4}, ctx);
  const ItemMesh mesh = buildItemMesh(s, atlas);
  ASSERT_EQ(mesh.indices.size(), 12u);
  EXPECT_EQ(mesh.positions.size(), 8u);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  ASSERT_EQ(mesh.patches.size(), mesh.positions.size());
  for (int32_t t = 0; t < 4; ++t) {
    const int32_t patch = patchOfTriangle(atlas, t);
    ASSERT_GE(patch, 0);
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[size_t(3 * t + k)];
      EXPECT_EQ(mesh.positions[v], s.triangles[size_t(t)].p[k]);
      EXPECT_EQ(mesh.patches[v], patch);
      EXPECT_EQ(mesh.normals[v], atlas.patches[size_t(patch)].normal);
    }
  }
}

// A triangle the atlas does not hold (no patch) still occludes, with its own face normal and ID -2.
TEST(ItemMesh, KeepsTrianglesOutsideTheAtlasAsOccluders) {
  Scene s;
  const uint32_t m = addMaterial(s, glm::vec3(0.5f));
  addRect(s, glm::vec3(0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), m);
  Context ctx;
  LightmapAtlas atlas = buildAtlas(s, findQuads(s), AtlasParams{.texelsPerQuad = 4}, ctx);
  for (Patch& p : atlas.patches) p.triangles.clear();
  const ItemMesh mesh = buildItemMesh(s, atlas);
  ASSERT_EQ(mesh.indices.size(), 6u);
  EXPECT_EQ(mesh.positions.size(), 4u);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    EXPECT_EQ(mesh.patches[v], -2);
    EXPECT_NEAR(mesh.normals[v].z, 1.0f, 1e-6f);
  }
}

}  // namespace
}  // namespace cpgi
