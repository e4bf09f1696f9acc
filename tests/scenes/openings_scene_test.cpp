#include "scenes/openings_scene.h"

#include <gtest/gtest.h>

#include "scenes/stability_scenes.h"

namespace cpgi {
namespace {

using L = OpeningsLayout;

TEST(OpeningsScene, ThreeCellsThreePortalsEveryTriangleInOneCell) {
  const SeedScene s = makeOpeningsScene();
  ASSERT_EQ(s.cells.cells.size(), 3u);
  ASSERT_EQ(s.cells.portals.size(), 3u);
  const CellValidation v = validateCells(s.scene, s.cells);
  EXPECT_TRUE(v.errors.empty()) << v.errors.front();
  EXPECT_TRUE(v.warnings.empty()) << v.warnings.front();
  const std::vector<int> cell = s.cells.cellOfTriangle(s.scene.triangles.size());
  for (int c : cell) EXPECT_GE(c, 0);
}

TEST(OpeningsScene, OpeningsOfSeveralWidthsAndAWindowAtTheWallMidPlanes) {
  const SeedScene s = makeOpeningsScene();
  const PortalQuad &wide = s.cells.portals[0], &window = s.cells.portals[1], &narrow = s.cells.portals[2];
  EXPECT_NEAR(wide.area, (L::kWideDoorZ1 - L::kWideDoorZ0) * L::kDoorTop, 1e-4f);
  EXPECT_NEAR(window.area, (L::kWindowZ1 - L::kWindowZ0) * (L::kWindowY1 - L::kWindowY0), 1e-4f);
  EXPECT_NEAR(narrow.area, (L::kNarrowDoorZ1 - L::kNarrowDoorZ0) * L::kDoorTop, 1e-4f);
  for (const glm::vec3& q : window.corners) EXPECT_GE(q.y, L::kWindowY0 - 1e-6f);  // a window, not a door
  // A|B is thick (portals at its mid-plane), B|C has no thickness (portal on the shared face).
  EXPECT_NEAR(wide.centre().x, L::kRoom + 0.5f * L::kThickWall, 1e-5f);
  EXPECT_NEAR(narrow.centre().x, 2 * L::kRoom + L::kThickWall, 1e-5f);
  for (const PortalQuad* p : {&wide, &window, &narrow}) EXPECT_NEAR(p->normal.x, 1.0f, 1e-5f);
  EXPECT_EQ(s.cells.cells[narrow.cellB].name, "C");
}

TEST(OpeningsScene, OneLampInAAndAClosedInterior) {
  const SeedScene s = makeOpeningsScene();
  const std::vector<int> cell = s.cells.cellOfTriangle(s.scene.triangles.size());
  glm::dvec3 normals(0.0);
  double area = 0.0, lamp = 0.0;
  for (size_t t = 0; t < s.scene.triangles.size(); ++t) {
    const Triangle& tri = s.scene.triangles[t];
    if (s.scene.materials[tri.material].isEmitter()) {
      EXPECT_EQ(s.cells.cells[cell[t]].name, "A");
      lamp += tri.area();
      continue;
    }
    normals += glm::dvec3(tri.geometricNormal()) * double(tri.area());
    area += tri.area();
  }
  EXPECT_NEAR(lamp, L::kLampSize * L::kLampSize, 1e-4);
  EXPECT_LT(glm::length(normals), 1e-5 * area);
}

TEST(OpeningsScene, IsABuiltinScene) {
  EXPECT_EQ(makeBuiltinScene("openings").scene.triangles.size(), makeOpeningsScene().scene.triangles.size());
}

}  // namespace
}  // namespace cpgi
