// Lightmaps per object (`bake --per-object`): every triangle reads in its object's lightmap, at its new
// coordinates, what it read in the scene's atlas (charts copied with their gutters, so bilinear reads agree
// to the bit); a chart two objects share goes into both; with the artist's UV2 each object's square is
// checked alone, so objects may overlap each other but not themselves; file names are safe and unique.
#include "radiosity/lightmap/object_lightmaps.h"

#include <set>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/lightmap/lightmap_sampling.h"
#include "radiosity/lightmap/scene_uv.h"
#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addClosedBox;
using testing::addMaterial;
using testing::addRect;
using testing::addTriangle;

// A room (node 0), a floor mat of two equal coplanar halves in nodes 1 and 2 (one merged chart), a loose
// triangle (node 3).
Scene fourObjects() {
  Scene scene;
  const uint32_t grey = addMaterial(scene, glm::vec3(0.7f));
  addClosedBox(scene, glm::vec3(0.0f), glm::vec3(4.0f, 3.0f, 2.5f), grey);
  addRect(scene, glm::vec3(1.0f, 0.01f, 1.0f), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), grey, 1);
  addRect(scene, glm::vec3(2.0f, 0.01f, 1.0f), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), grey, 2);
  addTriangle(scene, glm::vec3(3.9f, 0.5f, 0.3f), glm::vec3(3.9f, 0.9f, 0.3f), glm::vec3(3.9f, 0.5f, 1.1f),
              grey, 3);
  scene.nodePaths = {"room/walls", "mat/left", "mat/left", "a stray: triangle?"};
  return scene;
}

TEST(ObjectLightmaps, EveryTriangleReadsInItsObjectsLightmapWhatItReadInTheScenesAtlas) {
  const Scene scene = fourObjects();
  Context ctx;
  AtlasParams p;
  p.density = 8.0f;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), p, ctx);
  // A value that differs from texel to texel, gutters dilated as the outputs have them.
  std::vector<glm::vec3> values(atlas.texelCount(), glm::vec3(0.0f));
  for (size_t i = 0; i < values.size(); ++i)
    if (atlas.patch[i] >= 0) values[i] = atlas.position[i] + glm::vec3(0.1f * float(i % 7));
  dilate(atlas, values);

  const ObjectLightmaps layout = layOutObjectLightmaps(scene, atlas);
  ASSERT_EQ(layout.objects.size(), 4u);
  std::set<std::string> stems;
  for (const ObjectLightmap& o : layout.objects) stems.insert(o.fileStem);
  EXPECT_EQ(stems, (std::set<std::string>{"lightmap-room_walls", "lightmap-mat_left", "lightmap-mat_left-2",
                                          "lightmap-a_stray_triangle"}));
  std::vector<std::vector<glm::vec3>> images;
  for (size_t k = 0; k < layout.objects.size(); ++k)
    images.push_back(objectImage(scene, atlas, layout, k, values));
  size_t checked = 0;
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    const int k = layout.objectOfTriangle[t];
    ASSERT_GE(k, 0) << "triangle " << t;
    const ObjectLightmap& o = layout.objects[size_t(k)];
    EXPECT_EQ(o.node, scene.triangles[t].node);
    // The corners pulled a little inside, and the centre.
    for (const glm::vec3 b : {glm::vec3(0.9f, 0.05f, 0.05f), glm::vec3(0.05f, 0.9f, 0.05f),
                              glm::vec3(0.05f, 0.05f, 0.9f), glm::vec3(1.0f / 3.0f)}) {
      const auto& from = atlas.triangleUV[t];
      const auto& to = layout.triangleUV[t];
      const glm::vec2 a = b.x * from[0] + b.y * from[1] + b.z * from[2];
      const glm::vec2 c = b.x * to[0] + b.y * to[1] + b.z * to[2];
      ASSERT_TRUE(c.x >= 0.0f && c.y >= 0.0f && c.x <= 1.0f && c.y <= 1.0f) << "triangle " << t;
      const glm::vec3 want = sampleBilinear(atlas.width, atlas.height, values, a);
      const glm::vec3 got = sampleBilinear(o.width, o.height, images[size_t(k)], c);
      EXPECT_LT(glm::length(got - want), 1e-4f * (1.0f + glm::length(want))) << "triangle " << t;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 4 * scene.triangles.size());
  // The two halves of the mat share one chart, copied into both objects.
  size_t validTexels = 0;
  for (const ObjectLightmap& o : layout.objects) validTexels += o.validTexels;
  EXPECT_GE(validTexels, atlas.validTexels());
}

