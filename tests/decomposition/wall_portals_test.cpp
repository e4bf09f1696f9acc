// Portals moved onto their wall's mid-plane (decomposition/wall_portals.h), on hand-made labels: the moves
// are kept when they leave every face between the cells covered, and undone when they would open faces
// that no portal covers (a game level's walls meeting at angles round a doorway did that).
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "decomposition/portals.h"
#include "decomposition/wall_portals.h"
#include "tests/decomposition/scene_builder.h"

namespace cpgi::decomp {
namespace {

// A 12 × 6 × 12 grid of 1 m voxels (centres at whole metres), the border and the voxels `solid` says
// solid, the rest split at x = 5.5: cell 0 (x ≤ 5) and cell 1 (x ≥ 6). No portals yet.
template <typename Solid>
PortalSet twoCells(GridFrame& f, Solid solid) {
  f.dims = {12, 6, 12};
  f.voxel = 1.0;
  PortalSet set;
  set.cell.assign(f.count(), -1);
  for (size_t i = 0; i < f.count(); ++i) {
    const glm::ivec3 c = f.coord(i);
    if (glm::any(glm::equal(c, glm::ivec3(0))) || glm::any(glm::equal(c, f.dims - 1)) || solid(c)) continue;
    set.cell[i] = c.x <= 5 ? 0 : 1;
  }
  return set;
}

// Two cells (twoCells), and two portals in their plane side by side, z 0.5–5.5 and 5.5–10.5, which
// together cover every face between the cells.
PortalSet twoPortalsSideBySide(GridFrame& f) {
  PortalSet set = twoCells(f, [](const glm::ivec3&) { return false; });
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

// A door (y 0.5–4.5, z 2.5–8.5) in a zero-thickness wall at x = 5.5, the wall's voxels either side solid
// beside it, and the portal fitted to the voxels askew: the door's rectangle turned 3° about y and 3° about z
// (as plan 20's R1:R4 was fitted 2.3° off its wall by a corner, up to 15 cm off the wall's plane). Left
// askew, the portal cut R4's strip of wall by the door into R1's cell; pressed onto the wall as it was, its
// corners were no longer a rectangle, which a cell's atlas charts as two loose triangles.
TEST(WallPortals, AnAskewPortalIsFlattenedOntoItsZeroThicknessWallAsARectangle) {
  GridFrame f;
  // The wall's voxels beside the door are solid.
  PortalSet set =
      twoCells(f, [](const glm::ivec3& c) { return (c.x == 5 || c.x == 6) && (c.z <= 2 || c.z >= 9); });
  const glm::mat4 turn = glm::rotate(glm::rotate(glm::mat4(1.0f), glm::radians(3.0f), glm::vec3(0, 1, 0)),
                                     glm::radians(3.0f), glm::vec3(0, 0, 1));
  const glm::vec3 centre(5.5f, 2.5f, 5.5f);
  FittedPortal p;
  int k = 0;
  for (const glm::vec2 yz : {glm::vec2(-2, -3), glm::vec2(2, -3), glm::vec2(2, 3), glm::vec2(-2, 3)})
    p.quad.corners[size_t(k++)] = centre + glm::vec3(turn * glm::vec4(0.0f, yz.x, yz.y, 0.0f));
  computePortalFrame(p.quad);
  ASSERT_LT(std::abs(p.quad.normal.x), 0.999f);
  p.quad.cellA = 0, p.quad.cellB = 1;
  p.depth = 0.5f;
  set.portals.push_back(p);
  set.leakingFaces = countLeakingFaces(f, set.cell, quadsOf(set.portals));
  testing::SceneBuilder b;  // the wall's two faces each side of the door, under it and over it, back to back
  const auto wallFaces = [&b](glm::vec2 y, glm::vec2 z) {
    b.quad({5.5f, y.x, z.x}, {5.5f, y.y, z.x}, {5.5f, y.y, z.y}, {5.5f, y.x, z.y});
    b.quad({5.5f, y.x, z.x}, {5.5f, y.x, z.y}, {5.5f, y.y, z.y}, {5.5f, y.y, z.x});
  };
  for (const glm::vec2 z : {glm::vec2(0.5f, 2.5f), glm::vec2(8.5f, 10.5f)}) wallFaces({0.0f, 5.0f}, z);
  wallFaces({0.0f, 0.5f}, {2.5f, 8.5f});
  wallFaces({4.5f, 5.0f}, {2.5f, 8.5f});
  Context ctx;
  const WallSnap snap = snapPortalsToWalls(b.scene(), f, 0.5, set, ctx);
  EXPECT_EQ(snap.moved, 1);
  const PortalQuad& q = set.portals[0].quad;
  for (const glm::vec3& c : q.corners) EXPECT_NEAR(c.x, 5.5f, 1e-5f);
  EXPECT_NEAR(std::abs(q.normal.x), 1.0f, 1e-6f);
  const glm::vec3 u = q.corners[1] - q.corners[0], v = q.corners[3] - q.corners[0];
  EXPECT_LT(std::abs(glm::dot(glm::normalize(u), glm::normalize(v))), 1e-5f) << "not a rectangle";
  EXPECT_NEAR(glm::length(q.corners[2] - q.corners[1] - v), 0.0f, 1e-5f);
  // Over the door, on the edges of the wall's faces round it (not on the 2 cm steps off them, nor turned).
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& c : q.corners) lo = glm::min(lo, c), hi = glm::max(hi, c);
  EXPECT_NEAR(lo.z, 2.5f, 1e-5f);
  EXPECT_NEAR(hi.z, 8.5f, 1e-5f);
  EXPECT_NEAR(lo.y, 0.5f, 1e-5f);
  EXPECT_NEAR(hi.y, 4.5f, 1e-5f);
  EXPECT_EQ(snap.fittedToOpening, 1);
  EXPECT_EQ(set.leakingFaces, 0u);
}

// A window (y 1.2–3.3, z 2.3–8.6) through a wall 0.4 m thick at x 5.3–5.7, its portal fitted to the
// voxels' lattice in the wall's mid-plane at y 1.5–3.5, z 2.5–8.5: 0.3 m over the sill, 0.2 m into the
// lintel, 0.2 m off one jamb. The light a cell sends through the gap over the sill left both cells (a room
// behind a window 5.6 % too dark with the automatic cells). Each edge moves onto the reveal beside it.
TEST(WallPortals, APortalsEdgesMoveOntoTheOpeningsSillJambsAndLintel) {
  GridFrame f;
  PortalSet set = twoCells(f, [](const glm::ivec3& c) {
    return (c.x == 5 || c.x == 6) && (c.y <= 1 || c.y >= 4 || c.z <= 2 || c.z >= 9);
  });
  FittedPortal p;
  p.quad.corners = {glm::vec3(5.5f, 1.5f, 2.5f), glm::vec3(5.5f, 3.5f, 2.5f), glm::vec3(5.5f, 3.5f, 8.5f),
                    glm::vec3(5.5f, 1.5f, 8.5f)};
  computePortalFrame(p.quad);
  p.quad.normal = {1, 0, 0};
  p.quad.cellA = 0, p.quad.cellB = 1;
  p.depth = 0.5f;
  set.portals.push_back(p);
  ASSERT_EQ(countLeakingFaces(f, set.cell, quadsOf(set.portals)), 0u);
  testing::SceneBuilder b;  // the wall round the window: under it, over it, either side
  b.box({5.3f, 0.0f, 2.3f}, {5.7f, 1.2f, 8.6f});
  b.box({5.3f, 3.3f, 2.3f}, {5.7f, 5.0f, 8.6f});
  b.box({5.3f, 0.0f, 0.0f}, {5.7f, 5.0f, 2.3f});
  b.box({5.3f, 0.0f, 8.6f}, {5.7f, 5.0f, 11.0f});
  Context ctx;
  const WallSnap snap = snapPortalsToWalls(b.scene(), f, 0.5, set, ctx);
  EXPECT_EQ(snap.fittedToOpening, 1);
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& c : set.portals[0].quad.corners) lo = glm::min(lo, c), hi = glm::max(hi, c);
  EXPECT_NEAR(lo.x, 5.5f, 1e-5f);
  EXPECT_NEAR(hi.x, 5.5f, 1e-5f);
  EXPECT_NEAR(lo.y, 1.2f, 1e-5f);
  EXPECT_NEAR(hi.y, 3.3f, 1e-5f);
  EXPECT_NEAR(lo.z, 2.3f, 1e-5f);
  EXPECT_NEAR(hi.z, 8.6f, 1e-5f);
  EXPECT_NEAR(set.portals[0].quad.area, 2.1f * 6.3f, 1e-4f);
  EXPECT_EQ(set.leakingFaces, 0u);
}

}  // namespace
}  // namespace cpgi::decomp
