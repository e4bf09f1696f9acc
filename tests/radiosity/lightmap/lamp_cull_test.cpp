// The lamps' shot skips the rays of texels one occluder piece hides from the whole lamp (lamp_light.h,
// LampCull; occluder_pieces.h): the test of a piece across a shaft, and the shot with and without the cull
// on buildings, a wall of zero thickness, a lamp in a housing and a random plan, the same to the bit.
#include <algorithm>
#include <array>
#include <vector>

#include <gtest/gtest.h>

#include "core/quads.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/lamp_light.h"
#include "radiosity/lightmap/occluder_pieces.h"
#include "radiosity/lightmap/ray_scene.h"
#include "scenes/office_building.h"
#include "scenes/random_plans.h"
#include "scenes/stability_scenes.h"

namespace cpgi {
namespace {

// A 2 × 2 m square in the plane z = 1, as two triangles.
Triangle triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  Triangle t;
  t.p = {a, b, c};
  return t;
}

Scene squareAtZ1() {
  Scene s;
  s.materials.push_back(Material{});
  const glm::vec3 a(-1, -1, 1), b(1, -1, 1), c(1, 1, 1), d(-1, 1, 1);
  s.triangles.push_back(triangle(a, b, c));
  s.triangles.push_back(triangle(a, c, d));
  return s;
}

std::array<glm::dvec3, 4> squareAt(double x, double y, double z, double half) {
  return {glm::dvec3(x - half, y - half, z), glm::dvec3(x + half, y - half, z),
          glm::dvec3(x + half, y + half, z), glm::dvec3(x - half, y + half, z)};
}

TEST(OccluderPieces, APieceAcrossTheWholeShaftBlocksItAndNoOtherDoes) {
  const Scene scene = squareAtZ1();
  const OccluderPieces pieces(scene, 1e-3);
  ASSERT_EQ(pieces.size(), 1u) << "the square's two triangles are one piece";
  const int32_t piece = pieces.pieceOf(0);
  EXPECT_EQ(pieces.pieceOf(1), piece);
  const auto below = squareAt(0, 0, 0, 0.1), above = squareAt(0, 0, 2, 0.2);
  EXPECT_TRUE(pieces.blocks(piece, below, above, 1e-3));
  EXPECT_TRUE(pieces.blocks(piece, above, below, 1e-3)) << "either way round";
  // The shaft's section at z = 1 spans x up to 0.7 + 0.15 here: inside; at 1.2 + 0.15 it passes the edge.
  EXPECT_TRUE(pieces.blocks(piece, below, squareAt(1.4, 0, 2, 0.2), 1e-3));
  EXPECT_FALSE(pieces.blocks(piece, below, squareAt(2.4, 0, 2, 0.2), 1e-3));
  // A section that grazes the edge within the margin does not count.
  EXPECT_FALSE(pieces.blocks(piece, squareAt(0.9, 0, 0, 0.0995), squareAt(0.9, 0, 2, 0.0995), 1e-3));
  // Both on one side, or one end in the plane or within the ray's shortfall of it: nothing blocked.
  EXPECT_FALSE(pieces.blocks(piece, below, squareAt(0, 0, 0.5, 0.2), 1e-3));
  EXPECT_FALSE(pieces.blocks(piece, below, squareAt(0, 0, 1.0, 0.2), 1e-3));
  EXPECT_FALSE(pieces.blocks(piece, below, squareAt(0, 0, 1.004, 0.2), 0.01));
  EXPECT_TRUE(pieces.blocks(piece, below, squareAt(0, 0, 1.02, 0.2), 0.01));
  EXPECT_FALSE(pieces.blocks(-1, below, above, 1e-3));
}

TEST(OccluderPieces, ADegenerateTriangleIsNoPiece) {
  Scene scene = squareAtZ1();
  scene.triangles.push_back(triangle(glm::vec3(0, 0, 3), glm::vec3(1, 0, 3), glm::vec3(2, 0, 3)));
  const OccluderPieces pieces(scene, 1e-3);
  EXPECT_EQ(pieces.pieceOf(2), -1);
  EXPECT_EQ(pieces.pieceOf(7), -1);
}

struct Shots {
  LampLight all, culled;
};

Shots shootBoth(const Scene& scene, float density, int rays) {
  Context ctx;
  const LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), AtlasParams{.density = density}, ctx);
  const RayScene occluders(scene);
  const std::vector<char> lamps = lampPatches(scene, atlas);
  const auto never = std::chrono::steady_clock::time_point::max();
  return {shootLampsByRays(scene, occluders, atlas, lamps, rays, ctx, never, LampCull::None),
          shootLampsByRays(scene, occluders, atlas, lamps, rays, ctx, never, LampCull::Occluders)};
}

void expectSameLight(const Shots& s) {
  EXPECT_EQ(s.all.hiddenTexels, 0u);
  EXPECT_EQ(s.culled.irradiance, s.all.irradiance);
  EXPECT_EQ(s.culled.landed, s.all.landed);
  EXPECT_EQ(s.culled.emitted, s.all.emitted);
  EXPECT_EQ(s.culled.shot, s.all.shot);
}

TEST(LampCull, ABuildingsLampsLightTheSameTexelsAndMostHiddenOnesGetNoRay) {
  // Eighteen rooms on two storeys, six lamps: nearly every texel faces a lamp of another room.
  const SeedScene office = makeOfficeBuilding(OfficeLayout{.storeys = 2, .rows = 3, .columns = 3});
  const Shots s = shootBoth(office.scene, 2.0f, 16);
  expectSameLight(s);
  // Every texel × lamp the rays find wholly hidden is either culled or traced to be: the cull takes no
  // other, and most of them.
  EXPECT_EQ(s.culled.hiddenTexels + s.culled.tracedHiddenTexels, s.all.tracedHiddenTexels);
  EXPECT_GT(s.culled.hiddenTexels, 3 * s.culled.tracedHiddenTexels);
  EXPECT_LT(s.culled.rays, s.all.rays);
}

Scene moved(Scene scene, const glm::vec3& by) {
  for (Triangle& t : scene.triangles)
    for (glm::vec3& p : t.p) p += by;
  return scene;
}

TEST(LampCull, AWallOfZeroThicknessALampInAHousingAndARandomPlanLightTheSameTexels) {
  const Shots thin = shootBoth(makeThinWall(0.0f).scene, 5.0f, 16);
  expectSameLight(thin);
  EXPECT_GT(thin.culled.hiddenTexels, 0u) << "room B lies behind the wall";
  // 20 km from the origin, where a float coordinate rounds to 2 mm: the cull's margin grows with it.
  const Shots far =
      shootBoth(moved(makeThinWall(0.0f).scene, glm::vec3(20000.0f, 0.0f, -20000.0f)), 5.0f, 16);
  expectSameLight(far);
  EXPECT_GT(far.culled.hiddenTexels, 0u);
  expectSameLight(shootBoth(makeSpotThroughDoor().scene, 5.0f, 16));
  // Plan 4: zero-thickness walls, interior windows, lamps in some rooms.
  expectSameLight(shootBoth(makeRandomPlan(RandomPlanOptions{.seed = 4}).scene, 4.0f, 16));
}

}  // namespace
}  // namespace cpgi