// TEXCOORD_1 as an artist unwraps each object for a lightmap of its own: each mat half over the whole
// square [0,1]² (the two on the same texels), the stray triangle by its (y, z), the room's six faces on
// six strips.
void giveSceneUVs(Scene& scene) {
  for (Triangle& t : scene.triangles) {
    std::array<glm::vec2, 3> uv;
    for (int k = 0; k < 3; ++k)
      uv[k] = t.node == 3 ? glm::vec2(t.p[k].y / 3.0f, t.p[k].z / 2.5f)
                          : glm::vec2(t.p[k].x - float(t.node), t.p[k].z - 1.0f);
    if (t.node == 0) {  // the room's six faces: a quarter each would not fit; lay each face on its own strip
      const glm::vec3 n = glm::abs(t.geometricNormal());
      const int drop = n.x > n.y && n.x > n.z ? 0 : n.y > n.z ? 1 : 2;
      const int face = drop * 2 + (t.p[0][drop] > 0.5f);
      for (int k = 0; k < 3; ++k) {
        const glm::vec3 q = t.p[k] / glm::vec3(4.0f, 3.0f, 2.5f);
        uv[k] = glm::vec2((float(face) + 0.05f + 0.9f * q[(drop + 1) % 3]) / 6.0f,
                          0.05f + 0.9f * q[(drop + 2) % 3]);
      }
    }
    SurfaceUV map;
    map.fit(t.p, uv, 1);
    t.uv = uint32_t(scene.looks.uvs.size());
    scene.looks.uvs.push_back(map);
  }
}

TEST(ObjectLightmaps, EachObjectsTexcoord1IsCheckedAsASquareOfItsOwn) {
  Scene scene = fourObjects();
  scene.nodePaths = {"room", "mat-left", "mat-right", "stray"};
  giveSceneUVs(scene);
  Context ctx;
  AtlasParams p;
  p.density = 8.0f;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), p, ctx);
  // The two mat halves lie on the same part of [0,1]²: refused as one layout, fine per object.
  EXPECT_FALSE(checkSceneUVs(scene, sceneUvSize(scene, atlas.validTexels())).usable());
  std::vector<std::string> refusals, warnings;
  const ObjectLightmaps layout = layOutObjectSceneUVs(scene, atlas, refusals, warnings);
  EXPECT_TRUE(refusals.empty()) << refusals.front();
  ASSERT_EQ(layout.objects.size(), 4u);
  for (size_t t = 0; t < scene.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(layout.triangleUV[t][k],
                scene.looks.uvs[scene.triangles[t].uv].at(scene.triangles[t].p[k], 1));
  // The light read into each object's square: the mat's left half lit as the scene's atlas has it.
  std::vector<glm::vec3> values(atlas.texelCount(), glm::vec3(0.0f));
  for (size_t i = 0; i < values.size(); ++i)
    if (atlas.patch[i] >= 0) values[i] = glm::vec3(atlas.position[i].x);
  dilate(atlas, values);
  const std::vector<glm::vec3> left = objectImage(scene, atlas, layout, 1, values);
  const ObjectLightmap& o = layout.objects[1];
  const glm::vec3 mid = sampleBilinear(o.width, o.height, left, glm::vec2(0.5f, 0.5f));
  EXPECT_NEAR(mid.x, 1.5f, 0.1f);

  // Copies of the stray triangle beside it on the same texels: that object is refused, by its name.
  Scene twice = scene;
  for (uint32_t k = 0; k < 2; ++k) {
    Triangle t = twice.triangles[twice.triangles.size() - 1];
    t.p[1] += glm::vec3(0.0f, 0.01f * float(k + 1), 0.0f);
    twice.triangles.push_back(t);
  }
  refusals.clear();
  layOutObjectSceneUVs(twice, buildAtlas(twice, findQuads(twice), p, ctx), refusals, warnings);
  ASSERT_FALSE(refusals.empty());
  EXPECT_NE(refusals.front().find("mesh 'stray'"), std::string::npos) << refusals.front();
}

TEST(ObjectLightmaps, FileNamesAreSafe) {
  EXPECT_EQ(safeFileName("cell:A/A/floor"), "cell_A_A_floor");
  EXPECT_EQ(safeFileName("../../etc/passwd"), ".._.._etc_passwd");
  EXPECT_EQ(safeFileName("Ünïcode name"), "n_code_name");
  EXPECT_EQ(safeFileName(""), "object");
  EXPECT_EQ(safeFileName(".."), "object");
  EXPECT_EQ(safeFileName(std::string(200, 'a')).size(), 60u);
}

}  // namespace
}  // namespace cpgi
