#include "decomposition/outside_portals.h"

#include <utility>

namespace cpgi::decomp {

int orientOutsidePortals(const Scene& scene, CellGraph& graph) {
  const int outside = graph.findCell("outside");
  if (outside < 0) return 0;
  int turned = 0;
  for (PortalQuad& q : graph.portals) {
    if ((q.cellA == outside) == (q.cellB == outside) || q.cellA < 0 || q.cellB < 0) continue;
    const int room = q.cellA == outside ? q.cellB : q.cellA;
    double side = 0.0;
    for (uint32_t t : graph.cells[size_t(room)].triangles) {
      if (t >= scene.triangles.size()) continue;
      const Triangle& tri = scene.triangles[t];
      side += double(tri.area()) * double(glm::dot(tri.centroid() - q.centre(), q.normal));
    }
    // The room lies behind the normal when it is cell A, in front when it is cell B.
    if (side == 0.0 || (side < 0.0) == (room == q.cellA)) continue;
    std::swap(q.corners[1], q.corners[3]);
    computePortalFrame(q);
    ++turned;
  }
  return turned;
}

}  // namespace cpgi::decomp
