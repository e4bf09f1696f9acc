// RayScene: the Embree visibility shared by the reference path tracer, the view renderer and cell
// selection.
#include "radiosity/lightmap/ray_scene.h"

#include <gtest/gtest.h>

#include "tests/radiosity/test_scenes.h"

namespace cpgi {
namespace {

using testing::addMaterial;
using testing::addRect;

// A zero-thickness wall at x = 1 given as two coincident quads facing opposite ways, as modellers and
// the openings scene build partitions. A ray from either side must hit the face that faces it: the
// reference tracer ends a path on a back face, and with Embree's arbitrary pick between the two it left
// the room behind such a wall 17 % too dark (issue 11).
TEST(RayScene, CoincidentFacesShowTheOneFacingTheRay) {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.5f));
  addRect(s, {1, -2, -2}, {0, 4, 0}, {0, 0, 4}, grey);  // normal +x: triangles 0, 1
  addRect(s, {1, -2, -2}, {0, 0, 4}, {0, 4, 0}, grey);  // normal -x: triangles 2, 3
  const RayScene rays(s);
  int wrong = 0, rayCount = 0;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const glm::vec3 target(1.0f, -1.5f + 3.0f * i / 39.0f, -1.5f + 3.0f * j / 39.0f);
      for (float side : {-1.0f, 1.0f}) {
        const glm::vec3 origin(1.0f + side * 0.7f, 0.1f * side, -0.2f);
        const glm::vec3 dir = glm::normalize(target - origin);
        const RayScene::Hit hit = rays.intersect(origin, dir);
        ASSERT_TRUE(hit);
        ++rayCount;
        const glm::vec3 n = s.triangles[size_t(hit.triangle)].geometricNormal();
        if (glm::dot(n, dir) > 0.0f) ++wrong;
      }
    }
  EXPECT_EQ(wrong, 0) << "of " << rayCount << " rays";
}

// A true back face, with a front face 1 mm behind it, is still what the ray hits.
TEST(RayScene, ABackFaceWithAFrontFaceBehindIsStillHit) {
  Scene s;
  const uint32_t grey = addMaterial(s, glm::vec3(0.5f));
  addRect(s, {1, -2, -2}, {0, 4, 0}, {0, 0, 4}, grey);       // x = 1, normal +x: triangles 0, 1
  addRect(s, {1.001f, -2, -2}, {0, 0, 4}, {0, 4, 0}, grey);  // x = 1.001, normal -x: triangles 2, 3
  const RayScene rays(s);
  const RayScene::Hit hit = rays.intersect({0, 0.3f, 0.2f}, {1, 0, 0});
  ASSERT_TRUE(hit);
  EXPECT_LE(hit.triangle, 1);
  EXPECT_NEAR(hit.t, 1.0f, 1e-5f);
}

}  // namespace
}  // namespace cpgi
