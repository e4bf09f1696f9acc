#include "scenes/seed_scenes.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/quads.h"

namespace cpgi {
namespace {

TEST(SeedScenes, QuadCountsNearTheThesis) {
  // Thesis: 42, 90, 1224 quads. Ours: interior faces only, door reveals split at the portal plane.
  const size_t expected[3] = {44, 74, 1204};
  for (int level = 1; level <= 3; ++level) {
    const SeedScene s = makeSeedScene(level);
    const QuadSet q = findQuads(s.scene);
    EXPECT_EQ(q.quads.size(), expected[level - 1]) << "seed" << level;
    EXPECT_EQ(q.looseTriangles(), 0u) << "seed" << level;
  }
}

TEST(SeedScenes, ThreeCellsTwoPortalsEveryTriangleInOneCell) {
  for (int level = 1; level <= 3; ++level) {
    const SeedScene s = makeSeedScene(level);
    ASSERT_EQ(s.cells.cells.size(), 3u);
    ASSERT_EQ(s.cells.portals.size(), 2u);
    const CellValidation v = validateCells(s.scene, s.cells);
    EXPECT_TRUE(v.errors.empty()) << v.errors.front();
    EXPECT_TRUE(v.warnings.empty()) << v.warnings.front();
    for (int c : s.cells.cellOfTriangle(s.scene.triangles.size())) EXPECT_GE(c, 0);
  }
}

TEST(SeedScenes, PortalsAreTheDoorOpeningsAtTheWallMidPlane) {
  const SeedScene s = makeSeedScene(1);
  const float mids[2] = {4.1f, 8.3f};
  for (int i = 0; i < 2; ++i) {
    const PortalQuad& p = s.cells.portals[i];
    EXPECT_EQ(p.cellA, i);
    EXPECT_EQ(p.cellB, i + 1);
    EXPECT_NEAR(p.area, 1.0f * 2.1f, 1e-5f);
    EXPECT_NEAR(p.normal.x, 1.0f, 1e-6f);  // from the lower room into the next
    EXPECT_NEAR(p.centre().x, mids[i], 1e-5f);
    EXPECT_NEAR(p.centre().y, 1.05f, 1e-5f);
    EXPECT_NEAR(p.centre().z, 2.0f, 1e-5f);
  }
}

TEST(SeedScenes, TwoLightsOfOneSquareMetreAtEmission100) {
  for (int level = 1; level <= 3; ++level) {
    const SeedScene s = makeSeedScene(level);
    const glm::vec3 power = s.scene.emittedPower();
    EXPECT_NEAR(power.r, 200.0f, 1e-3f);
    EXPECT_NEAR(power.g, 200.0f, 1e-3f);
    // The lights face down into rooms A and C, 1 cm under the ceiling.
    size_t emissive = 0;
    for (const Triangle& t : s.scene.triangles) {
      if (!s.scene.materials[t.material].isEmitter()) continue;
      ++emissive;
      EXPECT_NEAR(t.geometricNormal().y, -1.0f, 1e-6f);
      EXPECT_NEAR(t.p[0].y, 2.99f, 1e-6f);
    }
    EXPECT_EQ(emissive, 4u);
  }
}

// The interior surface (lights aside) must be closed so light cannot leak: the area-weighted normals of
// a closed surface sum to zero, whatever its subdivision. Occluders stand on the floor with no bottom
// face, so theirs sum to their footprint facing up.
TEST(SeedScenes, InteriorSurfaceIsClosed) {
  for (int level = 1; level <= 3; ++level) {
    const SeedScene s = makeSeedScene(level);
    glm::dvec3 rooms(0.0), occluders(0.0);
    double area = 0.0;
    for (const Triangle& t : s.scene.triangles) {
      const Material& m = s.scene.materials[t.material];
      if (m.isEmitter()) continue;
      (m.name == "occluder" ? occluders : rooms) += glm::dvec3(t.geometricNormal()) * double(t.area());
      area += t.area();
    }
    EXPECT_LT(glm::length(rooms), 1e-5 * area) << "seed" << level;
    const double footprint = level >= 2 ? 3 * (1.0 + 2.0 * 0.05) : 0.0;
    EXPECT_NEAR(occluders.y, footprint, 1e-4) << "seed" << level;
  }
}

TEST(SeedScenes, RoomsAndWallsHaveTheDesignDimensions) {
  const SeedScene s = makeSeedScene(1);
  const Bounds b = s.scene.bounds();
  EXPECT_NEAR(b.lo.x, 0.0f, 1e-6f);
  EXPECT_NEAR(b.hi.x, 3 * 4.0f + 2 * 0.2f, 1e-5f);
  EXPECT_NEAR(b.hi.y, 3.0f, 1e-6f);
  EXPECT_NEAR(b.hi.z, 4.0f, 1e-6f);
  // Floor area: three 4 m × 4 m rooms plus two 1.0 m × 0.2 m thresholds.
  double floor = 0.0;
  for (const Triangle& t : s.scene.triangles)
    if (s.scene.materials[t.material].name == "floor") floor += t.area();
  EXPECT_NEAR(floor, 3 * 16.0 + 2 * 0.2, 1e-4);
  EXPECT_EQ(s.scene.cameras.size(), 3u);
}

// A camera inside an occluder sees only back faces: from every camera, the first surface hit along each
// axis direction must face the camera.
TEST(SeedScenes, CamerasStandInEmptySpace) {
  const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int level = 1; level <= 3; ++level) {
    const SeedScene s = makeSeedScene(level);
    for (const Camera& cam : s.scene.cameras) {
      for (const glm::vec3& d : dirs) {
        float nearest = 1e9f;
        glm::vec3 normal(0.0f);
        for (const Triangle& t : s.scene.triangles) {  // Möller–Trumbore
          const glm::vec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
          const glm::vec3 pv = glm::cross(d, e2);
          const float det = glm::dot(e1, pv);
          if (std::abs(det) < 1e-12f) continue;
          const glm::vec3 tv = cam.position - t.p[0];
          const float u = glm::dot(tv, pv) / det;
          const glm::vec3 qv = glm::cross(tv, e1);
          const float v = glm::dot(d, qv) / det, dist = glm::dot(e2, qv) / det;
          if (u < 0 || v < 0 || u + v > 1 || dist <= 0 || dist >= nearest) continue;
          nearest = dist;
          normal = t.geometricNormal();
        }
        EXPECT_LT(nearest, 1e8f) << "seed" << level << " camera " << cam.name << " sees out of the scene";
        EXPECT_LT(glm::dot(normal, d), 0.0f)
            << "seed" << level << " camera " << cam.name << " is inside something";
      }
    }
  }
}

TEST(SeedScenes, RejectsUnknownLevels) {
  EXPECT_THROW(makeSeedScene(0), std::invalid_argument);
  EXPECT_THROW(makeSeedScene(4), std::invalid_argument);
}

}  // namespace
}  // namespace cpgi
