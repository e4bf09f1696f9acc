// Portals moved onto their wall's mid-plane (decomposition/wall_portals.h), on hand-made labels: the moves
// are kept when they leave every face between the cells covered, and undone when they would open faces
// that no portal covers (a game level's walls meeting at angles round a doorway did that).
#include <gtest/gtest.h>

#include "decomposition/portals.h"
#include "decomposition/wall_portals.h"
#include "tests/decomposition/scene_builder.h"

namespace cpgi::decomp {
namespace {

// A 12 × 6 × 12 grid of 1 m voxels (centres at whole metres), the border solid, split at x = 5.5: cell 0
// (x ≤ 5) and cell 1 (x ≥ 6), and two portals in that plane side by side, z 0.5–5.5 and 5.5–10.5, which
// together cover every face between the cells.
PortalSet twoPortalsSideBySide(GridFrame& f) {
  f.dims = {12, 6, 12};
  f.voxel = 1.0;
  PortalSet set;
  set.cell.assign(f.count(), -1);
  for (size_t i = 0; i < f.count(); ++i) {
    const glm::ivec3 c = f.coord(i);
    if (glm::any(glm::equal(c, glm::ivec3(0))) || glm::any(glm::equal(c, f.dims - 1))) continue;
    set.cell[i] = c.x <= 5 ? 0 : 1;
  }
  for (float z0 : {0.5f, 5.5f}) {
    FittedPortal p;
    p.quad.corners = {glm::vec3(5.5f, 0.5f, z0), glm::vec3(5.5f, 4.5f, z0), glm::vec3(5.5f, 4.5f, z0 + 5.0f),
                      glm::vec3(5.5f, 0.5f, z0 + 5.0f)};
    computePortalFrame(p.quad);
    p.quad.normal = {1, 0, 0};
    p.quad.cellA = 0, p.quad.cellB = 1;
    p.depth = 0.5f;
    set.portals.push_back(p);
  }
  return set;
}

float portalX(const PortalSet& set, size_t k) {
  return set.portals[k].quad.corners[0].x;
}

// A wall 0.4 m thick whose mid-plane is x = 6.7, over z from 0 to `zTo`.
Scene wallBeside(float zTo) {
  testing::SceneBuilder b;
  b.box({6.5f, 0.0f, 0.0f}, {6.9f, 5.0f, zTo});
  return b.scene();
}

TEST(WallPortals, PortalsMoveOntoTheirWallWhenEveryFaceStaysCovered) {
  GridFrame f;
  PortalSet set = twoPortalsSideBySide(f);
  ASSERT_EQ(countLeakingFaces(f, set.cell, quadsOf(set.portals)), 0u);
  Context ctx;
  const WallSnap snap = snapPortalsToWalls(wallBeside(11.0f), f, 0.5, set, ctx);
  EXPECT_EQ(snap.moved, 2);
  EXPECT_NEAR(portalX(set, 0), 6.7f, 1e-5f);
  EXPECT_NEAR(portalX(set, 1), 6.7f, 1e-5f);
  EXPECT_EQ(set.cell[f.index(6, 2, 3)], 0);  // between the old plane and the new: now on cell 0's side
  EXPECT_EQ(set.leakingFaces, 0u);
}

TEST(WallPortals, MovesThatWouldOpenUncoveredFacesAreUndone) {
  GridFrame f;
  PortalSet set = twoPortalsSideBySide(f);
  const std::vector<int32_t> cellsAsFitted = set.cell;
  // The wall runs beside the first portal only: moving it alone takes the voxels x = 6, z ≤ 5 into cell 0,
  // and their faces with cell 1's voxels at z = 6 cross neither portal.
  Context ctx;
  const WallSnap snap = snapPortalsToWalls(wallBeside(4.0f), f, 0.5, set, ctx);
  EXPECT_EQ(snap.moved, 0);
  EXPECT_FLOAT_EQ(portalX(set, 0), 5.5f);
  EXPECT_FLOAT_EQ(portalX(set, 1), 5.5f);
  EXPECT_EQ(set.cell, cellsAsFitted);
  EXPECT_EQ(set.leakingFaces, 0u);
}

}  // namespace
}  // namespace cpgi::decomp
