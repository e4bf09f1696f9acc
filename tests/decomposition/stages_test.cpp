// Each stage on its own, against brute force or closed forms.
#include <random>

#include <gtest/gtest.h>

#include "decomposition/classify.h"
#include "decomposition/compare.h"
#include "decomposition/distance.h"
#include "decomposition/merge.h"
#include "decomposition/portals.h"
#include "decomposition/voxelize.h"
#include "decomposition/watershed.h"
#include "tests/decomposition/scene_builder.h"

namespace cpgi::decomp {
namespace {

// A solid grid from a predicate over voxel coordinates, every voxel classified by classifySpace's rule
// for scenes without triangles: here everything not solid and not on the border is made inside.
struct Synthetic {
  SolidGrid solid;
  SpaceGrid space;
};

template <typename IsSolid>
Synthetic synthetic(glm::ivec3 dims, IsSolid isSolid) {
  Synthetic s;
  s.solid.frame.dims = dims;
  s.solid.frame.voxel = 1.0;
  s.solid.solid.assign(s.solid.frame.count(), 0);
  s.solid.nearestTriangle.assign(s.solid.frame.count(), -1);
  s.space.frame = s.solid.frame;
  s.space.space.assign(s.solid.frame.count(), Space::Outside);
  for (size_t i = 0; i < s.solid.solid.size(); ++i) {
    const glm::ivec3 c = s.solid.frame.coord(i);
    const bool border = glm::any(glm::equal(c, glm::ivec3(0))) || glm::any(glm::equal(c, dims - 1));
    s.solid.solid[i] = !border && isSolid(c);
    s.space.space[i] = border ? Space::Outside : s.solid.solid[i] ? Space::Solid : Space::Inside;
  }
  return s;
}

// The cells of a distance field: its watershed's basins merged with `params`.
CellLabels mergedCells(const DistanceGrid& d, const MergeParams& params = {}) {
  Context ctx;
  return mergeBasins(floodWatershed(d, {}, ctx), params, ctx);
}

TEST(Distance, MatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const glm::ivec3 dims(13, 9, 11);
  std::vector<char> pattern(size_t(dims.x * dims.y * dims.z));
  for (char& c : pattern) c = u(rng) < 0.04f;
  const Synthetic s = synthetic(
      dims, [&](glm::ivec3 c) { return pattern[size_t((c.z * dims.y + c.y) * dims.x + c.x)] != 0; });
  Context ctx;
  const DistanceGrid d = distanceToGeometry(s.solid, s.space, ctx);
  const GridFrame& f = s.solid.frame;
  for (size_t i = 0; i < f.count(); ++i) {
    // Every empty voxel, the outside's included (the watershed floods it too), has its distance.
    if (s.space.space[i] != Space::Inside && s.space.space[i] != Space::Outside) {
      EXPECT_EQ(d.d2[i], 0u);
      continue;
    }
    uint32_t best = UINT32_MAX;
    for (size_t j = 0; j < f.count(); ++j)
      if (s.solid.solid[j]) {
        const glm::ivec3 e = f.coord(i) - f.coord(j);
        best = std::min(best, uint32_t(e.x * e.x + e.y * e.y + e.z * e.z));
      }
    ASSERT_EQ(d.d2[i], best) << "voxel " << i;
  }
}

TEST(Watershed, TwoChambersMeetAtTheDoorHalfWidth) {
  // Two 21³ chambers joined through a 1-voxel wall by a 7 × 7 hole: the basins meet in the hole, whose
  // centre is 4 voxels from the nearest solid voxel (the hole's rim), so the saddle is 4 voxels.
  const glm::ivec3 dims(47, 25, 25);
  const Synthetic s = synthetic(dims, [](glm::ivec3 c) {
    const bool shell = c.x == 1 || c.x == 45 || c.y == 1 || c.y == 23 || c.z == 1 || c.z == 23;
    const bool wall = c.x == 23 && !(std::abs(c.y - 12) <= 3 && std::abs(c.z - 12) <= 3);
    return shell || wall;
  });
  Context ctx;
  const DistanceGrid d = distanceToGeometry(s.solid, s.space, ctx);
  const WatershedLabels w = floodWatershed(d, {}, ctx);
  ASSERT_GE(w.basinCount(), 2);
  const CellLabels cells = mergeBasins(w, {}, ctx);
  ASSERT_EQ(cells.cellCount(), 2);
  // The chambers' centres are 11 voxels from their walls.
  EXPECT_FLOAT_EQ(cells.peak[0], 11.0f);
  EXPECT_FLOAT_EQ(cells.peak[1], 11.0f);
  float saddle = 0.0f;
  for (const BasinContact& c : w.contacts)
    if (cells.cellOfBasin[size_t(c.a)] != cells.cellOfBasin[size_t(c.b)]) saddle = std::max(saddle, c.saddle);
  EXPECT_FLOAT_EQ(saddle, 4.0f);
  // Each chamber is one cell, split at the wall.
  const GridFrame& f = d.frame;
  EXPECT_NE(cells.cell[f.index(12, 12, 12)], cells.cell[f.index(34, 12, 12)]);
  for (int x : {2, 10, 20}) EXPECT_EQ(cells.cell[f.index(x, 5, 18)], cells.cell[f.index(12, 12, 12)]);
  for (int x : {26, 35, 44}) EXPECT_EQ(cells.cell[f.index(x, 5, 18)], cells.cell[f.index(34, 12, 12)]);
}

TEST(Merge, WideOpeningMergesNarrowOneDoesNot) {
  // The same chambers with the hole widened to 17 × 17: no longer a constriction.
  const glm::ivec3 dims(47, 25, 25);
  const Synthetic s = synthetic(dims, [](glm::ivec3 c) {
    const bool shell = c.x == 1 || c.x == 45 || c.y == 1 || c.y == 23 || c.z == 1 || c.z == 23;
    const bool wall = c.x == 23 && !(std::abs(c.y - 12) <= 8 && std::abs(c.z - 12) <= 8);
    return shell || wall;
  });
  Context ctx;
  const DistanceGrid d = distanceToGeometry(s.solid, s.space, ctx);
  EXPECT_EQ(mergedCells(d).cellCount(), 1);
  // With every merge rule switched off but the saddle ratio at its maximum, the raw basins survive.
  MergeParams keep;
  keep.saddleRatio = 1.0, keep.minDepth = 0.0, keep.openingRatio = 0.0, keep.minCellVolume = 0.0;
  EXPECT_GE(mergedCells(d, keep).cellCount(), 2);
}

TEST(Merge, StoreysStayApartThroughAWideHoleInTheFloor) {
  // Two 21 × 21 voxel storeys, 10 and 11 voxels high, over a 2-voxel slab with a 10 × 14 hole: the
  // hole's saddle is nearly a storey's half-height (the saddle rule alone merges them, as it merged an
  // L-shaped stair's storeys), but it covers under half a floor seen from above.
  const glm::ivec3 dims(25, 27, 25);
  const Synthetic s = synthetic(dims, [](glm::ivec3 c) {
    const bool shell = c.x == 1 || c.x == 23 || c.z == 1 || c.z == 23 || c.y == 1 || c.y == 25;
    const bool hole = c.x >= 3 && c.x <= 12 && c.z >= 3 && c.z <= 16;
    return shell || ((c.y == 12 || c.y == 13) && !hole);
  });
  Context ctx;
  const DistanceGrid d = distanceToGeometry(s.solid, s.space, ctx);
  const CellLabels cells = mergedCells(d);
  ASSERT_EQ(cells.cellCount(), 2);
  const GridFrame& f = d.frame;
  EXPECT_NE(cells.cell[f.index(18, 6, 18)], cells.cell[f.index(18, 19, 18)]);
  MergeParams noStoreys;
  noStoreys.storeySpread = 0.0;
  EXPECT_EQ(mergedCells(d, noStoreys).cellCount(), 1);
}

TEST(Merge, AGalleryStaysApartFromTheDoubleHeightRoomItOverlooks) {
  // In 0.25 m voxels, a double-height room 20 × 23 × 21 voxels and beside it a gallery 11 × 11 × 21 (2.75 m
  // high) on a slab 12 voxels (3 m) up, open to it over a parapet along their whole shared wall (8 × 21
  // open): the opening is 0.9 of the gallery's cross-section, past the opening ratio, but their floors
  // stand a storey apart.
  const glm::ivec3 dims(36, 27, 25);
  Synthetic s = synthetic(dims, [](glm::ivec3 c) {
    const bool shell = c.x == 1 || c.x == 34 || c.y == 1 || c.y == 25 || c.z == 1 || c.z == 23;
    const bool parapet = c.x == 22 && c.y <= 16;
    const bool underGallery = c.x > 22 && c.y <= 13;
    return shell || parapet || underGallery;
  });
  s.solid.frame.voxel = s.space.frame.voxel = 0.25;
  Context ctx;
  const DistanceGrid d = distanceToGeometry(s.solid, s.space, ctx);
  const CellLabels cells = mergedCells(d);
  ASSERT_EQ(cells.cellCount(), 2);
  const GridFrame& f = d.frame;
  EXPECT_NE(cells.cell[f.index(12, 6, 12)], cells.cell[f.index(28, 18, 12)]);
  EXPECT_EQ(cells.cell[f.index(12, 22, 12)], cells.cell[f.index(12, 6, 12)]);
  MergeParams noGalleries;
  noGalleries.galleryFloorRise = 0.0;
  EXPECT_EQ(mergedCells(d, noGalleries).cellCount(), 1);
  // A space higher than a storey over its floor (a platform open to a game level's sky box) is no gallery:
  // with the headroom under this one's 1.4 m the opening ratio merges them again.
  MergeParams lowHeadroom;
  lowHeadroom.galleryHeadroom = 1.0;
  EXPECT_EQ(mergedCells(d, lowHeadroom).cellCount(), 1);
}

TEST(Voxelize, ThinRotatedShellDoesNotLeak) {
  // A closed 3 m cube of single-sided inward faces, turned by awkward angles: the 6-connected outside
  // flood must not get in, whatever the planes' orientation against the grid.
  for (float angle : {0.0f, 0.3f, 0.7853f, 1.1f}) {
    testing::SceneBuilder b;
    const float c = std::cos(angle), s = std::sin(angle);
    auto rot = [&](glm::vec3 p) {
      return glm::vec3(c * p.x - s * p.y, s * c * p.x + c * c * p.y - s * p.z,
                       s * s * p.x + s * c * p.y + c * p.z);
    };
    const glm::vec3 lo(-1.5f), hi(1.5f);
    const glm::vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    auto quadIn = [&](int a, int bb, int cc, int d) { b.quad(rot(p[d]), rot(p[cc]), rot(p[bb]), rot(p[a])); };
    quadIn(0, 3, 2, 1), quadIn(4, 5, 6, 7), quadIn(0, 4, 7, 3), quadIn(1, 2, 6, 5), quadIn(0, 1, 5, 4),
        quadIn(3, 7, 6, 2);
    Context ctx;
    VoxelizeParams vp;
    vp.voxelSize = 0.1;
    const SolidGrid solid = voxelize(b.scene(), vp, ctx);
    const SpaceGrid space = classifySpace(b.scene(), solid, {}, ctx);
    EXPECT_EQ(space.insideComponents, 1) << "angle " << angle;
    // ~27 m³ less the half-voxel skin: at least 2.8³ m³ of 1e-3 m³ voxels.
    EXPECT_GT(double(space.insideVoxels), 2.8 * 2.8 * 2.8 / 1e-3) << "angle " << angle;
  }
}

TEST(Compare, AdjustedRandIndexKnownValues) {
  const std::vector<int32_t> a{0, 0, 0, 1, 1, 1}, b{0, 0, 1, 1, 2, 2};
  // Contingency [[2,1,0],[0,1,2]]: Σ C(n_ij,2) = 2, rows 6, columns 3, C(6,2) = 15:
  // (2 − 6·3/15) / (4.5 − 1.2) = 0.8 / 3.3.
  EXPECT_NEAR(adjustedRandIndex(a, b), 0.8 / 3.3, 1e-12);
  EXPECT_DOUBLE_EQ(adjustedRandIndex(a, a), 1.0);
  const std::vector<int32_t> renamed{5, 5, 5, 2, 2, 2};
  EXPECT_DOUBLE_EQ(adjustedRandIndex(a, renamed), 1.0);
  const std::vector<int32_t> withUnlabelled{0, 0, 0, 1, 1, -1};  // -1 positions do not count
  EXPECT_DOUBLE_EQ(adjustedRandIndex(withUnlabelled, a), 1.0);
  const std::vector<double> iou = bestMatchIoU(a, 2, b, 3);
  EXPECT_NEAR(iou[0], 2.0 / 3.0, 1e-12);  // {0,1,2} vs {0,1}: 2 / 3
  EXPECT_NEAR(iou[1], 2.0 / 3.0, 1e-12);
}

TEST(Compare, PortalMatchMeasures) {
  PortalQuad ref, cand;
  ref.corners = {glm::vec3(0, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, 2, 1), glm::vec3(0, 2, 0)};
  computePortalFrame(ref);
  const float t = 0.1f;  // the candidate: moved 0.1 m, tilted by atan(0.1), 1.5 × the area
  cand.corners = {glm::vec3(0.1f, 0, 0), glm::vec3(0.1f + t * 1.5f, 0, 1.5f),
                  glm::vec3(0.1f + t * 1.5f, 2, 1.5f), glm::vec3(0.1f, 2, 0)};
  computePortalFrame(cand);
  const auto m = matchPortals({ref}, {cand});
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].candidate, 0);
  EXPECT_NEAR(m[0].normalAngle, std::atan(t) * 180.0 / M_PI, 1e-3);
  EXPECT_NEAR(m[0].areaRatio, 1.5f * std::sqrt(1.0f + t * t), 1e-4);
  EXPECT_NEAR(m[0].centreDistance, glm::length(cand.centre() - ref.centre()), 1e-6);
}

