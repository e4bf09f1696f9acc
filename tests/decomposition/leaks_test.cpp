// The leak pass (decomposition/leaks.h) on hand-made labels with known answers: a pocket of one cell
// on the other's side of their portal is relabelled; two cells whose portal does not cut them apart are
// merged; a pair without a portal is merged; the outside is never merged away.
#include <gtest/gtest.h>

#include <algorithm>

#include "decomposition/leaks.h"

namespace cpgi::decomp {
namespace {

// A 12 × 6 × 12 box of 1 m voxels, all empty (distance 1 except the border, 0), split at x = 6: cells 0
// (x < 6) and 1 (x ≥ 6), and a portal in the plane x = 5.5 over `portalZ` (z range, all y).
struct TwoCells {
  DistanceGrid distance;
  PortalSet set;
};

TwoCells twoCells(float z0, float z1) {
  TwoCells t;
  GridFrame& f = t.distance.frame;
  f.dims = {12, 6, 12};
  f.voxel = 1.0;
  t.distance.d2.assign(f.count(), 0);
  t.set.cell.assign(f.count(), -1);
  for (size_t i = 0; i < f.count(); ++i) {
    const glm::ivec3 c = f.coord(i);
    if (glm::any(glm::equal(c, glm::ivec3(0))) || glm::any(glm::equal(c, f.dims - 1))) continue;
    // Deepest in the middle of each half: the relabelling's seeds.
    t.distance.d2[i] = 1 + uint32_t(c.x == 3 || c.x == 8) * uint32_t(c.y == 3 && c.z == 6) * 8;
    t.set.cell[i] = c.x < 6 ? 0 : 1;
  }
  FittedPortal p;
  p.quad.corners = {glm::vec3(5.5f, 0.5f, z0), glm::vec3(5.5f, 4.5f, z0), glm::vec3(5.5f, 4.5f, z1),
                    glm::vec3(5.5f, 0.5f, z1)};
  computePortalFrame(p.quad);
  p.quad.normal = {1, 0, 0};
  p.quad.cellA = 0, p.quad.cellB = 1;
  t.set.portals.push_back(p);
  return t;
}

TEST(Leaks, ABulgeAcrossThePortalIsRelabelled) {
  TwoCells t = twoCells(0.5f, 10.5f);  // the portal covers the whole interface
  const GridFrame& f = t.distance.frame;
  // Cell 1 bulges a voxel past the portal's plane: its faces with cell 0 there cross no portal.
  t.set.cell[f.index(5, 2, 2)] = 1, t.set.cell[f.index(5, 2, 3)] = 1;
  ASSERT_GT(countLeakingFaces(f, t.set.cell, {t.set.portals.front().quad}), 0u);
  Context ctx;
  const ClosedLeaks c = closeLeaks(t.set, t.distance, 2, -1, LeakParams{}, ctx);
  EXPECT_EQ(c.cellCount, 2);
  EXPECT_EQ(c.relabelledPairs, 1);
  EXPECT_EQ(c.mergedPairs, 0);
  EXPECT_EQ(t.set.leakingFaces, 0u);
  EXPECT_EQ(t.set.cell[f.index(5, 2, 2)], 0);
  EXPECT_EQ(t.set.portals.size(), 1u);
  EXPECT_EQ(c.placements, 1u);  // the portal as fitted parts the two: nothing else tried
}

TEST(Leaks, APocketCutOffFromItsCellJoinsTheCellAroundIt) {
  TwoCells t = twoCells(0.5f, 10.5f);
  const GridFrame& f = t.distance.frame;
  t.set.cell[f.index(2, 2, 2)] = 1, t.set.cell[f.index(2, 2, 3)] = 1;  // inside cell 0, apart from cell 1
  Context ctx;
  const ClosedLeaks c = closeLeaks(t.set, t.distance, 2, -1, LeakParams{}, ctx);
  EXPECT_EQ(c.cellCount, 2);
  EXPECT_EQ(c.mergedPairs, 0);
  EXPECT_EQ(t.set.leakingFaces, 0u);
  EXPECT_EQ(t.set.cell[f.index(2, 2, 2)], 0);
}

TEST(Leaks, APortalBetweenCellsThatDoNotTouchIsDropped) {
  TwoCells t = twoCells(0.5f, 10.5f);
  FittedPortal stray = t.set.portals.front();
  stray.quad.cellA = 0, stray.quad.cellB = 2;  // cell 2: a few voxels walled off in a corner of cell 1
  t.set.portals.push_back(stray);
  const GridFrame& f = t.distance.frame;
  t.set.cell[f.index(10, 4, 10)] = 2;
  Context ctx;
  const ClosedLeaks c = closeLeaks(t.set, t.distance, 3, -1, LeakParams{}, ctx);
  EXPECT_EQ(c.droppedPortals, 1);
  EXPECT_EQ(t.set.portals.size(), 1u);
}

TEST(Leaks, CellsThePortalDoesNotCutApartAreMerged) {
  TwoCells t = twoCells(0.5f, 3.5f);  // most of the interface open beside the portal (more than
                                      // the two voxels the pass may grow a portal by)
  Context ctx;
  const ClosedLeaks c = closeLeaks(t.set, t.distance, 2, -1, LeakParams{}, ctx);
  EXPECT_EQ(c.cellCount, 1);
  EXPECT_EQ(c.mergedPairs, 1);
  EXPECT_EQ(c.cellOf[0], 0);
  EXPECT_EQ(c.cellOf[1], 0);
  EXPECT_TRUE(t.set.portals.empty());
  EXPECT_EQ(t.set.leakingFaces, 0u);
  for (int32_t l : t.set.cell) EXPECT_TRUE(l == -1 || l == 0);
}

TEST(Leaks, APortalAVoxelShortOfTheJambIsGrown) {
  TwoCells t = twoCells(2.5f, 10.5f);  // rows z = 1, 2 open beside the portal (z = 2 within its
                                       // half-voxel tolerance, z = 1 not)
  ASSERT_GT(countLeakingFaces(t.distance.frame, t.set.cell, {t.set.portals.front().quad}), 0u);
  Context ctx;
  const ClosedLeaks c = closeLeaks(t.set, t.distance, 2, -1, LeakParams{}, ctx);
  EXPECT_EQ(c.cellCount, 2);
  EXPECT_EQ(c.mergedPairs, 0);
  EXPECT_EQ(t.set.leakingFaces, 0u);
  float lowest = 1e9f;
  for (const glm::vec3& c : t.set.portals.front().quad.corners) lowest = std::min(lowest, c.z);
  EXPECT_NEAR(lowest, 1.5f, 1e-4f);  // grown by one voxel, not two
  // The quad as fitted, then every growth and shift (3 × 13 − 1), each one flood of the pair.
  EXPECT_EQ(c.placements, 39u);
}

TEST(Leaks, ADoorPortalPushedPastTheWallMovesBackIntoTheDoor) {
  // A wall at x = 5 with a door over z in [4, 7]; the door's portal was fitted at x = 7.5, two voxels into
  // cell 1 (furniture in front of the door made that the narrowest stretch), and cell 0 was relabelled up
  // to it: its bulge meets cell 1 edge on, beside the door.
  TwoCells t = twoCells(3.5f, 7.5f);
  const GridFrame& f = t.distance.frame;
  for (int y = 1; y < 5; ++y)
    for (int z = 1; z < 11; ++z) {
      const size_t i = f.index(5, y, z);
      const bool door = z >= 4 && z <= 7;
      t.set.cell[i] = door ? 0 : -1;
      t.distance.d2[i] = door ? 1 : 0;
      if (door) t.set.cell[f.index(6, y, z)] = 0, t.set.cell[f.index(7, y, z)] = 0;
    }
  for (glm::vec3& c : t.set.portals.front().quad.corners) c.x = 7.5f;
  ASSERT_GT(countLeakingFaces(f, t.set.cell, {t.set.portals.front().quad}), 0u);
  Context ctx;
  const ClosedLeaks c = closeLeaks(t.set, t.distance, 2, -1, LeakParams{}, ctx);
  EXPECT_EQ(c.cellCount, 2);
  EXPECT_EQ(c.mergedPairs, 0);
  EXPECT_EQ(t.set.leakingFaces, 0u);
  ASSERT_EQ(t.set.portals.size(), 1u);
  EXPECT_LT(t.set.portals.front().quad.centre().x, 6.0f);  // back in the door, not in the room
  EXPECT_EQ(t.set.cell[f.index(7, 2, 5)], 1);
}

TEST(Leaks, CellsGivenByTheUserAreNeverMerged) {
  TwoCells t = twoCells(0.5f, 3.5f);
  LeakParams keep;
  keep.merge = false;
  Context ctx;
  const ClosedLeaks c = closeLeaks(t.set, t.distance, 2, -1, keep, ctx);
  EXPECT_EQ(c.cellCount, 2);
  EXPECT_GT(t.set.leakingFaces, 0u);
}

TEST(Leaks, TheOutsideKeepsItsPlaceWhenARoomMergesIntoIt) {
  TwoCells t = twoCells(0.5f, 10.5f);
  t.set.portals.clear();  // no portal at all between the room (0) and the outside (1)
  Context ctx;
  const ClosedLeaks c = closeLeaks(t.set, t.distance, 2, 1, LeakParams{}, ctx);
  EXPECT_EQ(c.cellCount, 1);
  EXPECT_EQ(c.outsideCell, 0);  // renumbered, still the outside
  EXPECT_EQ(c.keptCell, std::vector<int32_t>{1});
  EXPECT_EQ(t.set.leakingFaces, 0u);
}

}  // namespace
}  // namespace cpgi::decomp
