// Glass is closed for the decomposition (issue 12 item 1): every triangle is solid to the voxelizer,
// whatever its material, so a glazed window is a wall between its room and the outside, not a portal,
// while the same opening without its pane is one.
#include <gtest/gtest.h>

#include "decomposition/decompose.h"
#include "scenes/buildings.h"

namespace cpgi::decomp {
namespace {

// A two-sided pane of `material` across the opening at its mid-plane.
void glaze(Scene& scene, const BuildingOpening& o, uint32_t material) {
  const int a = o.axis, a1 = (a + 1) % 3, a2 = (a + 2) % 3;
  const float mid = 0.5f * (o.box.lo[a] + o.box.hi[a]);
  glm::vec3 c[4];
  const float u[4] = {o.box.lo[a1], o.box.hi[a1], o.box.hi[a1], o.box.lo[a1]};
  const float v[4] = {o.box.lo[a2], o.box.lo[a2], o.box.hi[a2], o.box.hi[a2]};
  for (int k = 0; k < 4; ++k) c[k][a] = mid, c[k][a1] = u[k], c[k][a2] = v[k];
  const int quads[2][4] = {{0, 1, 2, 3}, {0, 3, 2, 1}};
  for (const auto& q : quads)
    for (const auto& tri : {std::array{q[0], q[1], q[2]}, std::array{q[0], q[2], q[3]}}) {
      Triangle t;
      t.p = {c[tri[0]], c[tri[1]], c[tri[2]]};
      const glm::vec3 n = t.geometricNormal();
      t.n = {n, n, n};
      t.material = material;
      scene.triangles.push_back(t);
    }
}

size_t portalsToOutside(const Decomposition& d) {
  size_t n = 0;
  for (const PortalQuad& q : d.graph.portals) n += q.cellA == d.outsideCell || q.cellB == d.outsideCell;
  return n;
}

TEST(Glazing, AGlazedWindowIsNoPortal) {
  Building b = makeOpenHouse();
  size_t exterior = 0;
  for (const BuildingOpening& o : b.openings) exterior += o.exterior();
  Scene& scene = b.seed.scene;
  scene.materials.push_back(Material{"glass", glm::vec3(0.05f), glm::vec3(0.0f)});
  const uint32_t glass = uint32_t(scene.materials.size() - 1);
  int glazed = 0;
  for (const BuildingOpening& o : b.openings)
    if (o.name.rfind("window-", 0) == 0) glaze(scene, o, glass), ++glazed;
  ASSERT_GT(glazed, 0);
  DecomposeParams p;
  p.voxelSize = 0.1;
  p.sourceName = "glazed house";
  Context ctx;
  const Decomposition d = decompose(scene, p, ctx);
  ASSERT_GE(d.outsideCell, 0);  // the doors still stand open
  EXPECT_EQ(portalsToOutside(d), exterior - size_t(glazed));
  EXPECT_EQ(d.leakingFaces, 0u);
}

}  // namespace
}  // namespace cpgi::decomp
