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
using testing::addRect;
using testing::addTriangle;

// `t` cut by the plane x = `cut` into triangles, as the automatic cells cut a surface on a portal's
// plane: the corners on each side and the two crossings, each side's polygon fanned.
void addCutPieces(Scene& pieces, const Triangle& t, float cut) {
  for (int side = 0; side < 2; ++side) {
    std::vector<glm::vec3> polygon;
    for (int c = 0; c < 3; ++c) {
      const glm::vec3 a = t.p[size_t(c)], b = t.p[size_t((c + 1) % 3)];
      const bool aIn = side == 0 ? a.x <= cut : a.x >= cut, bIn = side == 0 ? b.x <= cut : b.x >= cut;
      if (aIn) polygon.push_back(a);
      if (aIn != bIn) polygon.push_back(a + (b - a) * ((cut - a.x) / (b.x - a.x)));
    }
    for (size_t k = 2; k < polygon.size(); ++k)
      addTriangle(pieces, polygon[0], polygon[k - 1], polygon[k], t.material);
  }
}

// A lightmap over the xz-rectangle [0, 2]² (200 × 200 texels) holding a light linear in x and z, and the
// coordinates of a triangle's corners in it: what any chart of a flat floor reads back between centres.
constexpr int kFloorMap = 200;
float floorLight(glm::dvec3 x) {
  return float(1.0 + 0.5 * x.x + 0.25 * x.z);
}
std::array<glm::vec2, 3> floorUVs(const Triangle& t) {
  std::array<glm::vec2, 3> uv;
  for (size_t c = 0; c < 3; ++c) uv[c] = glm::vec2(t.p[c].x, t.p[c].z) / 2.0f;
  return uv;
}

// True when x's projection on the xz-plane lies inside triangle t's grown by `margin` metres along each
// edge's normal.
bool withinOf(const Triangle& t, glm::dvec3 x, double margin) {
  const auto cross = [](glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; };
  glm::dvec2 c[3];
  for (size_t k = 0; k < 3; ++k) c[k] = glm::dvec2(t.p[k].x, t.p[k].z);
  const double turn = cross(c[1] - c[0], c[2] - c[0]) > 0.0 ? 1.0 : -1.0;
  for (size_t k = 0; k < 3; ++k) {
    const glm::dvec2 e = c[(k + 1) % 3] - c[k];
    if (turn * cross(e, glm::dvec2(x.x, x.z) - c[k]) / glm::length(e) < -margin) return false;
  }
  return true;
}

// Every texel of `atlas` read as the floor's light at its point (clamped onto the floor's quad), and many
// of them on the quad's second triangle: the texels a read through the first triangle's chart got wrong.
void expectFloorLightAtTexels(const LightmapAtlas& atlas, const Scene& scene,
                              const std::vector<glm::vec3>& read) {
  size_t onSecond = 0;
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    if (atlas.patch[t] < 0) continue;
    const glm::dvec3 x(atlas.position[t]);
    const glm::dvec3 on(std::clamp(x.x, 0.02, 1.95), 0.0, std::clamp(x.z, 0.03, 1.40));
    onSecond += !withinOf(scene.triangles[0], on, 0.0);
    EXPECT_NEAR(read[t].x, floorLight(on), 1e-3f) << "texel " << t << " at " << x.x << ", " << x.z;
  }
  EXPECT_GT(onSecond * 3, atlas.validTexels());
}

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
  addTriangle(scene, glm::vec3(2.0f, 0.5f, 0.3f), glm::vec3(2.0f, 0.9f, 0.3f), glm::vec3(2.0f, 0.5f, 1.1f),
              wall, 3);
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
  const std::vector<glm::vec3> read = sampleAtTexels(fine, scene, identity, coarse.triangleUV, coarse.width,
                                                     coarse.height, coarseMap, &missing);
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

