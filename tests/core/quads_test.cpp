// findQuads: rectangles made of two triangles are recognised, anything else stays loose.
#include <gtest/gtest.h>

#include "core/quads.h"

namespace cpgi {
namespace {

Triangle tri(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material = 0) {
  Triangle t;
  t.p = {a, b, c};
  t.n = {t.geometricNormal(), t.geometricNormal(), t.geometricNormal()};
  t.material = material;
  return t;
}

Scene sceneOf(std::vector<Triangle> triangles) {
  Scene s;
  s.materials = {Material{}, Material{}};
  s.nodePaths = {"n"};
  s.triangles = std::move(triangles);
  return s;
}

TEST(Quads, UnitSquareSplitEitherDiagonal) {
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
  for (const Scene& s : {sceneOf({tri(a, b, c), tri(a, c, d)}), sceneOf({tri(a, b, d), tri(b, c, d)})}) {
    const QuadSet q = findQuads(s);
    ASSERT_EQ(q.quads.size(), 1u);
    EXPECT_EQ(q.looseTriangles(), 0u);
    EXPECT_NEAR(q.quads[0].area(), 1.0f, 1e-6f);
    EXPECT_NEAR(q.quads[0].normal.z, 1.0f, 1e-6f);
    const Quad& quad = q.quads[0];
    EXPECT_GT(glm::dot(glm::cross(quad.corners[1] - quad.corners[0], quad.corners[3] - quad.corners[0]),
                       quad.normal),
              0.0f);
  }
}

TEST(Quads, NonRectanglesAndMismatchesStayLoose) {
  const glm::vec3 a(0, 0, 0), b(2, 0, 0), c(3, 1, 0), d(1, 1, 0);
  const Scene parallelogram = sceneOf({tri(a, b, c), tri(a, c, d)});
  EXPECT_EQ(findQuads(parallelogram).quads.size(), 0u);
  const Scene trapezoid = sceneOf({tri(a, b, {1.5f, 1, 0}), tri(a, {1.5f, 1, 0}, {0.5f, 1, 0})});
  EXPECT_EQ(findQuads(trapezoid).quads.size(), 0u);
  // A square folded along its diagonal (not coplanar) and one whose halves have different materials.
  const Scene folded =
      sceneOf({tri({0, 0, 0}, {1, 0, 0}, {1, 1, 0}), tri({0, 0, 0}, {1, 1, 0}, {0, 1, 0.5f})});
  EXPECT_EQ(findQuads(folded).quads.size(), 0u);
  const Scene twoMaterials =
      sceneOf({tri({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, 0), tri({0, 0, 0}, {1, 1, 0}, {0, 1, 0}, 1)});
  const QuadSet q = findQuads(twoMaterials);
  EXPECT_EQ(q.quads.size(), 0u);
  EXPECT_EQ(q.looseTriangles(), 2u);
}

TEST(Quads, BoxIsSixQuads) {
  const glm::vec3 size(1, 2, 3);
  std::vector<Triangle> tris;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      glm::vec3 o(0.0f), u(0.0f), v(0.0f);
      o[axis] = side ? size[axis] : 0.0f;
      u[(axis + 1) % 3] = size[(axis + 1) % 3];
      v[(axis + 2) % 3] = size[(axis + 2) % 3];
      if (!side) std::swap(u, v);  // outward normals
      tris.push_back(tri(o, o + u, o + u + v));
      tris.push_back(tri(o, o + u + v, o + v));
    }
  const QuadSet q = findQuads(sceneOf(tris));
  ASSERT_EQ(q.quads.size(), 6u);
  EXPECT_EQ(q.looseTriangles(), 0u);
  float area = 0.0f;
  for (const Quad& quad : q.quads) {
    area += quad.area();
    const glm::vec3 centre = (quad.corners[0] + quad.corners[2]) * 0.5f;
    EXPECT_GT(glm::dot(quad.normal, centre - size * 0.5f), 0.0f);
  }
  EXPECT_NEAR(area, 2.0f * (1 * 2 + 2 * 3 + 3 * 1), 1e-4f);
}

}  // namespace
}  // namespace cpgi
