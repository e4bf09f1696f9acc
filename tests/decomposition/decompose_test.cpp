// End-to-end decomposition of scenes built in code, against their known rooms and doors.
#include "decomposition/decompose.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/contact_cuts.h"
#include "core/error.h"
#include "decomposition/compare.h"
#include "decomposition/report.h"
#include "tests/decomposition/scene_builder.h"

namespace cpgi::decomp {
namespace {

using testing::makeThreeRooms;
using testing::manualThreeRooms;
using testing::SceneBuilder;
using testing::ThreeRooms;
using testing::ThreeRoomsOptions;

Decomposition run(const Scene& scene, double voxel, Context& ctx, double seal = 0.0) {
  DecomposeParams p;
  p.voxelSize = voxel;
  p.sealRadius = seal;
  return decompose(scene, p, ctx);
}

// Labels of the inside voxels by the room their centre lies in.
std::vector<int32_t> roomsByPosition(const Decomposition& d) {
  std::vector<int32_t> rooms(d.frame.count(), -1);
  for (size_t i = 0; i < rooms.size(); ++i)
    if (d.space[i] == Space::Inside) rooms[i] = ThreeRooms::roomOf(d.frame.centre(i));
  return rooms;
}

bool anyWarningContains(const Context& ctx, const std::string& text) {
  for (const std::string& w : ctx.warnings())
    if (w.find(text) != std::string::npos) return true;
  return false;
}

TEST(Decompose, ThreeRoomsGiveThreeCellsAndTwoDoorPortals) {
  Context ctx;
  const double h = 0.1;
  const Decomposition d = run(makeThreeRooms(), h, ctx);
  for (const auto& w : ctx.warnings()) ADD_FAILURE() << w;
  ASSERT_EQ(d.graph.cells.size(), 3u);
  ASSERT_EQ(d.graph.portals.size(), 2u);
  EXPECT_EQ(d.leakingFaces, 0u);
  for (const PortalQuad& q : d.graph.portals) {
    const int k = q.centre().x < 6.0f ? 1 : 2;
    EXPECT_LT(glm::length(q.centre() - ThreeRooms::doorCentre(k)), h) << q.name;
    EXPECT_GT(std::abs(q.normal.x), 0.999f) << q.name;
    EXPECT_NEAR(q.area, 2.1f, 0.25f) << q.name;  // the door is 1.0 × 2.1 m
    EXPECT_NE(q.cellA, q.cellB);
  }
  EXPECT_GE(adjustedRandIndex(d.voxelCell, roomsByPosition(d)), 0.97);
  EXPECT_TRUE(d.graph.connected());
  const CellValidation v = validateCells(d.scene, d.graph);
  EXPECT_TRUE(v.errors.empty()) << v.errors.front();
  EXPECT_TRUE(v.warnings.empty()) << v.warnings.front();
}

TEST(Decompose, FloorThroughTheDoorsIsSplitOnThePortalPlanes) {
  Context ctx;
  const Decomposition d = run(makeThreeRooms(), 0.1, ctx);
  ASSERT_EQ(d.graph.portals.size(), 2u);
  EXPECT_GE(d.splitTriangles, 4u);  // the floor's and the ceiling's two triangles each
  // Every piece of the floor's top face lies on one side of each portal plane and belongs to the room
  // on that side.
  const float x1 = std::min(d.graph.portals[0].centre().x, d.graph.portals[1].centre().x);
  const float x2 = std::max(d.graph.portals[0].centre().x, d.graph.portals[1].centre().x);
  auto roomOf = [&](const glm::vec3& p) { return p.x < x1 ? 0 : p.x < x2 ? 1 : 2; };
  std::vector<int> roomToCell(3, -1);
  const std::vector<int> cellOf = d.graph.cellOfTriangle(d.scene.triangles.size());
  for (size_t t = 0; t < d.scene.triangles.size(); ++t) {
    const Triangle& tri = d.scene.triangles[t];
    if (std::abs(tri.p[0].y) > 1e-5f || tri.geometricNormal().y < 0.99f) continue;  // floor top only
    const int room = roomOf(tri.centroid());
    for (const glm::vec3& q : tri.p) EXPECT_EQ(roomOf(q + 1e-3f * (tri.centroid() - q)), room);
    if (roomToCell[size_t(room)] < 0) roomToCell[size_t(room)] = cellOf[t];
    EXPECT_EQ(cellOf[t], roomToCell[size_t(room)]) << "floor piece " << t;
  }
  EXPECT_NE(roomToCell[0], roomToCell[1]);
  EXPECT_NE(roomToCell[1], roomToCell[2]);
}

TEST(Decompose, AgreesWithHandMadeCells) {
  Context ctx;
  ThreeRoomsOptions o;
  o.slabsPerRoom = true;
  const Scene scene = makeThreeRooms(o);
  const Decomposition d = run(scene, 0.1, ctx);
  const CellGraph manual = manualThreeRooms(scene);
  const std::vector<int32_t> labels = labelsFromCells(scene, manual, d.frame, d.space);
  EXPECT_GE(adjustedRandIndex(d.voxelCell, labels), 0.95);
  for (double iou : bestMatchIoU(labels, 3, d.voxelCell, int(d.graph.cells.size()))) EXPECT_GE(iou, 0.9);
  const std::vector<PortalMatch> m = matchPortals(manual.portals, d.graph.portals);
  ASSERT_EQ(m.size(), 2u);
  for (const PortalMatch& pm : m) {
    EXPECT_LT(pm.centreDistance, 0.1f);
    EXPECT_LT(pm.normalAngle, 1.0f);
    EXPECT_NEAR(pm.areaRatio, 1.0f, 0.15f);
  }
}

TEST(Compare, CellVolumesLabelTheVoxelsTheyEnclose) {
  // Hand-made cells given as `cellvolume:` boxes over the three rooms, split at the door mid-planes:
  // labels equal the rooms by position wherever a volume covers the voxel.
  ThreeRoomsOptions o;
  o.slabsPerRoom = true;
  const Scene scene = makeThreeRooms(o);
  Context ctx;
  const Decomposition d = run(scene, 0.1, ctx);
  // Only the volumes: no triangles to grow from, no portals to stop at.
  CellGraph manual;
  manual.cells.resize(3);
  const float cuts[4] = {0.0f, ThreeRooms::doorCentre(1).x, ThreeRooms::doorCentre(2).x, 20.0f};
  for (int c = 0; c < 3; ++c) {
    SceneBuilder box;
    box.box({cuts[c], -0.1f, -0.1f}, {cuts[c + 1], 3.1f, 4.5f});
    manual.cells[size_t(c)].volume = box.scene().triangles;
  }
  const std::vector<int32_t> labels = labelsFromCells(scene, manual, d.frame, d.space);
  const std::vector<int32_t> rooms = roomsByPosition(d);
  size_t labelled = 0, agree = 0;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (rooms[i] < 0) continue;
    labelled += labels[i] >= 0;
    agree += labels[i] == rooms[i];
  }
  EXPECT_EQ(labelled, agree);
  EXPECT_GT(
      double(labelled),
      0.99 * double(d.space.size() > 0 ? std::count(d.space.begin(), d.space.end(), Space::Inside) : 0));
}

TEST(Decompose, FurnishedRoomIsOneCell) {
  SceneBuilder b;
  b.box({-0.2f, -0.2f, -0.2f}, {5.2f, 0.0f, 4.2f});  // floor
  b.box({-0.2f, 3.0f, -0.2f}, {5.2f, 3.2f, 4.2f});   // ceiling
  b.box({-0.2f, 0, -0.2f}, {0, 3, 4.2f});
  b.box({5, 0, -0.2f}, {5.2f, 3, 4.2f});
  b.box({0, 0, -0.2f}, {5, 3, 0});
  b.box({0, 0, 4}, {5, 3, 4.2f});
  // A table with legs, a chair, a sofa, a wardrobe against a wall, a cube.
  for (float x : {1.0f, 2.4f})
    for (float z : {1.0f, 1.8f}) b.box({x, 0, z}, {x + 0.06f, 0.72f, z + 0.06f});
  b.box({0.95f, 0.72f, 0.95f}, {2.5f, 0.76f, 1.9f});
  b.box({1.5f, 0, 2.1f}, {1.95f, 0.45f, 2.55f});
  b.box({1.5f, 0.45f, 2.5f}, {1.95f, 1.0f, 2.55f});
  b.box({3.4f, 0, 0.1f}, {4.9f, 0.8f, 1.0f});
  b.box({0.05f, 0, 3.3f}, {1.3f, 2.2f, 3.95f});
  b.box({3.5f, 0, 2.8f}, {4.2f, 0.7f, 3.5f});
  Context ctx;
  const Decomposition d = run(b.scene(), 0.05, ctx);
  EXPECT_EQ(d.graph.cells.size(), 1u);
  EXPECT_EQ(d.graph.portals.size(), 0u);
  EXPECT_GT(d.basins, 1);  // the watershed did see the furniture; merging undid it
}

TEST(Decompose, LShapedCorridorIsOneCell) {
  // A 1.2 m wide, 2.5 m high corridor: 8 m along x, then 6 m along z; walls 0.2 m.
  SceneBuilder b;
  const float w = 0.2f, W = 1.2f, H = 2.5f;
  b.box({-w, -w, -w}, {8 + w, 0, 6 + w});
  b.box({-w, H, -w}, {8 + w, H + w, 6 + w});
  b.box({-w, 0, -w}, {8 + w, H, 0});     // outer wall along x
  b.box({8, 0, 0}, {8 + w, H, 6 + w});   // outer wall along z
  b.box({-w, 0, 0}, {0, H, W});          // start cap
  b.box({-w, 0, W}, {8 - W, H, 6 + w});  // the inner block
  b.box({8 - W, 0, 6}, {8, H, 6 + w});   // end cap
  Context ctx;
  const Decomposition d = run(b.scene(), 0.05, ctx);
  EXPECT_EQ(d.graph.cells.size(), 1u);
  EXPECT_EQ(d.graph.portals.size(), 0u);
}

TEST(Decompose, HallOfPillarsIsNotOverSegmented) {
  // 10 × 10 × 4 m with 0.4 m pillars every 2.5 m.
  SceneBuilder b;
  const float w = 0.2f, L = 10.0f, H = 4.0f;
  b.box({-w, -w, -w}, {L + w, 0, L + w});
  b.box({-w, H, -w}, {L + w, H + w, L + w});
  b.box({-w, 0, -w}, {0, H, L + w});
  b.box({L, 0, -w}, {L + w, H, L + w});
  b.box({0, 0, -w}, {L, H, 0});
  b.box({0, 0, L}, {L, H, L + w});
  for (int i = 1; i < 4; ++i)
    for (int k = 1; k < 4; ++k)
      b.box({2.5f * i - 0.2f, 0, 2.5f * k - 0.2f}, {2.5f * i + 0.2f, H, 2.5f * k + 0.2f});
  Context ctx;
  const Decomposition d = run(b.scene(), 0.1, ctx);
  EXPECT_EQ(d.graph.cells.size(), 1u);
  EXPECT_EQ(d.graph.portals.size(), 0u);
}

TEST(Decompose, CrackNarrowerThanTheSealIsClosed) {
  // A 0.1 m slit in the A|B wall: sealed by a 0.05 m closing (fills up to 3 voxels), open without one.
  ThreeRoomsOptions o;
  o.crackWidth = 0.1f;
  Context sealedCtx, openCtx;
  const Decomposition sealed = run(makeThreeRooms(o), 0.05, sealedCtx, 0.05);
  EXPECT_GT(sealed.sealedVoxels, 0u);
  EXPECT_EQ(sealed.graph.cells.size(), 3u);
  EXPECT_EQ(sealed.graph.portals.size(), 2u);
  EXPECT_EQ(sealed.leakingFaces, 0u);

  const Decomposition open = run(makeThreeRooms(o), 0.05, openCtx);
  EXPECT_EQ(open.graph.cells.size(), 3u);
  ASSERT_EQ(open.graph.portals.size(), 3u);  // the two doors and the crack
  EXPECT_EQ(open.leakingFaces, 0u);
  float smallest = 1e9f;
  for (const PortalQuad& q : open.graph.portals) smallest = std::min(smallest, q.area);
  EXPECT_LT(smallest, 0.6f);  // the crack: 0.1 × 3 m
}

TEST(Decompose, CrackWiderThanTheSealStaysAnOpening) {
  ThreeRoomsOptions o;
  o.crackWidth = 0.3f;
  Context ctx;
  const Decomposition d = run(makeThreeRooms(o), 0.05, ctx, 0.05);
  EXPECT_EQ(d.graph.cells.size(), 3u);
  EXPECT_EQ(d.graph.portals.size(), 3u);
  EXPECT_EQ(d.leakingFaces, 0u);
}

TEST(Decompose, OpenSceneIsOneOutsideCellWithAMessage) {
  SceneBuilder b;
  b.box({-10, -0.1f, -10}, {10, 0, 10});  // ground
  b.box({-2, 0, -2}, {2, 3, 2});          // a closed block of a house
  b.box({4, 0, 4}, {5, 1, 6});
  Context ctx;
  const Decomposition d = run(b.scene(), 0.1, ctx);
  EXPECT_FALSE(d.enclosed);
  ASSERT_EQ(d.graph.cells.size(), 1u);
  EXPECT_EQ(d.graph.cells[0].name, "outside");
  EXPECT_EQ(d.graph.cells[0].triangles.size(), d.scene.triangles.size());
  EXPECT_TRUE(anyWarningContains(ctx, "no enclosed empty space"));
}

TEST(Decompose, WallsThinnerThanAVoxelAreReported) {
  ThreeRoomsOptions o;
  o.innerWall = 0.02f;
  Context ctx;
  const Decomposition d = run(makeThreeRooms(o), 0.1, ctx);
  EXPECT_EQ(d.graph.cells.size(), 3u);
  EXPECT_EQ(d.graph.portals.size(), 2u);
  EXPECT_GT(d.thinWallArea, 10.0);  // both faces of both inner walls, less the doors: ~4 × 9.9 m²
  EXPECT_TRUE(anyWarningContains(ctx, "thinner than one voxel"));
}

TEST(Decompose, RejectsEmptyAndNonFiniteInput) {
  Context ctx;
  EXPECT_THROW(run(Scene{}, 0.1, ctx), InputError);
  Scene nan = makeThreeRooms();
  nan.triangles[5].p[1].y = std::nanf("");
  EXPECT_THROW(run(nan, 0.1, ctx), InputError);
  EXPECT_THROW(run(makeThreeRooms(), -1.0, ctx), InputError);
  EXPECT_THROW(run(makeThreeRooms(), 0.1, ctx, 5.0), InputError);
}

TEST(Decompose, ChoosesTheVoxelFromTheScene) {
  DecomposeParams p;
  std::string how;
  EXPECT_DOUBLE_EQ(chooseVoxelSize(makeThreeRooms(), p, &how), 0.05);  // ~200 m³: the floor of 5 cm
  EXPECT_NE(how.find("auto"), std::string::npos);
  SceneBuilder big;
  big.box({0, 0, 0}, {200, 20, 100});
  EXPECT_NEAR(chooseVoxelSize(big.scene(), p), std::cbrt(200.5 * 20.5 * 100.5 / 4e6), 1e-3);
}

// A game level sealed under its sky box: a hall 100 × 40 × 100 m (faces inward), and with `corridors`, six
// corridors 3 m wide and 85 m long between seven walls 2.5 m tall (15 % of the floor).
Scene hallWithCorridors(bool corridors) {
  SceneBuilder b;
  const float w = 100, h = 40;
  b.quad({0, 0, 0}, {0, 0, w}, {w, 0, w}, {w, 0, 0});  // the floor, facing up
  b.quad({0, h, 0}, {w, h, 0}, {w, h, w}, {0, h, w});  // the sky, facing down
  b.quad({0, 0, 0}, {w, 0, 0}, {w, h, 0}, {0, h, 0});  // the walls, facing in
  b.quad({0, 0, w}, {0, h, w}, {w, h, w}, {w, 0, w});
  b.quad({0, 0, 0}, {0, h, 0}, {0, h, w}, {0, 0, w});
  b.quad({w, 0, 0}, {w, 0, w}, {w, h, w}, {w, h, 0});
  for (int k = 0; corridors && k < 7; ++k) b.box({10 + 3.2f * k, 0, 5}, {10.2f + 3.2f * k, 2.5f, 90});
  return b.scene();
}

// Issue 46: a large level's voxel from its bounds (0.6–1 m) leaves its corridors fewer than the eight
// voxels a door needs; the passages measured over its floors make it finer, as far as memory allows, and
// leave it where no passage is narrow (the empty hall) or the budget's voxel is fine already (a house).
TEST(Decompose, ALargeLevelsVoxelSpansItsCorridorsWithinTheMemory) {
  DecomposeParams p;
  p.minExtentVoxel =
      0.4;  // the coarse pass that finds the rooms' extent, coarse for speed: the hall is its box
  const double volume = 100.5 * 40.5 * 100.5;
  auto millimetres = [](double v) { return std::ceil(v * 1000.0) / 1000.0; };
  Context ctx;
  const GridChoice empty = chooseGrid(hallWithCorridors(false), p, ctx);
  EXPECT_DOUBLE_EQ(empty.voxel, millimetres(std::cbrt(volume / 4e6))) << empty.how;  // 0.468 m
  const GridChoice level = chooseGrid(hallWithCorridors(true), p, ctx);
  EXPECT_NEAR(level.passage, 3.0, 1e-3) << level.how;
  EXPECT_DOUBLE_EQ(level.voxel, 0.375) << level.how;  // 8 voxels across 3 m
  EXPECT_NE(level.how.find("finer for the passages"), std::string::npos) << level.how;
  p.maxAutoVoxels = 6e6;  // memory for fewer voxels than 8 across the corridors take: as fine as it allows
  EXPECT_DOUBLE_EQ(chooseGrid(hallWithCorridors(true), p, ctx).voxel, millimetres(std::cbrt(volume / 6e6)));
  EXPECT_DOUBLE_EQ(chooseVoxelSize(makeThreeRooms(), DecomposeParams()), 0.05);
}

// The grid follows where the rooms are: a lone 2 m box 200 m away (a game level's far scenery, a shed at
// the end of a plot) and a square kilometre of terrain under the building change neither the automatic
// voxel nor the rooms' cells; the far box's triangles go to a cell, said in one warning.
Scene withFarBox(Scene scene) {
  SceneBuilder far;
  far.box({200, 0, 0}, {202, 2, 2});
  for (const Triangle& t : far.scene().triangles) scene.triangles.push_back(t);
  return scene;
}

Scene onTerrain(Scene scene) {
  SceneBuilder ground;
  ground.quad({-500, -0.5f, -500}, {-500, -0.5f, 500}, {500, -0.5f, 500}, {500, -0.5f, -500});  // facing up
  for (const Triangle& t : ground.scene().triangles) scene.triangles.push_back(t);
  return scene;
}

TEST(Decompose, AFarObjectOrATerrainLeavesTheVoxelAndTheRoomsAsTheyWere) {
  const Scene rooms = makeThreeRooms();
  DecomposeParams p;
  p.minAutoVoxel = 0.1;  // the automatic voxel's floor, for speed: the rule above it is the same
  Context ctx;
  const Decomposition alone = decompose(rooms, p, ctx);
  for (const Scene& scene : {withFarBox(rooms), onTerrain(rooms)}) {
    Context c;
    const Decomposition d = decompose(scene, p, c);
    EXPECT_DOUBLE_EQ(d.frame.voxel, alone.frame.voxel) << d.voxelChoice;
    EXPECT_NE(d.voxelChoice.find("where the rooms are"), std::string::npos) << d.voxelChoice;
    EXPECT_LT(d.frame.dims.x, alone.frame.dims.x + int(std::ceil(2 * 2.0 / d.frame.voxel)) + 1);
    EXPECT_EQ(d.leakingFaces, 0u);
    // The same rooms voxel for voxel (an outside may come with the terrain: the rooms are what count).
    std::vector<size_t> a, b;
    for (size_t k = 0; k < alone.cellStats.size(); ++k)
      if (int(k) != alone.outsideCell) a.push_back(alone.cellStats[k].voxels);
    for (size_t k = 0; k < d.cellStats.size(); ++k)
      if (int(k) != d.outsideCell) b.push_back(d.cellStats[k].voxels);
    std::sort(a.begin(), a.end()), std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);
    size_t given = 0;
    for (const Cell& cell : d.graph.cells) given += cell.triangles.size();
    EXPECT_GE(given, scene.triangles.size());  // every triangle in some cell (split ones count twice)
  }
  Context c;
  decompose(withFarBox(rooms), p, c);
  EXPECT_TRUE(anyWarningContains(c, "12 triangles lie past the grid round the rooms")) << c.warnings().size();
}

