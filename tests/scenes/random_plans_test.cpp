// The random floor plans over a few fixed seeds: every plan valid (rooms in range, apart, inside the
// footprint; openings inside the walls they pierce; every room reachable from a lamp; hand-made cells and
// portals that validate), the variety the bench counts on (thick and zero-thickness walls, doors beside a
// corner, windows, rooms two and three openings from any lamp), deterministic for a seed, and closed: the
// automatic decomposition finds about the plan's rooms and no outside.
#include "scenes/random_plans.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "decomposition/decompose.h"

namespace cpgi {
namespace {

const uint64_t kSeeds[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};

bool overlap1(float a0, float a1, float b0, float b1) {
  return std::min(a1, b1) - std::max(a0, b0) > 1e-4f;
}

TEST(RandomPlans, RoomsInRangeApartAndInsideTheFootprint) {
  for (uint64_t seed : kSeeds) {
    const RandomPlan p = randomPlanLayout({seed, 0});
    ASSERT_GE(p.rooms.size(), 3u) << seed;
    ASSERT_LE(p.rooms.size(), 12u) << seed;
    for (size_t i = 0; i < p.rooms.size(); ++i) {
      const PlanRoom& a = p.rooms[i];
      EXPECT_GE(a.lo.x, 0.0f);
      EXPECT_GE(a.lo.y, 0.0f);
      EXPECT_LE(a.hi.x, p.footprint.x + 1e-4f);
      EXPECT_LE(a.hi.y, p.footprint.y + 1e-4f);
      EXPECT_GE(std::min(a.hi.x - a.lo.x, a.hi.y - a.lo.y), 2.2f - 1e-4f) << seed << " " << a.name;
      for (size_t j = i + 1; j < p.rooms.size(); ++j) {
        const PlanRoom& b = p.rooms[j];
        EXPECT_FALSE(overlap1(a.lo.x, a.hi.x, b.lo.x, b.hi.x) && overlap1(a.lo.y, a.hi.y, b.lo.y, b.hi.y))
            << "seed " << seed << ": " << a.name << " overlaps " << b.name;
      }
    }
  }
}

TEST(RandomPlans, TheRoomCountIsTheOneAskedFor) {
  for (int rooms = 3; rooms <= 12; ++rooms)
    EXPECT_EQ(randomPlanLayout({7, rooms}).rooms.size(), size_t(rooms));
  EXPECT_THROW(randomPlanLayout({7, 2}), std::invalid_argument);
  EXPECT_THROW(randomPlanLayout({7, 13}), std::invalid_argument);
}

// Each opening lies in the wall between its two rooms: room a's high face and room b's low face on its
// axis, inside the stretch both rooms share, under the ceiling; doors 0.6–2 m wide from the floor, windows
// with a sill; walls 0 or 0.1–0.3 m thick; two openings in one wall never meet.
TEST(RandomPlans, OpeningsLieInsideTheWallsTheyPierce) {
  for (uint64_t seed : kSeeds) {
    const RandomPlan p = randomPlanLayout({seed, 0});
    for (const PlanOpening& o : p.openings) {
      const PlanRoom &a = p.rooms[size_t(o.a)], &b = p.rooms[size_t(o.b)];
      const int t = o.axis == 0 ? 1 : 0;  // the wall's direction in (x, z)
      const int n = o.axis == 0 ? 0 : 1;
      EXPECT_NEAR(o.faceA, a.hi[n], 1e-4f);
      EXPECT_NEAR(o.faceB, b.lo[n], 1e-4f);
      const float thickness = o.faceB - o.faceA;
      EXPECT_TRUE(thickness < 1e-4f || (thickness > 0.1f - 1e-4f && thickness < 0.3f + 1e-4f)) << thickness;
      EXPECT_GE(o.t0, std::max(a.lo[t], b.lo[t]) - 1e-4f) << seed;
      EXPECT_LE(o.t1, std::min(a.hi[t], b.hi[t]) + 1e-4f) << seed;
      EXPECT_LT(o.y1, p.height);
      if (o.window) {
        EXPECT_GT(o.y0, 0.5f);
        EXPECT_GE(o.t1 - o.t0, 0.6f - 1e-4f);
      } else {
        EXPECT_EQ(o.y0, 0.0f);
        EXPECT_GE(o.t1 - o.t0, 0.6f - 1e-4f) << seed;
        EXPECT_LE(o.t1 - o.t0, 2.0f + 1e-4f) << seed;
      }
      for (const PlanOpening& q : p.openings)
        if (&q != &o && q.a == o.a && q.b == o.b) {
          EXPECT_FALSE(overlap1(o.t0, o.t1, q.t0, q.t1)) << seed;
        }
    }
  }
}

TEST(RandomPlans, EveryRoomIsReachedFromALampAndSomeRoomsOnlyThroughTwoOrThreeOpenings) {
  int two = 0, three = 0;
  for (uint64_t seed : kSeeds) {
    const RandomPlan p = randomPlanLayout({seed, 0});
    const std::vector<int> d = openingsFromLamp(p);
    for (int k : d) EXPECT_GE(k, 0) << "seed " << seed << ": a room no opening joins to a lamp";
    const size_t lit = size_t(std::count(d.begin(), d.end(), 0));
    EXPECT_GE(lit, 1u);
    EXPECT_LT(lit, p.rooms.size()) << "seed " << seed << ": a lamp in every room";
    two += int(std::count(d.begin(), d.end(), 2));
    three += int(std::count(d.begin(), d.end(), 3));
  }
  EXPECT_GE(two, 6);
  EXPECT_GE(three, 2);
}

// The variety the bench's distribution needs, over the seeds: both kinds of wall, doors beside a corner
// (within 0.1 m of where the shared stretch ends), windows, wide and narrow doors.
TEST(RandomPlans, TheSeedsTogetherHoldEveryKindOfWallAndOpening) {
  int thin = 0, thick = 0, corner = 0, windows = 0, narrow = 0, wide = 0;
  for (uint64_t seed : kSeeds) {
    const RandomPlan p = randomPlanLayout({seed, 0});
    for (const PlanOpening& o : p.openings) {
      (o.faceB - o.faceA < 1e-4f ? thin : thick)++;
      windows += o.window;
      if (o.window) continue;
      narrow += o.t1 - o.t0 < 0.9f;
      wide += o.t1 - o.t0 > 1.5f;
      const PlanRoom &a = p.rooms[size_t(o.a)], &b = p.rooms[size_t(o.b)];
      const int t = o.axis == 0 ? 1 : 0;
      corner += o.t0 - std::max(a.lo[t], b.lo[t]) < 0.1f + 1e-4f ||
                std::min(a.hi[t], b.hi[t]) - o.t1 < 0.1f + 1e-4f;
    }
  }
  EXPECT_GT(thin, 0);
  EXPECT_GT(thick, 0);
  EXPECT_GT(corner, 2);
  EXPECT_GE(windows, int(std::size(kSeeds)));
  EXPECT_GT(narrow, 0);
  EXPECT_GT(wide, 0);
}

TEST(RandomPlans, CellsAndPortalsValidateAndEveryTriangleIsInARoom) {
  for (uint64_t seed : kSeeds) {
    const RandomPlan p = randomPlanLayout({seed, 0});
    const SeedScene s = buildRandomPlan(p);
    ASSERT_EQ(s.cells.cells.size(), p.rooms.size());
    ASSERT_EQ(s.cells.portals.size(), p.openings.size());
    const CellValidation v = validateCells(s.scene, s.cells);
    EXPECT_TRUE(v.errors.empty()) << seed << ": " << v.errors.front();
    EXPECT_TRUE(v.warnings.empty()) << seed << ": " << v.warnings.front();
    for (int c : s.cells.cellOfTriangle(s.scene.triangles.size())) EXPECT_GE(c, 0);
    for (const Cell& c : s.cells.cells) EXPECT_EQ(c.volume.size(), 12u);
    for (size_t i = 0; i < p.openings.size(); ++i) {
      const PortalQuad& q = s.cells.portals[i];
      const PlanOpening& o = p.openings[i];
      EXPECT_NEAR(q.area, (o.t1 - o.t0) * (o.y1 - o.y0), 1e-3f);
      EXPECT_NEAR(q.centre()[o.axis], o.midPlane(), 1e-4f);
      EXPECT_NEAR(q.normal[o.axis], 1.0f, 1e-5f);  // from a to b
    }
    EXPECT_EQ(s.scene.cameras.size(), p.rooms.size());
  }
}

// Closed: the faces' area-weighted normals cancel (every face has its opposite, through the openings'
// reveals too), and the lamps are only in the rooms the layout lights.
TEST(RandomPlans, TheInteriorIsClosedAndLitOnlyWhereTheLayoutSays) {
  for (uint64_t seed : kSeeds) {
    const RandomPlan p = randomPlanLayout({seed, 0});
    const SeedScene s = buildRandomPlan(p);
    const std::vector<int> cell = s.cells.cellOfTriangle(s.scene.triangles.size());
    glm::dvec3 normals(0.0);
    double area = 0.0;
    std::set<int> lit;
    for (size_t t = 0; t < s.scene.triangles.size(); ++t) {
      const Triangle& tri = s.scene.triangles[t];
      if (s.scene.materials[tri.material].isEmitter()) {
        lit.insert(cell[t]);
        continue;
      }
      normals += glm::dvec3(tri.geometricNormal()) * double(tri.area());
      area += tri.area();
    }
    EXPECT_LT(glm::length(normals), 1e-5 * area) << seed;
    for (size_t r = 0; r < p.rooms.size(); ++r) EXPECT_EQ(lit.count(int(r)) > 0, p.rooms[r].lamp) << seed;
  }
}

TEST(RandomPlans, DeterministicForASeedAndDifferentAcrossSeeds) {
  const SeedScene a = makeRandomPlan({5, 0}), b = makeRandomPlan({5, 0}), c = makeRandomPlan({6, 0});
  ASSERT_EQ(a.scene.triangles.size(), b.scene.triangles.size());
  for (size_t t = 0; t < a.scene.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(a.scene.triangles[t].p[k], b.scene.triangles[t].p[k]);
  for (size_t m = 0; m < a.scene.materials.size(); ++m)
    EXPECT_EQ(a.scene.materials[m].albedo, b.scene.materials[m].albedo);
  const RandomPlan p5 = randomPlanLayout({5, 0}), p6 = randomPlanLayout({6, 0});
  EXPECT_TRUE(p5.footprint != p6.footprint || p5.rooms.size() != p6.rooms.size() ||
              a.scene.triangles.size() != c.scene.triangles.size());
}

// No leak: the watershed finds the plan's rooms (within one or two: a 2 m door in a short wall may join
// two rooms, a long room may split), none of them open to an outside, and no voxel face between two cells
// outside a portal.
TEST(RandomPlans, TheAutomaticDecompositionFindsTheRoomsAndNoOutside) {
  for (uint64_t seed : {1, 3, 8}) {
    const RandomPlan p = randomPlanLayout({seed, 5});
    const SeedScene s = buildRandomPlan(p);
    decomp::DecomposeParams params;
    params.voxelSize = 0.1;
    Context ctx;
    const decomp::Decomposition d = decomp::decompose(s.scene, params, ctx);
    EXPECT_EQ(d.outsideCell, -1) << seed;
    EXPECT_TRUE(d.enclosed) << seed;
    EXPECT_EQ(d.leakingFaces, 0u) << seed;
    EXPECT_TRUE(d.connectedOpen) << seed;
    EXPECT_NEAR(double(d.graph.cells.size()), double(p.rooms.size()), 1.0) << seed;
    // Each automatic portal over one of the plan's openings is that opening's rectangle: its edges on the
    // sill, jambs and lintel, not on the voxels' lattice (a gap left the cells' light out).
    int matched = 0;
    for (const PortalQuad& q : d.graph.portals) {
      glm::vec3 lo(1e9f), hi(-1e9f);
      for (const glm::vec3& c : q.corners) lo = glm::min(lo, c), hi = glm::max(hi, c);
      for (const PortalQuad& own : s.cells.portals) {
        glm::vec3 ownLo(1e9f), ownHi(-1e9f);
        for (const glm::vec3& c : own.corners) ownLo = glm::min(ownLo, c), ownHi = glm::max(ownHi, c);
        const glm::bvec3 overlaps = glm::lessThan(glm::max(lo, ownLo), glm::min(hi, ownHi) + 1e-3f);
        if (!glm::all(overlaps) || std::abs(glm::dot(q.normal, own.normal)) < 0.999f) continue;
        ++matched;
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(lo[k], ownLo[k], 2e-3f) << seed << " " << q.name << " axis " << k;
          EXPECT_NEAR(hi[k], ownHi[k], 2e-3f) << seed << " " << q.name << " axis " << k;
        }
      }
    }
    EXPECT_GE(matched, int(d.graph.portals.size()) - 1) << seed;
  }
}

}  // namespace
}  // namespace cpgi