// A column of one cell standing through another: the interface wraps round it, its faces look both ways
// along x and y in equal numbers, and their mean direction is zero. Normalised, that was NaN, and CGAL's
// exact rectangle fit crashed on it (SIGFPE in GMP) on OpenArena's aggressor. Whatever it fits must be
// finite.
TEST(Portals, AnInterfaceWrappedRoundAColumnFitsAFiniteQuad) {
  CellLabels cells;
  cells.frame.dims = {7, 5, 6};
  cells.frame.voxel = 0.1;
  cells.cell.assign(cells.frame.count(), 1);
  for (int z = 0; z < cells.frame.dims.z; ++z) cells.cell[cells.frame.index(3, 2, z)] = 0;
  cells.peak = {0.2f, 0.2f};
  cells.volume = {6u, uint32_t(cells.frame.count() - 6)};
  DistanceGrid distance;
  distance.frame = cells.frame;
  distance.d2.assign(cells.frame.count(), 4u);
  distance.maxD2 = 4u;
  Context ctx;
  const PortalSet set = fitPortals(cells, distance, PortalParams{}, ctx);
  for (const FittedPortal& p : set.portals)
    for (const glm::vec3& c : p.quad.corners) EXPECT_TRUE(std::isfinite(c.x + c.y + c.z));
}

}  // namespace
}  // namespace cpgi::decomp