// Faces cut at their contacts (core/contact_cuts.h, as every scene is loaded) are voxelized with the pieces
// the cuts dropped put back: the decomposition is that of the faces whole. Here a 1.2 m box sunk 0.6 m
// through the floor slab of the middle room takes the floor's faces inside it away; without the pieces the
// box's inside and the slab's joined into one void (108 voxels' classes differed), and on
// OpenArena maps the level's shell opened: oa_dm2's 503 049 enclosed voxels became outside.
TEST(Decompose, FacesCutAtTheirContactsGiveTheVoxelsAndCellsOfTheFacesWhole) {
  Scene whole = makeThreeRooms();
  SceneBuilder sunk;
  sunk.box({6.0f, -0.6f, 1.2f}, {7.2f, 0.6f, 2.4f});
  whole.triangles.insert(whole.triangles.end(), sunk.scene().triangles.begin(), sunk.scene().triangles.end());
  Scene cut = whole;
  CellGraph none;
  const ContactCuts cuts = cutAtContacts(cut, none);
  ASSERT_GT(cuts.buriedArea, 1.0);
  ASSERT_FALSE(cut.buriedPieces.empty());
  Context a, b;
  const Decomposition fromWhole = run(whole, 0.09, a), fromCut = run(cut, 0.09, b);
  ASSERT_EQ(fromCut.frame.dims, fromWhole.frame.dims);
  size_t spaceDiffers = 0, cellDiffers = 0;
  for (size_t i = 0; i < fromWhole.space.size(); ++i)
    spaceDiffers += fromCut.space[i] != fromWhole.space[i],
        cellDiffers += fromCut.voxelCell[i] != fromWhole.voxelCell[i];
  EXPECT_EQ(spaceDiffers, 0u);
  EXPECT_EQ(cellDiffers, 0u);
  EXPECT_EQ(fromCut.graph.cells.size(), fromWhole.graph.cells.size());
  EXPECT_EQ(fromCut.graph.portals.size(), fromWhole.graph.portals.size());
  EXPECT_EQ(fromCut.leakingFaces, 0u);
  // The cells hold the cut faces, not the buried pieces.
  size_t given = 0;
  for (const Cell& cell : fromCut.graph.cells) given += cell.triangles.size();
  EXPECT_GE(given, cut.triangles.size());
  EXPECT_EQ(fromCut.inputTriangles, cut.triangles.size());
}

}  // namespace
}  // namespace cpgi::decomp

