// One portal per opening (decomposition/portal_merge.h) on hand-made labels: a doorway left in pieces
// becomes one quad, every face still covered; two doors with a wall between them stay two; pieces off
// each other's plane stay apart.
#include <gtest/gtest.h>

#include "decomposition/portal_merge.h"

namespace cpgi::decomp {
namespace {

const GridFrame& frame() {
  static GridFrame f = [] {
    GridFrame g;
    g.dims = {12, 6, 24};
    g.voxel = 1.0;
    return g;
  }();
  return f;
}

// A 12 × 6 × 24 grid of 1 m voxels split at x = 6: cell 0 (x < 6), cell 1 (x ≥ 6), but for a wall of
// solid (unlabelled) voxels at x = 5 and 6 with openings where `open(z)` holds, for y in [1, 4].
template <typename Open>
PortalSet twoRoomsThroughAWall(Open open) {
  PortalSet set;
  const GridFrame& f = frame();
  set.cell.assign(f.count(), -1);
  for (size_t i = 0; i < f.count(); ++i) {
    const glm::ivec3 c = f.coord(i);
    if (glm::any(glm::equal(c, glm::ivec3(0))) || glm::any(glm::equal(c, f.dims - 1))) continue;
    const bool wall = c.x == 5 || c.x == 6;
    if (wall && !(open(c.z) && c.y >= 1 && c.y <= 4)) continue;
    set.cell[i] = c.x < 6 ? 0 : 1;
  }
  return set;
}

// A portal in the plane x = xPlane over z in [z0, z1] (voxel faces), y in [0.5, 4.5].
FittedPortal piece(float xPlane, float z0, float z1) {
  FittedPortal p;
  p.quad.corners = {glm::vec3(xPlane, 0.5f, z0), glm::vec3(xPlane, 4.5f, z0), glm::vec3(xPlane, 4.5f, z1),
                    glm::vec3(xPlane, 0.5f, z1)};
  computePortalFrame(p.quad);
  p.quad.normal = {1, 0, 0};
  p.quad.cellA = 0, p.quad.cellB = 1;
  p.faces = 1;
  return p;
}

// Issue 46: aggressor's and oa_dm7's openings came as several pieces of one plane. A doorway 8 m wide
// covered by three pieces (the middle one a sliver) is one portal, its faces all still covered.
TEST(PortalMerge, ADoorwayInPiecesIsOnePortal) {
  PortalSet set = twoRoomsThroughAWall([](int z) { return z >= 4 && z < 12; });
  set.portals = {piece(5.5f, 3.5f, 7.5f), piece(5.5f, 7.5f, 8.5f), piece(5.5f, 8.5f, 12.5f)};
  const GridFrame& f = frame();
  ASSERT_EQ(countLeakingFaces(f, set.cell, {set.portals[0].quad, set.portals[1].quad, set.portals[2].quad}),
            0u);
  Context ctx;
  const MergedPortals m = mergePortalPieces(set, f, PortalMergeParams{}, ctx);
  EXPECT_EQ(m.merged, 2);
  ASSERT_EQ(set.portals.size(), 1u);
  EXPECT_NEAR(set.portals[0].quad.area, 4.0f * 9.0f, 1e-3f);
  EXPECT_EQ(set.portals[0].faces, 3u);
  EXPECT_EQ(set.leakingFaces, 0u);
}

// Two doors of one wall, 8 m of wall between them, stay two portals.
TEST(PortalMerge, TwoDoorsWithAWallBetweenStayTwo) {
  PortalSet set = twoRoomsThroughAWall([](int z) { return (z >= 2 && z < 5) || (z >= 13 && z < 16); });
  set.portals = {piece(5.5f, 1.5f, 5.5f), piece(5.5f, 12.5f, 16.5f)};
  Context ctx;
  const MergedPortals m = mergePortalPieces(set, frame(), PortalMergeParams{}, ctx);
  EXPECT_EQ(m.merged, 0);
  EXPECT_EQ(set.portals.size(), 2u);
  EXPECT_EQ(set.leakingFaces, 0u);
}

// Pieces three voxels apart along their normal are not one plane: they stay apart.
TEST(PortalMerge, PiecesOffEachOthersPlaneStayApart) {
  PortalSet set = twoRoomsThroughAWall([](int z) { return z >= 4 && z < 12; });
  set.portals = {piece(5.5f, 3.5f, 8.5f), piece(8.5f, 7.5f, 12.5f)};
  Context ctx;
  const MergedPortals m = mergePortalPieces(set, frame(), PortalMergeParams{}, ctx);
  EXPECT_EQ(m.merged, 0);
  EXPECT_EQ(set.portals.size(), 2u);
}

}  // namespace
}  // namespace cpgi::decomp
