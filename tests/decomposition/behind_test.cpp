// Space behind the geometry is no room (decomposition/behind.h), on levels built the way a Quake map is:
// one-sided faces towards the playable space only, nothing towards the void.
#include <gtest/gtest.h>

#include "decomposition/decompose.h"
#include "tests/decomposition/scene_builder.h"

namespace cpgi::decomp {
namespace {

using testing::SceneBuilder;

// The faces added since `from`, turned over (a box's outward faces become a room's inward ones).
void flipFrom(SceneBuilder& b, size_t from) {
  for (size_t t = from; t < b.scene().triangles.size(); ++t) {
    Triangle& tri = b.scene().triangles[t];
    std::swap(tri.p[1], tri.p[2]);
    const glm::vec3 n = tri.geometricNormal();
    tri.n = {n, n, n};
  }
}

// A room as a game level has it: six one-sided faces looking in, no wall thickness behind them.
void levelRoom(SceneBuilder& b, glm::vec3 lo, glm::vec3 hi) {
  const size_t from = b.scene().triangles.size();
  b.box(lo, hi);
  flipFrom(b, from);
}

// The back of a brush: a hollow box [lo, hi] whose faces look out of it (its inside sees only their
// backs), with a square hole of side `hole` in the middle of its +x face.
void hollowBrush(SceneBuilder& b, glm::vec3 lo, glm::vec3 hi, float hole) {
  const glm::vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  b.quad(p[0], p[3], p[2], p[1]);  // -z
  b.quad(p[4], p[5], p[6], p[7]);  // +z
  b.quad(p[0], p[4], p[7], p[3]);  // -x
  b.quad(p[0], p[1], p[5], p[4]);  // -y
  b.quad(p[3], p[7], p[6], p[2]);  // +y
  // +x, round the hole: four quads facing +x.
  const float x = hi.x, ym = 0.5f * (lo.y + hi.y), zm = 0.5f * (lo.z + hi.z), r = 0.5f * hole;
  auto face = [&](float y0, float y1, float z0, float z1) {
    b.quad({x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1});
  };
  face(lo.y, ym - r, lo.z, hi.z);
  face(ym + r, hi.y, lo.z, hi.z);
  face(ym - r, ym + r, lo.z, zm - r);
  face(ym - r, ym + r, zm + r, hi.z);
}

Decomposition run(const Scene& scene, Context& ctx, double backToFront = BehindParams().backToFront,
                  double apartBackToFront = BehindParams().apartBackToFront) {
  DecomposeParams p;
  p.voxelSize = 0.1;
  p.behind.backToFront = backToFront;
  p.behind.apartBackToFront = apartBackToFront;
  return decompose(scene, p, ctx);
}

// A sealed level's pocket folded into the outside, which then meets no room: the level one room, whole.
void expectThePocketFoldedIntoTheOutside(const Decomposition& d) {
  EXPECT_EQ(d.foldedBehind, 1);
  EXPECT_EQ(d.outsideCell, -1);
  ASSERT_EQ(d.graph.cells.size(), 1u);
  EXPECT_TRUE(d.graph.connected());
  EXPECT_EQ(d.leakingFaces, 0u);
}

// Issue 46 (oa_dm1, oa_dm7): a sealed level's space behind its walls, reached from the void through a
// narrow gap, was a cell of its own that only the outside reached; the outside then was a cell apart from
// the rooms and the graph was not connected. It is the outside: folded into it, and the outside, meeting
// no room, is no cell, as round any closed building.
TEST(BehindGeometry, ASealedLevelsPocketBehindItsWallsIsTheOutside) {
  SceneBuilder b;
  levelRoom(b, {0, 0, 0}, {6, 3, 6});
  hollowBrush(b, {7, 0, 0}, {10, 3, 3}, 0.4f);
  Context before;
  const Decomposition kept = run(b.scene(), before, 0.0);  // the stage off: as before it
  ASSERT_GE(kept.outsideCell, 0);
  EXPECT_FALSE(kept.graph.connected());
  Context ctx;
  const Decomposition d = run(b.scene(), ctx);
  expectThePocketFoldedIntoTheOutside(d);
  EXPECT_NEAR(d.cellStats[0].volume, 6.0 * 3.0 * 6.0, 20.0);
}

// The cell of a brush in the corner of a 6 × 3 × 6 m room (the one under 10 m³), or −1.
int brushCell(const Decomposition& d) {
  for (size_t c = 0; c < d.graph.cells.size(); ++c)
    if (d.cellStats[c].volume < 10.0) return int(c);
  return -1;
}

// That room is the one cell left, round a brush of side w in its corner whose voxels are no cell's.
void expectTheRoomRoundTheBrushAlone(const Decomposition& d, float w) {
  ASSERT_EQ(d.graph.cells.size(), 1u);
  EXPECT_NEAR(d.cellStats[0].volume, 6.0 * 3.0 * 6.0 - w * w * 3.0, 10.0);
  EXPECT_EQ(d.voxelCell[d.frame.index(d.frame.voxelOf({0.7f, 1.5f, 0.7f}))], -1);
  EXPECT_EQ(d.leakingFaces, 0u);
}

// Issue 46 (kaos, ctf_inyard, oasago2): a brush in a room's corner, floor to ceiling, whose two faces look
// into the room; the compiler leaves the room's walls, floor and ceiling behind it. Its inside is closed
// and looks at the fronts of four of its sides and the backs of two, so the behind stage keeps it, and
// it was a closed room that no triangle faces (the room's big faces and the brush's own look into the
// room). It is solid matter: dropped, its voxels unlabelled, the room the one cell left.
TEST(BehindGeometry, ABrushsClosedInsideThatNoFaceLooksIntoIsNoRoom) {
  SceneBuilder b;
  levelRoom(b, {0, 0, 0}, {6, 3, 6});
  const float w = 1.5f;  // the brush's side: its inside holds about 5 m3, over the minimum cell
  b.quad({w, 0, 0}, {w, 3, 0}, {w, 3, w}, {w, 0, w});  // the brush's +x face, looking into the room
  b.quad({0, 0, w}, {w, 0, w}, {w, 3, w}, {0, 3, w});  // its +z face
  DecomposeParams p;
  p.voxelSize = 0.1;
  p.behind.apartBackToFront = 0.0;  // the behind stage's second pass drops it too: this is the last stage
  p.dropUnfacedClosedCells = false;
  Context before;
  const Decomposition kept = decompose(b.scene(), p, before);
  ASSERT_EQ(kept.graph.cells.size(), 2u);
  EXPECT_EQ(kept.foldedBehind, 0);
  const int pocket = brushCell(kept);
  ASSERT_GE(pocket, 0);
  EXPECT_TRUE(kept.graph.cells[size_t(pocket)].triangles.empty());
  EXPECT_TRUE(kept.closedRoom[size_t(pocket)]);

  p.dropUnfacedClosedCells = true;
  Context ctx;
  const Decomposition d = decompose(b.scene(), p, ctx);
  EXPECT_EQ(d.droppedUnfaced, 1);
  expectTheRoomRoundTheBrushAlone(d, w);
}

// Issue 46 (aggressor): a slab of space behind a room's wall, opening into the room through a gap, was
// a cell joined to the room by slivers. It folds into the room it opens onto; the room keeps its
// portal to the room beside it.
TEST(BehindGeometry, ASpaceBehindAWallOpeningIntoARoomFoldsIntoIt) {
  SceneBuilder b;
  levelRoom(b, {0, 0, 0}, {8, 3, 8});
  hollowBrush(b, {1, 0.5f, 1}, {4, 2.5f, 4}, 0.4f);  // a brush standing in the room, its face holed
  Context before;
  const Decomposition kept = run(b.scene(), before, 0.0);
  ASSERT_EQ(kept.graph.cells.size(), 2u);
  EXPECT_FALSE(kept.graph.portals.empty());
  Context ctx;
  const Decomposition d = run(b.scene(), ctx);
  EXPECT_EQ(d.foldedBehind, 1);
  ASSERT_EQ(d.graph.cells.size(), 1u);
  EXPECT_TRUE(d.graph.portals.empty());
  EXPECT_EQ(d.leakingFaces, 0u);
}

// Issue 46 (kaos, oa_rpg3dm2, oa_dm2's crawl space): a detail brush in a room's corner, floor to ceiling,
// with the room's walls, floor and ceiling under it kept as faces of their own (the compiler splits them
// at the brush's edges and culls none behind a detail brush). Its inside looks at the fronts of those
// and the backs of the brush's two faces — about 1 behind in 3, under the first pass's 1 in 2 — and,
// given triangles, it was a closed room. It is solid matter: dropped by the second pass, apart from the
// rooms, its voxels unlabelled.
TEST(BehindGeometry, ADetailBrushsInsideLookingAtTheWallsBehindItIsNoRoom) {
  SceneBuilder b;
  levelRoom(b, {0, 0, 0}, {6, 3, 6});
  const float w = 1.5f;
  b.quad({w, 0, 0}, {w, 3, 0}, {w, 3, w}, {w, 0, w});  // the brush's +x face, looking into the room
  b.quad({0, 0, w}, {w, 0, w}, {w, 3, w}, {0, 3, w});  // its +z face
  const size_t under = b.scene().triangles.size();
  b.box({0, 0, 0}, {w, 3, w});  // the room's faces behind it: its walls', floor's and ceiling's pieces
  flipFrom(b, under);
  auto& tris = b.scene().triangles;  // less its +x and +z faces (box order -z +z -x +x -y +y), the brush's
  tris.erase(tris.begin() + long(under + 6), tris.begin() + long(under + 8));
  tris.erase(tris.begin() + long(under + 2), tris.begin() + long(under + 4));
  Context before;
  const Decomposition kept = run(b.scene(), before, BehindParams().backToFront, 0.0);
  ASSERT_EQ(kept.graph.cells.size(), 2u);
  const int brush = brushCell(kept);
  ASSERT_GE(brush, 0);
  EXPECT_FALSE(kept.graph.cells[size_t(brush)].triangles.empty());
  EXPECT_TRUE(kept.closedRoom[size_t(brush)]);

  Context ctx;
  const Decomposition d = run(b.scene(), ctx);
  EXPECT_EQ(d.foldedBehind, 1);
  expectTheRoomRoundTheBrushAlone(d, w);
}

// Issue 46 (oa_dm2, oa_dm5): a sealed level's pocket that the void reaches through a gap, bounded by the
// backs of two walls and the fronts of four faces that look into it (1 behind in 3): the first pass
// keeps it, and it was a cell that only the outside reached (an outside pocket, the graph not
// connected). Apart from the level's rooms, it is folded into the outside, which then meets no room.
TEST(BehindGeometry, ASealedLevelsPocketLookingAtSomeFrontsIsTheOutside) {
  SceneBuilder b;
  levelRoom(b, {0, 0, 0}, {6, 3, 6});
  const size_t from = b.scene().triangles.size();
  hollowBrush(b, {7, 0, 0}, {10, 3, 3}, 0.4f);
  // Its -z, +z, -y and +y faces (hollowBrush's 1st, 2nd, 4th and 5th quads) turned to look into it.
  for (size_t t : {from + 0, from + 1, from + 2, from + 3, from + 6, from + 7, from + 8, from + 9}) {
    Triangle& tri = b.scene().triangles[t];
    std::swap(tri.p[1], tri.p[2]);
    const glm::vec3 n = tri.geometricNormal();
    tri.n = {n, n, n};
  }
  Context before;
  const Decomposition kept = run(b.scene(), before, BehindParams().backToFront, 0.0);
  ASSERT_GE(kept.outsideCell, 0);
  EXPECT_EQ(kept.foldedBehind, 0);
  EXPECT_FALSE(kept.graph.connected());
  EXPECT_FALSE(kept.reachableOrClosed);  // the pocket and the outside: apart from the room, not closed

  Context ctx;
  const Decomposition d = run(b.scene(), ctx);
  expectThePocketFoldedIntoTheOutside(d);
  EXPECT_TRUE(d.reachableOrClosed);
}

// Folding needs rooms in front of the geometry to trust its faces' sides: in a model whose faces all
// point away from the space (a flipped export) every cell looks behind the geometry, and none is folded.
TEST(BehindGeometry, NothingFoldsWithoutRoomsInFrontOfTheGeometry) {
  SceneBuilder b;
  b.box({0, 0, 0}, {6, 3, 6});  // outward faces: the room inside sees their backs
  hollowBrush(b, {7, 0, 0}, {10, 3, 3}, 0.4f);
  Context ctx;
  const Decomposition d = run(b.scene(), ctx);
  EXPECT_EQ(d.foldedBehind, 0);
}

}  // namespace
}  // namespace cpgi::decomp