namespace cpgi::decomp {
namespace {

// A hollow box of 0.2 m slabs round the empty box [lo, hi].
void closedRoom(SceneBuilder& b, glm::vec3 lo, glm::vec3 hi) {
  const float t = 0.2f;
  b.box({lo.x - t, lo.y - t, lo.z - t}, {hi.x + t, lo.y, hi.z + t});  // floor
  b.box({lo.x - t, hi.y, lo.z - t}, {hi.x + t, hi.y + t, hi.z + t});  // ceiling
  b.box({lo.x - t, lo.y, lo.z - t}, {lo.x, hi.y, hi.z + t});
  b.box({hi.x, lo.y, lo.z - t}, {hi.x + t, hi.y, hi.z + t});
  b.box({lo.x, lo.y, lo.z - t}, {hi.x, hi.y, lo.z});
  b.box({lo.x, lo.y, hi.z}, {hi.x, hi.y, hi.z + t});
}

// Issue 46: a cell with no portal says what it is. Beside the three rooms, a sealed 2.5 m room is a
// closed room (kind closed_room, the rooms still all reachable), and a sealed cupboard of 1 × 1 × 1.8 m
// (1.8 m3, under the 2.5 m3 minimum) is no cell at all.
TEST(Decompose, ASealedRoomIsAClosedRoomAndACupboardNoCell) {
  Scene scene = testing::makeThreeRooms();
  SceneBuilder extra;
  closedRoom(extra, {14.0f, 0.0f, 0.5f}, {16.5f, 2.5f, 3.0f});
  closedRoom(extra, {14.0f, 0.0f, 4.0f}, {15.0f, 1.8f, 5.0f});
  for (const Triangle& t : extra.scene().triangles) scene.triangles.push_back(t);
  Context ctx;
  const Decomposition d = run(scene, 0.1, ctx);
  ASSERT_EQ(d.graph.cells.size(), 4u);  // three rooms and the sealed room
  int closed = -1;
  for (size_t c = 0; c < d.graph.cells.size(); ++c)
    if (d.closedRoom[c]) {
      EXPECT_EQ(closed, -1);
      closed = int(c);
    }
  ASSERT_GE(closed, 0);
  EXPECT_GT(d.cellStats[size_t(closed)].bounds.lo.x, 13.9f);
  EXPECT_TRUE(d.graph.portalsOf(closed).empty());
  EXPECT_TRUE(d.connectedOpen);
  EXPECT_FALSE(d.graph.connected());
  // Said as what it is: every cell reachable or a closed room, the three rooms reachable, it not.
  EXPECT_TRUE(d.reachableOrClosed);
  for (size_t c = 0; c < d.graph.cells.size(); ++c) EXPECT_EQ(bool(d.reachable[c]), int(c) != closed) << c;
  EXPECT_EQ(d.leakingFaces, 0u);
  EXPECT_TRUE(anyWarningContains(ctx, "is a closed room"));
  EXPECT_EQ(graphSummary(d),
            "graph: 2 parts — the main one of 3 cells joined by portals, one closed room with "
            "no opening (" +
                d.graph.cells[size_t(closed)].name + ": lit by its own lamps alone)");
}

// Issue 46 (oa_dm1 at 0.15 m): a sealed flat cavity, 4 × 0.4 × 4 m inside (6.4 m3, over the minimum
// cell volume), was a closed room; nowhere 0.7 m across, it is no cell at all.
TEST(Decompose, ASealedFlatCavityIsNoCell) {
  Scene scene = testing::makeThreeRooms();
  SceneBuilder extra;
  closedRoom(extra, {14.0f, 0.5f, 0.5f}, {18.0f, 0.9f, 4.5f});
  for (const Triangle& t : extra.scene().triangles) scene.triangles.push_back(t);
  Context ctx;
  const Decomposition d = run(scene, 0.1, ctx);
  EXPECT_EQ(d.graph.cells.size(), 3u);
  for (char closed : d.closedRoom) EXPECT_FALSE(closed);
  EXPECT_TRUE(d.graph.connected());
  EXPECT_EQ(d.leakingFaces, 0u);
}

// Issue 46 (kaos, oa_shouse, islanddm at 0.4–0.56 m voxels): a sealed cavity one voxel thick inside (a
// hollow pillar's, a brush's; here 1.4 m between faces, two layers of 0.4 m voxels once the faces' own
// voxels are solid) has its voxels 0.4 m from the nearest solid voxel's centre, over the 0.35 m minimum
// peak at any voxel that coarse: it was a closed room. Its surface lies half a voxel nearer than those
// centres; with that it is no cell.
TEST(Decompose, ASealedCavityOneVoxelThickIsNoCellAtACoarseVoxel) {
  SceneBuilder b;
  b.box({0.0f, 0.0f, 0.0f}, {8.0f, 3.0f, 8.0f});                      // a room
  b.box({1.0f, 3.4f, 1.0f}, {5.0f, 4.8f, 5.0f});                      // the cavity over its ceiling
  for (Triangle& t : b.scene().triangles) std::swap(t.p[1], t.p[2]);  // faces looking in, as a level's
  DecomposeParams p;
  p.voxelSize = 0.4;
  p.merge.minClosedPeak = 0.35 - 0.5 * p.voxelSize;  // the rule as it was: the peak against 0.35 m
  p.merge.minClosedPeakVoxels = 0.0;                 // and none in voxels
  Context before;
  const Decomposition kept = decompose(b.scene(), p, before);
  ASSERT_EQ(kept.graph.cells.size(), 2u);
  EXPECT_TRUE(kept.closedRoom[0] && kept.closedRoom[1]);

  p.merge.minClosedPeak = MergeParams().minClosedPeak;
  Context ctx;
  const Decomposition d = decompose(b.scene(), p, ctx);
  ASSERT_EQ(d.graph.cells.size(), 1u);
  EXPECT_LT(d.cellStats[0].bounds.hi.y, 3.5f);  // the room
}

// Issue 46 (oa_shine at 0.77 m, wrackdm17 at 1.17 m): at a voxel that coarse a brush's inside whose faces
// the compiler partly dropped (a platform's band with no top or bottom between two plates looking at it,
// the wedge under a ramp) is a sealed cavity two voxels thick, 1.6 m between faces: its peak, one voxel,
// is over 0.35 m even less half a voxel, and it was a closed room. Every voxel of it touches the solid,
// the grid resolves no space in it: no cell. A sealed 3.6 m box beside it, resolved, stays a closed room,
// and at a house's voxel the same cavity is one too.
TEST(Decompose, ASealedCavityTwoVoxelsThickIsNoCellAtAGameLevelsVoxel) {
  SceneBuilder b;
  b.box({0.0f, 0.0f, 0.0f}, {16.0f, 6.0f, 16.0f});                    // the level's room
  b.box({2.0f, 6.5f, 2.0f}, {10.0f, 8.1f, 10.0f});                    // the slab over its ceiling
  b.box({18.0f, 0.0f, 2.0f}, {21.6f, 3.6f, 5.6f});                    // a sealed room beside it
  for (Triangle& t : b.scene().triangles) std::swap(t.p[1], t.p[2]);  // faces looking in, as a level's
  DecomposeParams p;
  p.voxelSize = 0.8;
  p.merge.minClosedPeakVoxels = 0.0;  // the rule as it was
  Context before;
  const Decomposition kept = decompose(b.scene(), p, before);
  ASSERT_EQ(kept.graph.cells.size(), 3u);
  for (size_t c = 0; c < 3; ++c) EXPECT_TRUE(kept.closedRoom[c]) << c;

  p.merge.minClosedPeakVoxels = MergeParams().minClosedPeakVoxels;
  Context ctx;
  const Decomposition d = decompose(b.scene(), p, ctx);
  ASSERT_EQ(d.graph.cells.size(), 2u);
  for (size_t c = 0; c < 2; ++c) {
    EXPECT_TRUE(d.closedRoom[c]) << c;
    EXPECT_LT(d.cellStats[c].bounds.hi.y, 6.2f) << c;  // the room and the sealed box, not the slab
  }
  EXPECT_TRUE(d.reachableOrClosed);

  p.voxelSize = 0.2;
  Context fine;
  EXPECT_EQ(decompose(b.scene(), p, fine).graph.cells.size(), 3u);
}

// A scene whose every space is too thin for a room at its voxel keeps them: a decomposition of no cell
// said "the whole scene is one outside cell" with no cell at all.
TEST(Decompose, ASceneOfOneThinSealedCavityKeepsItAsItsCell) {
  SceneBuilder b;
  b.box({0.0f, 0.0f, 0.0f}, {8.0f, 1.6f, 8.0f});
  for (Triangle& t : b.scene().triangles) std::swap(t.p[1], t.p[2]);  // faces looking in
  DecomposeParams p;
  p.voxelSize = 0.8;
  Context ctx;
  const Decomposition d = decompose(b.scene(), p, ctx);
  ASSERT_EQ(d.graph.cells.size(), 1u);
  EXPECT_TRUE(d.closedRoom[0]);
  EXPECT_EQ(d.graph.cells[0].triangles.size(), 12u);
}

// A game level's hall as its drawn faces: floor, ceiling and three walls facing in; its fourth side is a
// wall no face shows (a compiled map leaves out the faces no player sees), which the level's seal gives as
// a solid. Issue 46: without the seal the outside flooded the playable space of sealed maps, unsaid.
struct UnsealedHall {
  Scene scene;
  std::vector<Triangle> seal;
};
UnsealedHall makeUnsealedHall() {
  const float L = 6.0f, H = 3.0f;
  SceneBuilder b;
  b.quad({0, 0, 0}, {0, 0, L}, {L, 0, L}, {L, 0, 0});  // floor, up
  b.quad({0, H, 0}, {L, H, 0}, {L, H, L}, {0, H, L});  // ceiling, down
  b.quad({L, 0, 0}, {L, 0, L}, {L, H, L}, {L, H, 0});  // x = L, facing −x
  b.quad({0, 0, 0}, {L, 0, 0}, {L, H, 0}, {0, H, 0});  // z = 0, facing +z
  b.quad({0, 0, L}, {0, H, L}, {L, H, L}, {L, 0, L});  // z = L, facing −z
  SceneBuilder wall;
  wall.box({-0.4f, -0.4f, -0.4f}, {0.0f, H + 0.4f, L + 0.4f});
  return {b.scene(), wall.scene().triangles};
}

TEST(Decompose, ASealClosesWhatTheFacesLeaveOpenAndALeakedLevelIsSaidSo) {
  const UnsealedHall hall = makeUnsealedHall();
  const std::string leaked = "of the empty space under a roof";
  {
    Context ctx;
    const Decomposition d = run(hall.scene, 0.1, ctx);
    EXPECT_GT(d.covered.outsideShare(), 0.9);
    EXPECT_TRUE(anyWarningContains(ctx, leaked));
    size_t said = 0;
    for (const std::string& w : ctx.warnings()) said += w.find(leaked) != std::string::npos;
    EXPECT_EQ(said, 1u);  // one line
  }
  Scene sealed = hall.scene;
  sealed.seal = hall.seal;
  Context ctx;
  const Decomposition d = run(sealed, 0.1, ctx);
  EXPECT_FALSE(anyWarningContains(ctx, leaked));
  EXPECT_LT(d.covered.outsideShare(), 0.05);
  ASSERT_TRUE(d.enclosed);
  // The hall is one room, holding the hall's faces and none of the seal's.
  int rooms = 0;
  for (size_t c = 0; c < d.graph.cells.size(); ++c)
    if (int(c) != d.outsideCell) {
      ++rooms;
      EXPECT_NEAR(d.cellStats[c].volume, 6.0 * 6.0 * 3.0, 15.0);
      EXPECT_EQ(d.graph.cells[c].triangles.size(), hall.scene.triangles.size());
    }
  EXPECT_EQ(rooms, 1);
  EXPECT_EQ(d.scene.triangles.size(), hall.scene.triangles.size());
}

}  // namespace
}  // namespace cpgi::decomp