// A bake on the automatic cells cuts a surface on a portal's plane and writes the pieces, not the
// surface's triangles: a reference's texels on it are read on the pieces. A quad's texels all name its
// first triangle, so when the cut (a door's width) splits that one only, half of them lie on the second,
// unsplit, and are read through its match; a border texel's centre, off the floor, is read at its nearest
// point on the floor.
TEST(LightmapSampling, TexelsOfATriangleSplitOnAPortalPlaneAreReadOnItsPieces) {
  Scene scene;
  const uint32_t m = addMaterial(scene, glm::vec3(0.5f));
  // A floor (normal +y) 1.93 × 1.37 m, its diagonal from (0.02, 0.03) to (1.95, 1.40).
  addRect(scene, glm::vec3(0.02f, 0.0f, 0.03f), glm::vec3(0.0f, 0.0f, 1.37f), glm::vec3(1.93f, 0.0f, 0.0f),
          m);
  std::vector<glm::vec3> map(size_t(kFloorMap) * kFloorMap);
  for (int j = 0; j < kFloorMap; ++j)
    for (int i = 0; i < kFloorMap; ++i)
      map[size_t(j) * kFloorMap + size_t(i)] =
          glm::vec3(floorLight({(i + 0.5) * 2.0 / kFloorMap, 0.0, (j + 0.5) * 2.0 / kFloorMap}));
  Context ctx;
  AtlasParams params;
  params.density = 10.0f;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), params, ctx);
  ASSERT_EQ(atlas.patches.size(), 1u);

  for (const bool bothCut : {false, true}) {
    SCOPED_TRACE(bothCut ? "both triangles cut" : "the first triangle cut, the second whole");
    Scene baked;
    baked.materials = scene.materials;
    addCutPieces(baked, scene.triangles[0], 0.71f);
    if (bothCut)
      addCutPieces(baked, scene.triangles[1], 0.71f);
    else
      baked.triangles.push_back(scene.triangles[1]);
    std::reverse(baked.triangles.begin(), baked.triangles.end());  // a file lists them in its own order
    std::vector<std::array<glm::vec2, 3>> uvs;
    for (const Triangle& t : baked.triangles) uvs.push_back(floorUVs(t));

    const std::vector<int32_t> source = matchTriangles(scene, baked);
    EXPECT_EQ(source[0], -1);
    EXPECT_EQ(source[1] >= 0, !bothCut);
    const std::vector<std::vector<int32_t>> pieces = matchSplitPieces(scene, baked, source);
    ASSERT_EQ(pieces.size(), scene.triangles.size());
    EXPECT_EQ(pieces[0].size() + pieces[1].size(), baked.triangles.size() - (bothCut ? 0 : 1));
    EXPECT_EQ(pieces[1].empty(), !bothCut);

    // As compare-light reads: the matched triangles first, then the texels on cut ones.
    std::vector<glm::vec3> read = sampleAtTexels(atlas, scene, source, uvs, kFloorMap, kFloorMap, map);
    std::vector<char> unread;
    EXPECT_EQ(sampleOnSplitPieces(atlas, scene, source, pieces, baked, uvs, kFloorMap, kFloorMap, map, read,
                                  unread),
              0u);
    expectFloorLightAtTexels(atlas, scene, read);  // the case: many texels of the first lie on the second

    // The pieces of the cut triangle dropped: its texels on it are unread, those on the second read.
    std::vector<std::vector<int32_t>> lost = pieces;
    lost[0].clear();
    const size_t dropped =
        sampleOnSplitPieces(atlas, scene, source, lost, baked, uvs, kFloorMap, kFloorMap, map, read, unread);
    EXPECT_GT(dropped, 0u);
    EXPECT_LT(dropped, atlas.validTexels());
    EXPECT_EQ(size_t(std::count(unread.begin(), unread.end(), char(1))), dropped);
  }
}

// The other way round: the cut splits a quad's second triangle and leaves its first whole, so the bake
// charts the first alone. texelTriangle names the first for the texels on the second too; read through
// the first's coordinates carried past its edge they landed outside its chart, on another surface's
// texels (plan 10's R2 in the automatic cells' bake: a column of its wall at 20× the room's light). They
// are read on the second's pieces.
TEST(LightmapSampling, TexelsOnTheCutSecondTriangleOfAQuadAreReadOnItsPiecesNotPastTheFirstsChart) {
  Scene scene;
  const uint32_t m = addMaterial(scene, glm::vec3(0.5f));
  addRect(scene, glm::vec3(0.02f, 0.0f, 0.03f), glm::vec3(0.0f, 0.0f, 1.37f), glm::vec3(1.93f, 0.0f, 0.0f),
          m);
  Context ctx;
  AtlasParams params;
  params.density = 10.0f;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), params, ctx);
  ASSERT_EQ(atlas.patches.size(), 1u);
  ASSERT_EQ(atlas.patches[0].triangles.front(), 0);  // the quad's first triangle, the one left whole

  Scene baked;
  baked.materials = scene.materials;
  baked.triangles.push_back(scene.triangles[0]);
  addCutPieces(baked, scene.triangles[1], 0.71f);
  // Two charts in a 200 × 400 map, each the floor's xz at 1 cm a texel: the whole triangle's in the top
  // half, the light right within 3 cm of it and another surface's (100) beyond; the pieces' in the bottom.
  std::vector<glm::vec3> map(size_t(kFloorMap) * 2 * kFloorMap);
  for (int j = 0; j < 2 * kFloorMap; ++j)
    for (int i = 0; i < kFloorMap; ++i) {
      const glm::dvec3 x((i + 0.5) * 2.0 / kFloorMap, 0.0, ((j % kFloorMap) + 0.5) * 2.0 / kFloorMap);
      const bool nearWhole = withinOf(scene.triangles[0], x, 0.03);
      map[size_t(j) * kFloorMap + size_t(i)] =
          glm::vec3(j >= kFloorMap || nearWhole ? floorLight(x) : 100.0f);
    }
  std::vector<std::array<glm::vec2, 3>> uvs;
  for (size_t k = 0; k < baked.triangles.size(); ++k) {
    std::array<glm::vec2, 3> uv = floorUVs(baked.triangles[k]);
    for (glm::vec2& c : uv) c = glm::vec2(c.x, 0.5f * c.y + (k == 0 ? 0.0f : 0.5f));
    uvs.push_back(uv);
  }

  const std::vector<int32_t> source = matchTriangles(scene, baked);
  ASSERT_EQ(source[0], 0);
  ASSERT_EQ(source[1], -1);
  size_t missing = 0;
  std::vector<glm::vec3> read =
      sampleAtTexels(atlas, scene, source, uvs, kFloorMap, 2 * kFloorMap, map, &missing);
  EXPECT_GT(missing, 0u);
  std::vector<char> unread;
  EXPECT_EQ(sampleOnSplitPieces(atlas, scene, source, matchSplitPieces(scene, baked, source), baked, uvs,
                                kFloorMap, 2 * kFloorMap, map, read, unread),
            0u);
  expectFloorLightAtTexels(atlas, scene, read);
}

}  // namespace
}  // namespace cpgi
