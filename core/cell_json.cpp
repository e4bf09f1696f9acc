#include "core/cell_json.h"

#include <algorithm>

namespace cpgi {

nlohmann::json toJson(const glm::vec3& v) {
  return nlohmann::json::array({v.x, v.y, v.z});
}

nlohmann::json cellGraphToJson(const Scene& scene, const CellGraph& graph) {
  using nlohmann::json;
  json cells = json::array();
  for (const Cell& cell : graph.cells) {
    Bounds b;
    double area = 0.0;
    for (uint32_t t : cell.triangles) {
      if (t >= scene.triangles.size()) continue;
      area += scene.triangles[t].area();
      for (const glm::vec3& q : scene.triangles[t].p) b.extend(q);
    }
    json bounds = b.empty() ? json(nullptr) : json{{"min", toJson(b.lo)}, {"max", toJson(b.hi)}};
    cells.push_back({{"name", cell.name},
                     {"triangles", cell.triangles.size()},
                     {"area_m2", area},
                     {"bounds", bounds},
                     {"volume_triangles", cell.volume.size()}});
  }
  auto cellName = [&](int c) {
    return c >= 0 && c < static_cast<int>(graph.cells.size()) ? json(graph.cells[c].name) : json(nullptr);
  };
  json portals = json::array();
  for (const PortalQuad& p : graph.portals) {
    json corners = json::array();
    for (const glm::vec3& q : p.corners) corners.push_back(toJson(q));
    portals.push_back({{"name", p.name},
                       {"cells", {cellName(p.cellA), cellName(p.cellB)}},
                       {"corners", corners},
                       {"centre", toJson(p.centre())},
                       {"normal", toJson(p.normal)},
                       {"area_m2", p.area}});
  }
  json adjacency = json::object();
  for (size_t c = 0; c < graph.cells.size(); ++c) {
    std::vector<std::string> neighbours;
    for (int pi : graph.portalsOf(static_cast<int>(c))) {
      const PortalQuad& p = graph.portals[pi];
      const int other = p.cellA == static_cast<int>(c) ? p.cellB : p.cellA;
      if (other >= 0 && other < static_cast<int>(graph.cells.size()))
        neighbours.push_back(graph.cells[other].name);
    }
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    adjacency[graph.cells[c].name] = neighbours;
  }
  const std::vector<int> owner = graph.cellOfTriangle(scene.triangles.size());
  const size_t uncelled = graph.cells.empty()
                              ? scene.triangles.size()
                              : static_cast<size_t>(std::count(owner.begin(), owner.end(), -1));
  return {{"cells", cells},
          {"portals", portals},
          {"adjacency", adjacency},
          {"connected", graph.connected()},
          {"uncelled_triangles", uncelled}};
}

}  // namespace cpgi
