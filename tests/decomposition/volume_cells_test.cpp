// Cells from room volumes alone (issue 12 item 3): the buildings' rooms given only as their cellvolume:
// boxes become cells with portals in every opening and every surface in the room it faces.
#include <gtest/gtest.h>

#include <map>

#include "decomposition/compare.h"
#include "decomposition/volume_cells.h"
#include "scenes/buildings.h"

namespace cpgi::decomp {
namespace {

// The building's hand-made cells reduced to what an IFC export gives: the rooms' volumes.
CellGraph volumesOf(const Building& b) {
  CellGraph g;
  for (const Cell& c : b.seed.cells.cells)
    if (!c.volume.empty()) g.cells.push_back(Cell{c.name, {}, c.volume});
  return g;
}

Decomposition fromVolumes(const Building& b, double voxel) {
  DecomposeParams p;
  p.voxelSize = voxel;
  p.sourceName = "building";
  Context ctx;
  return decomposeFromVolumes(b.seed.scene, volumesOf(b), p, {}, ctx);
}

// The share of the surface area given to the room that owns it in the generator (the first part of its
// node's path: the room in front of it, or "outside").
double areaInOwnRoom(const Decomposition& d) {
  double right = 0.0, all = 0.0;
  const std::vector<int> cellOf = d.graph.cellOfTriangle(d.scene.triangles.size());
  for (size_t t = 0; t < d.scene.triangles.size(); ++t) {
    const Triangle& tri = d.scene.triangles[t];
    const std::string& path = d.scene.nodePaths[tri.node];
    const std::string owner = path.substr(0, path.find('/'));
    all += tri.area();
    if (cellOf[t] >= 0 && d.graph.cells[size_t(cellOf[t])].name == owner) right += tri.area();
  }
  return right / all;
}

// A portal of the decomposition within `tolerance` metres of each opening's own portal, joining the same
// two cells.
void expectPortalPerOpening(const Building& b, const Decomposition& d, float tolerance) {
  for (const PortalQuad& made : b.seed.cells.portals) {
    const std::string a = b.seed.cells.cells[size_t(made.cellA)].name,
                      c = b.seed.cells.cells[size_t(made.cellB)].name;
    bool found = false;
    for (const PortalQuad& q : d.graph.portals) {
      const std::string qa = d.graph.cells[size_t(q.cellA)].name, qb = d.graph.cells[size_t(q.cellB)].name;
      const bool same = (qa == a && qb == c) || (qa == c && qb == a);
      if (same && glm::length(q.centre() - made.centre()) < tolerance) found = true;
    }
    EXPECT_TRUE(found) << made.name << " at " << made.centre().x << ", " << made.centre().y << ", "
                       << made.centre().z;
  }
}

TEST(VolumeCells, OpenHouseRoomsBecomeCellsWithAPortalPerOpening) {
  const Building b = makeOpenHouse();
  const Decomposition d = fromVolumes(b, 0.1);
  ASSERT_EQ(d.graph.cells.size(), b.rooms.size() + 1);
  for (size_t r = 0; r < b.rooms.size(); ++r) EXPECT_EQ(d.graph.cells[r].name, b.seed.cells.cells[r].name);
  EXPECT_EQ(d.graph.cells.back().name, "outside");
  EXPECT_EQ(d.outsideCell, int(b.rooms.size()));
  EXPECT_EQ(d.graph.portals.size(), b.openings.size());
  expectPortalPerOpening(b, d, 0.15f);
  EXPECT_EQ(d.leakingFaces, 0u);
  EXPECT_TRUE(d.graph.connected());
  EXPECT_EQ(validateCells(d.scene, d.graph).warnings.size(), 0u);  // every triangle in a cell
  EXPECT_GE(areaInOwnRoom(d), 0.98);
}

TEST(VolumeCells, TwoStoreysMeetAtTheStairsHole) {
  for (const bool spiral : {false, true}) {
    SCOPED_TRACE(spiral ? "spiral" : "straight");
    const Building b = makeTwoStoreyHouse(spiral);
    const Decomposition d = fromVolumes(b, 0.1);
    EXPECT_EQ(d.graph.cells.size(), b.rooms.size() + 1);
    expectPortalPerOpening(b, d, 0.3f);
    EXPECT_EQ(d.leakingFaces, 0u);
    EXPECT_GE(areaInOwnRoom(d), 0.95);
  }
}

TEST(VolumeCells, ClosedHouseHasNoOutsideCell) {
  const Building b = makeTwoStoreyHouse(false, true);
  const Decomposition d = fromVolumes(b, 0.1);
  EXPECT_EQ(d.outsideCell, -1);
  EXPECT_EQ(d.graph.cells.size(), b.rooms.size());
  EXPECT_EQ(d.graph.portals.size(), b.openings.size());
}

TEST(VolumeCells, VolumesHoldingNothingAreRefused) {
  Building b = makeOpenHouse();
  CellGraph far;
  Cell c{"far", {}, {}};
  for (Triangle t : b.seed.cells.cells.front().volume) {
    for (glm::vec3& p : t.p) p += glm::vec3(1000.0f);
    c.volume.push_back(t);
  }
  far.cells.push_back(c);
  DecomposeParams p;
  p.voxelSize = 0.1;
  Context ctx;
  EXPECT_THROW(decomposeFromVolumes(b.seed.scene, far, p, {}, ctx), InputError);
}

TEST(VolumeCells, OverlappingBoxesOfOneRoomFillTheirUnion) {
  // Two overlapping boxes given as one volume: the parity of the union's crossings would leave the
  // overlap out; filled piece by piece it is in.
  GridFrame f;
  f.origin = glm::dvec3(0.05);
  f.voxel = 0.1;
  f.dims = glm::ivec3(30, 10, 10);
  const std::vector<Space> space(f.count(), Space::Inside);
  std::vector<Triangle> mesh;
  auto box = [&](glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    for (const auto& q : quads) {
      Triangle t;
      t.p = {c[q[0]], c[q[1]], c[q[2]]};
      mesh.push_back(t);
      t.p = {c[q[0]], c[q[2]], c[q[3]]};
      mesh.push_back(t);
    }
  };
  box({0.0f, 0.0f, 0.0f}, {2.0f, 1.0f, 1.0f});
  box({1.0f, 0.0f, 0.0f}, {3.0f, 1.0f, 1.0f});
  std::vector<int32_t> label(f.count(), -1);
  labelVolumeVoxels(mesh, f, space, 7, label);
  EXPECT_EQ(label[f.index(f.voxelOf(glm::vec3(1.5f, 0.5f, 0.5f)))], 7);  // the overlap
  EXPECT_EQ(label[f.index(f.voxelOf(glm::vec3(0.5f, 0.5f, 0.5f)))], 7);
  EXPECT_EQ(label[f.index(f.voxelOf(glm::vec3(2.5f, 0.5f, 0.5f)))], 7);
}

TEST(VolumeCells, InteriorLabelsCountWhatEitherSideLeavesOut) {
  // A labels the whole interior as two rooms; B only the first half of one room. Scored over the
  // interior (either side's rooms), B's missing part is a "no room" cluster of its own.
  const std::vector<int32_t> a = {0, 0, 0, 0, 1, 1, 1, 1, 2, -1};  // 2: A's outside
  const std::vector<int32_t> b = {0, 0, -1, -1, -1, -1, -1, -1, -1, -1};
  const InteriorLabels in = interiorLabels(a, 3, 2, b, 1, -1);
  EXPECT_EQ(in.interior, 8u);
  EXPECT_EQ(in.both, 2u);
  EXPECT_DOUBLE_EQ(in.coverageA(), 1.0);
  EXPECT_DOUBLE_EQ(in.coverageB(), 0.25);
  EXPECT_EQ(in.b[2], 1);   // B's "no room"
  EXPECT_EQ(in.a[8], -1);  // A's outside, B nothing: not interior
  EXPECT_LT(adjustedRandIndex(in.a, in.b), 0.5);
}

}  // namespace
}  // namespace cpgi::decomp
